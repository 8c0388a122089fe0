// Point location in the local cells of a mesh (internal to compat/): bounding-box trees
// are built once per mesh, so that a field evaluated again and again at other meshes'
// nodes (transfers between meshes refined from the same base mesh) pays for them once.
#pragma once
#include "compat/CellContains.h"
#include "compat/Dolfinx.h"
#include "compat/PeriodicImages.h"
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <dolfinx/geometry/utils.h>
#include <algorithm>
#include <array>
#include <numeric>

namespace cellphase::compat::detail
{
inline std::vector<std::int32_t> all_local_cells(const Mesh& m)
{
  auto map = m.topology().index_map(m.topology().dim());
  std::vector<std::int32_t> cells(map->size_local() + map->num_ghosts());
  std::iota(cells.begin(), cells.end(), 0);
  return cells;
}

/// Holds no reference to the mesh: its user keeps the mesh alive (a function on it), and
/// a cache of locators may outlive meshes without keeping them.
class PointLocator
{
public:
  explicit PointLocator(std::shared_ptr<const Mesh> m)
      : mesh_(m.get()), cells_(all_local_cells(*m)),
        tree_(*m, m->topology().dim(), cells_, 1e-10)
  {
    // The box of the local part's nodes (ghosts included), padded by round-off below.
    auto x = m->geometry().x();
    for (std::size_t i = 0; i < x.size(); i += 3)
      for (int d = 0; d < 3; ++d)
        box_[d] = std::min(box_[d], x[i + d]), box_[3 + d] = std::max(box_[3 + d], x[i + d]);
    double extent = 0;
    for (int d = 0; d < 3; ++d)
      extent = std::max(extent, box_[3 + d] - box_[d]);
    round_off_ = 1e-9 * extent;
    for (int d = 0; d < 3; ++d)
      box_[d] -= round_off_, box_[3 + d] += round_off_;
    // The whole mesh's box (collective), into which points of a periodic domain are moved.
    if (any_periodic())
    {
      mesh_box_ = box_;
      for (int d = 0; d < 3; ++d)
        mesh_box_[3 + d] = -mesh_box_[3 + d]; // one MIN reduction for both ends
      MPI_Allreduce(MPI_IN_PLACE, mesh_box_.data(), 6, MPI_DOUBLE, MPI_MIN, m->comm());
      for (int d = 0; d < 3; ++d)
        mesh_box_[3 + d] = -mesh_box_[3 + d];
    }
  }

  /// Points moved to their periodic images in this mesh, where they lie outside it along
  /// a periodic axis (compat/PeriodicImages.h); unchanged without periodic axes.
  void move_into_mesh(std::span<double> pts) const
  {
    if (any_periodic())
      move_into(pts, mesh_box_);
  }

  /// The local cell holding each point (N x 3). Points missed by round-off on cell
  /// boundaries take the closest cell; with `outside_is_missing`, points farther than
  /// round-off from every local cell get -1 (they lie outside this mesh's part).
  std::vector<std::int32_t> locate(std::span<const double> pts, bool outside_is_missing = false) const
  {
    const std::size_t n = pts.size() / 3;
    std::vector<std::int32_t> cells(n, -1);
    if (cells_.empty())
      return cells;
    auto candidates = dolfinx::geometry::compute_collisions(tree_, pts);
    const CellContains contains(*mesh_);
    std::vector<std::size_t> missed;
    for (std::size_t i = 0; i < n; ++i)
    {
      cells[i] = contains.first(candidates.links(i), pts.data() + 3 * i);
      if (cells[i] < 0)
        missed.push_back(i);
    }
    if (missed.empty())
      return cells;
    if (!midpoint_tree_)
      midpoint_tree_ = std::make_unique<dolfinx::geometry::BoundingBoxTree>(
          dolfinx::geometry::create_midpoint_tree(*mesh_, mesh_->topology().dim(), cells_));
    std::vector<double> mp;
    for (auto i : missed)
      mp.insert(mp.end(), pts.begin() + 3 * i, pts.begin() + 3 * i + 3);
    auto closest = dolfinx::geometry::compute_closest_entity(tree_, *midpoint_tree_, *mesh_, mp);
    std::vector<double> d2;
    if (outside_is_missing)
      d2 = dolfinx::geometry::squared_distance(*mesh_, mesh_->topology().dim(), closest, mp);
    for (std::size_t j = 0; j < missed.size(); ++j)
      if (!outside_is_missing || d2[j] <= round_off_ * round_off_)
        cells[missed[j]] = closest[j];
    return cells;
  }

  /// Distance within which a point counts as in a cell (1e-9 of the part's extent).
  double round_off() const { return round_off_; }

  /// Bounding box of the local part (lo x, y, z, hi x, y, z), padded by round_off();
  /// empty (lo > hi) on a rank without nodes.
  const std::array<double, 6>& box() const { return box_; }

private:
  const Mesh* mesh_;
  std::vector<std::int32_t> cells_;
  dolfinx::geometry::BoundingBoxTree tree_;
  mutable std::unique_ptr<dolfinx::geometry::BoundingBoxTree> midpoint_tree_;
  std::array<double, 6> box_{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  std::array<double, 6> mesh_box_{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  double round_off_;
};
} // namespace cellphase::compat::detail
