// One all-to-all exchange of variable-length lists (internal to compat/).
#pragma once
#include <dolfinx/common/MPI.h>
#include <vector>

namespace cellphase::compat::detail
{
/// Collective: send[r] goes to rank r (send has one list per rank); returns what each
/// rank sent here.
template <typename T>
std::vector<std::vector<T>> all_to_all(MPI_Comm comm, const std::vector<std::vector<T>>& send)
{
  const int size = int(send.size());
  std::vector<int> send_count(size), recv_count(size), send_offset(size + 1, 0),
      recv_offset(size + 1, 0);
  for (int r = 0; r < size; ++r)
    send_count[r] = int(send[r].size());
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r)
  {
    send_offset[r + 1] = send_offset[r] + send_count[r];
    recv_offset[r + 1] = recv_offset[r] + recv_count[r];
  }
  std::vector<T> out(send_offset[size]), in(recv_offset[size]);
  for (int r = 0; r < size; ++r)
    std::copy(send[r].begin(), send[r].end(), out.begin() + send_offset[r]);
  const auto type = dolfinx::MPI::mpi_type<T>();
  MPI_Alltoallv(out.data(), send_count.data(), send_offset.data(), type, in.data(),
                recv_count.data(), recv_offset.data(), type, comm);
  std::vector<std::vector<T>> received(size);
  for (int r = 0; r < size; ++r)
    received[r].assign(in.begin() + recv_offset[r], in.begin() + recv_offset[r + 1]);
  return received;
}
} // namespace cellphase::compat::detail
