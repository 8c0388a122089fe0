#include "io/FieldSnapshot.h"
#include "mesh/PointLookup.h"
#include <algorithm>
#include <cmath>

namespace cellphase
{
std::vector<double> gather_to_root(MPI_Comm comm, const std::vector<double>& local)
{
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int n = int(local.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(rank == 0 ? offsets[size] : 0);
  MPI_Gatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
              MPI_DOUBLE, 0, comm);
  return all;
}

void save_field(const Function& u, const std::string& key, CheckpointData& data)
{
  const auto& V = *u.function_space();
  const int bs = V.dofmap()->index_map_bs();
  const std::int32_t owned = V.dofmap()->index_map->size_local();
  const std::vector<double> x = V.tabulate_dof_coordinates(false);
  std::vector<double> points(x.begin(), x.begin() + 3 * owned);
  auto values = u.x()->array();
  std::vector<double> own(values.begin(), values.begin() + std::size_t(owned) * bs);

  MPI_Comm comm = V.mesh()->comm();
  auto all_points = gather_to_root(comm, points);
  auto all_values = gather_to_root(comm, own);
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0)
    return;
  data.arrays[key + ".x"] = std::move(all_points);
  data.arrays[key + ".values"] = std::move(all_values);
  data.set(key + ".block_size", bs);
}

void restore_field(const CheckpointData& data, const std::string& key, Function& u)
{
  const auto& V = *u.function_space();
  const int bs = V.dofmap()->index_map_bs();
  if (int(data.scalar(key + ".block_size")) != bs)
    throw CheckpointError("field '" + key + "' has block size "
                          + std::to_string(int(data.scalar(key + ".block_size")))
                          + " in the checkpoint, " + std::to_string(bs) + " in the run");
  const auto& points = data.array(key + ".x");
  const auto& values = data.array(key + ".values");
  if (values.size() != points.size() / 3 * bs)
    throw CheckpointError("field '" + key + "': number of values and of nodes differ");

  // Tolerance: far above round-off in coordinates (1e-16 of the extent) and far below the
  // distance of two nodes even at the 20 refinement levels a scene may ask for (> 1e-8).
  double lo = 1e300, hi = -1e300;
  for (double c : points)
    lo = std::min(lo, c), hi = std::max(hi, c);
  PointLookup stored(points, 1e-11 * std::max(hi - lo, 1e-300));
  const std::vector<double> x = V.tabulate_dof_coordinates(false);
  auto out = u.x()->mutable_array();
  for (std::size_t i = 0; i < x.size() / 3; ++i)
  {
    const std::int64_t j = stored.find(&x[3 * i]);
    if (j < 0)
      throw CheckpointError("field '" + key + "': the node at (" + std::to_string(x[3 * i])
                            + ", " + std::to_string(x[3 * i + 1]) + ", "
                            + std::to_string(x[3 * i + 2])
                            + ") is not in the checkpoint: the mesh differs");
    for (int k = 0; k < bs; ++k)
      out[i * bs + k] = values[j * bs + k];
  }
}
} // namespace cellphase
