#include "compat/RemotePoints.h"
#include "compat/AllToAll.h"

namespace cellphase::compat::detail
{
RemotePoints::RemotePoints(std::shared_ptr<const Mesh> mesh, const PointLocator& locator,
                           std::span<const double> pts, std::span<const std::int32_t> cells)
    : comm_(mesh->comm()), mesh_(mesh)
{
  int size = 1, rank = 0;
  MPI_Comm_size(comm_, &size);
  MPI_Comm_rank(comm_, &rank);
  const std::size_t n = pts.size() / 3;
  source_.assign(n, -1);
  asked_.resize(size);
  served_points_.resize(size);
  served_cells_.resize(size);

  // Every rank's box of its part of the mesh, padded by the locator's round-off.
  const std::array<double, 6>& box = locator.box();
  std::vector<double> boxes(6 * size);
  MPI_Allgather(box.data(), 6, MPI_DOUBLE, boxes.data(), 6, MPI_DOUBLE, comm_);

  // Ask the ranks whose box holds a point that this rank misses.
  std::vector<std::vector<double>> ask(size);
  std::vector<std::vector<std::int32_t>> asked(size);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (cells[i] >= 0)
      continue;
    for (int s = 0; s < size; ++s)
    {
      const double* b = &boxes[6 * s];
      bool in = s != rank;
      for (int d = 0; d < 3 && in; ++d)
        in = pts[3 * i + d] >= b[d] && pts[3 * i + d] <= b[3 + d];
      if (in)
      {
        ask[s].insert(ask[s].end(), pts.begin() + 3 * i, pts.begin() + 3 * i + 3);
        asked[s].push_back(std::int32_t(i));
      }
    }
  }
  const auto requests = all_to_all(comm_, ask);

  // Answer: which of the requested points this rank holds (to within round-off).
  std::vector<std::vector<std::int32_t>> held(size);
  for (int r = 0; r < size; ++r)
  {
    const auto found = locator.locate(requests[r], true);
    for (std::size_t k = 0; k < found.size(); ++k)
    {
      held[r].push_back(found[k] >= 0 ? 1 : 0);
      if (found[k] >= 0)
      {
        served_points_[r].insert(served_points_[r].end(), requests[r].begin() + 3 * k,
                                 requests[r].begin() + 3 * k + 3);
        served_cells_[r].push_back(found[k]);
      }
    }
  }
  const auto answers = all_to_all(comm_, held);
  for (int s = 0; s < size; ++s)
    for (std::size_t k = 0; k < answers[s].size(); ++k)
      if (answers[s][k])
      {
        const std::int32_t i = asked[s][k];
        asked_[s].push_back(i);
        if (source_[i] < 0) // ranks in increasing order: the lowest holder wins
          source_[i] = s;
      }
}

void RemotePoints::fill(const Function& u, std::span<double> values) const
{
  const int size = int(asked_.size());
  const std::size_t vs = u.function_space()->element()->value_size();
  std::vector<std::vector<double>> reply(size);
  for (int r = 0; r < size; ++r)
  {
    const std::size_t m = served_cells_[r].size();
    reply[r].resize(m * vs);
    if (m > 0)
      u.eval(served_points_[r], {m, 3}, served_cells_[r], reply[r], {m, vs});
  }
  const auto got = all_to_all(comm_, reply);
  for (int s = 0; s < size; ++s)
    for (std::size_t k = 0; k < asked_[s].size(); ++k)
      if (const std::int32_t i = asked_[s][k]; source_[i] == s)
        for (std::size_t c = 0; c < vs; ++c)
          values[i * vs + c] = got[s][k * vs + c];
}
} // namespace cellphase::compat::detail
