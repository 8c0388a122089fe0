// Fields that live on different meshes refined from the same base mesh (a cell's own
// patch and the flow's mesh, section 7.2): evaluation with a value outside the mesh a
// field lives on, and repeated transfers whose points are located once. Rank-local like
// compat::transfer (children stay on their base cell's rank, compat/Patch.h) except at a
// patch's edge, where a point may be held by another rank (compat/RemotePoints.h).
#pragma once
#include "compat/Dolfinx.h"
#include "compat/PeriodicImages.h"
#include <dolfinx/la/Vector.h>
#include <array>
#include <memory>

namespace cellphase::compat
{
namespace detail
{
class RemotePoints;
}
class PointWeights;

/// Point evaluator of u; points outside u's mesh (beyond round-off) get `outside` (a field
/// that is constant there, phi = -1 outside a cell's patch). A point outside the local part
/// but inside another rank's takes its value there. Collective on u's mesh.
PointEvaluator make_evaluator(std::shared_ptr<const Function> u, double outside);

/// to <- from at the interpolation points of the given local cells of to's mesh (none on
/// a rank whose list is empty; local_cells() for all), repeatedly: the points are located
/// in from's mesh once, at construction. Points outside from's mesh take `outside`; points
/// outside its local part but in another rank's take the value there. Scalar or vector
/// fields. Constructing and applying are collective on from's mesh.
class Resampler
{
public:
  Resampler(std::shared_ptr<const Function> from, std::shared_ptr<Function> to,
            std::vector<std::int32_t> cells, double outside);
  void apply();
  /// The same points for another pair of fields on the same meshes and spaces.
  void apply(const Function& from, Function& to, double outside) const;
  /// The owned cells of to's mesh whose values apply() can change: its cells and those
  /// that share a dof with them (on any rank). Elsewhere `to` keeps what it held before.
  std::vector<std::int32_t> support() const;

private:
  void share_writes(Function& to) const;

  std::shared_ptr<const Function> from_;
  std::shared_ptr<Function> to_;
  std::vector<std::int32_t> cells_, from_cells_;
  std::vector<double> points_;
  double outside_;
  int value_size_;
  std::shared_ptr<const detail::RemotePoints> remote_; ///< several ranks: points held elsewhere
  std::shared_ptr<const PointWeights> weights_; ///< from's basis at the points (if applicable)
  std::vector<char> written_here_, written_anywhere_;  ///< per dof (block) of to's space
  std::shared_ptr<dolfinx::la::Vector<T>> writes_, writers_; ///< several ranks: exchange
};

/// All local cells of `mesh`.
std::vector<std::int32_t> local_cells(const Mesh& mesh);

/// Local cells of `mesh` whose midpoint lies in a local cell of `patch`.
std::vector<std::int32_t> cells_inside(const Mesh& mesh, std::shared_ptr<const Mesh> patch);
} // namespace cellphase::compat
