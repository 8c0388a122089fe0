// Points that the local part of a mesh misses but another rank's part holds (internal to
// compat/). Transfers between meshes cut from the same base mesh are rank-local except at
// the edge of a cell's patch: a point there may lie in a base cell of this rank that the
// patch leaves out, while the patch cell beside it is on another rank. Without this, such a
// point took the value outside the patch, and two ranks differed from one.
#pragma once
#include "compat/PointLocator.h"
#include <vector>

namespace cellphase::compat::detail
{
/// Collective: every rank constructs one for the same call and evaluates it as often as
/// the others, in the same order (a rank with no points takes part too).
class RemotePoints
{
public:
  /// `pts` (N x 3) and the local cells of `mesh` holding them (-1: not held here);
  /// `locator` is mesh's.
  RemotePoints(std::shared_ptr<const Mesh> mesh, const PointLocator& locator,
               std::span<const double> pts, std::span<const std::int32_t> cells);

  /// For every point not held here but held by another rank, u's value there (N rows of
  /// u's value size in `values`; other rows are left as they are).
  void fill(const Function& u, std::span<double> values) const;

private:
  MPI_Comm comm_;
  std::shared_ptr<const Mesh> mesh_;
  /// asked_[s]: my points that rank s holds, in the order s sends their values.
  std::vector<std::vector<std::int32_t>> asked_;
  /// For each of my points: the rank whose value it takes (the lowest that holds it), or -1.
  std::vector<int> source_;
  /// served_*[r]: the points rank r asked of me that I hold, and my cells holding them.
  std::vector<std::vector<double>> served_points_;
  std::vector<std::vector<std::int32_t>> served_cells_;
};
} // namespace cellphase::compat::detail
