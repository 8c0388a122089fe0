// A field's values at fixed points as weighted sums of its dofs. Function::eval pulls every
// point back to its cell and tabulates the basis there on each call; the transfers between
// a cell's own mesh and the shared mesh (compat/Resample.h) evaluate fields at the same
// points every step until the next remesh, so the weights are computed once.
#pragma once
#include "compat/Dolfinx.h"
#include <cstdint>
#include <span>
#include <vector>

namespace cellphase::compat
{
class PointWeights
{
public:
  /// Whether V's fields can be evaluated this way: affine cells, a Lagrange-type element
  /// (point evaluations, identity map) without dof transformations (P1, P2; blocked or not).
  static bool applicable(const Space& V);

  /// The weights of V's dofs at the points (N rows of 3) in the given local cells of V's
  /// mesh (-1: no cell, the point is skipped).
  PointWeights(const Space& V, std::span<const double> points, std::span<const std::int32_t> cells);

  /// values (N rows of the block size) <- u at the points; rows of points without a cell
  /// are left as they are. u lives in the space the weights were made for.
  void eval(const Function& u, std::span<double> values) const;

  /// Whether u lives in the space the weights were made for.
  bool fits(const Function& u) const { return u.function_space().get() == space_; }

private:
  const Space* space_;
  int bs_ = 1;               ///< block size: components per node
  std::size_t per_cell_ = 0; ///< scalar basis functions per cell
  std::vector<std::int32_t> cells_;
  std::vector<std::int32_t> dofs_; ///< N rows of per_cell_ (block) dofs
  std::vector<double> weights_;    ///< N rows of per_cell_ basis values
};
} // namespace cellphase::compat
