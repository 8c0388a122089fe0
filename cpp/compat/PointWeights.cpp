#include "compat/PointWeights.h"
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/fem/FiniteElement.h>
#include <stdexcept>

namespace cellphase::compat
{
namespace
{
/// Solve J X = b for a tdim x tdim matrix J (rows of tdim), tdim = 2 or 3 (Cramer's rule).
void solve_small(int tdim, const double* J, const double* b, double* X)
{
  if (tdim == 2)
  {
    const double det = J[0] * J[3] - J[1] * J[2];
    X[0] = (J[3] * b[0] - J[1] * b[1]) / det;
    X[1] = (J[0] * b[1] - J[2] * b[0]) / det;
    return;
  }
  auto det3 = [](const double* a, const double* b, const double* c)
  { return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
           + a[2] * (b[0] * c[1] - b[1] * c[0]); };
  // Columns of J: the edges from vertex 0.
  const double c0[3] = {J[0], J[3], J[6]}, c1[3] = {J[1], J[4], J[7]}, c2[3] = {J[2], J[5], J[8]};
  const double det = det3(c0, c1, c2);
  X[0] = det3(b, c1, c2) / det;
  X[1] = det3(c0, b, c2) / det;
  X[2] = det3(c0, c1, b) / det;
}
} // namespace

bool PointWeights::applicable(const Space& V)
{
  const auto& element = *V.element();
  const auto& mesh = *V.mesh();
  return mesh.geometry().cmap().is_affine() && element.map_ident()
         && element.interpolation_ident() && !element.needs_dof_transformations()
         && mesh.geometry().dim() == mesh.topology().dim();
}

PointWeights::PointWeights(const Space& V, std::span<const double> points,
                           std::span<const std::int32_t> cells)
    : space_(&V), cells_(cells.begin(), cells.end())
{
  if (!applicable(V))
    throw std::invalid_argument("PointWeights: the space is not an affine Lagrange space");
  const auto& mesh = *V.mesh();
  const int tdim = mesh.topology().dim();
  const auto& x_dofmap = mesh.geometry().dofmap();
  std::span<const double> x_g = mesh.geometry().x();
  auto element = V.element();
  bs_ = element->block_size();
  auto scalar = bs_ > 1 ? element->extract_sub_element({0}) : element;
  per_cell_ = scalar->space_dimension();

  // Reference coordinates: x = x_0 + J X on an affine cell, J's columns the edges from x_0.
  const std::size_t n = cells_.size();
  std::vector<double> X(n * tdim, 0.0);
  for (std::size_t p = 0; p < n; ++p)
  {
    if (cells_[p] < 0)
      continue;
    auto v = x_dofmap.links(cells_[p]);
    double J[9], b[3];
    for (int i = 0; i < tdim; ++i)
    {
      for (int j = 0; j < tdim; ++j)
        J[i * tdim + j] = x_g[3 * v[j + 1] + i] - x_g[3 * v[0] + i];
      b[i] = points[3 * p + i] - x_g[3 * v[0] + i];
    }
    solve_small(tdim, J, b, &X[p * tdim]);
  }
  weights_.resize(n * per_cell_);
  scalar->tabulate(weights_, X, {n, std::size_t(tdim)}, 0); // (1, n, per_cell_, 1)

  dofs_.assign(n * per_cell_, -1);
  const auto& dofmap = *V.dofmap();
  for (std::size_t p = 0; p < n; ++p)
    if (cells_[p] >= 0)
    {
      auto d = dofmap.cell_dofs(cells_[p]);
      std::copy(d.begin(), d.end(), dofs_.begin() + p * per_cell_);
    }
}

void PointWeights::eval(const Function& u, std::span<double> values) const
{
  if (!fits(u))
    throw std::invalid_argument("PointWeights: the field is not in the weights' space");
  std::span<const T> x = u.x()->array();
  for (std::size_t p = 0; p < cells_.size(); ++p)
  {
    if (cells_[p] < 0)
      continue;
    const double* w = &weights_[p * per_cell_];
    const std::int32_t* d = &dofs_[p * per_cell_];
    for (int k = 0; k < bs_; ++k)
    {
      double sum = 0;
      for (std::size_t i = 0; i < per_cell_; ++i)
        sum += w[i] * x[bs_ * d[i] + k];
      values[p * bs_ + k] = sum;
    }
  }
}
} // namespace cellphase::compat
