#include "compat/Periodic.h"
#include "compat/PeriodicData.h"
#include "solve/Assemble.h"
// dolfinx_mpc 0.5 headers: PeriodicConstraint.h has no include guard and lifting.h defines
// non-inline functions, so both may be included by this file only. The umbrella header
// dolfinx_mpc.h is unusable (it includes <utils.h> & co. without the folder name).
#include <dolfinx_mpc/MultiPointConstraint.h>
#include <dolfinx_mpc/PeriodicConstraint.h>
#include <dolfinx_mpc/assemble_matrix.h>
#include <dolfinx_mpc/assemble_vector.h>
#include <dolfinx_mpc/lifting.h>
#include <dolfinx_mpc/utils.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <xtensor/xarray.hpp>

namespace cellphase
{
using namespace dolfinx;

namespace
{
/// The scalar pieces of a space: dolfinx_mpc 0.5 makes only scalar spaces periodic
/// ("not implemented for vector valued spaces"), so vectors go component by component.
void scalar_subspaces(std::shared_ptr<const Space> V,
                      std::vector<std::shared_ptr<const Space>>& out)
{
  const auto& e = *V->element();
  if (e.is_mixed())
    for (int i = 0; i < e.num_sub_elements(); ++i)
      scalar_subspaces(V->sub({i}), out);
  else if (e.block_size() > 1)
    for (int i = 0; i < e.block_size(); ++i)
      out.push_back(V->sub({i}));
  else
    out.push_back(V);
}
} // namespace

PeriodicConstraint::PeriodicConstraint(std::shared_ptr<const Space> V,
                                       const std::array<double, 3>& lower,
                                       const std::array<double, 3>& upper,
                                       const std::vector<int>& periodic_axes,
                                       const BCs& bcs)
    : V_(V)
{
  if (periodic_axes.empty())
    return;
  const int gdim = V->mesh()->geometry().dim();
  for (int a : periodic_axes)
    if (a < 0 || a >= gdim)
      throw std::runtime_error("periodic axis " + std::to_string(a)
                               + " outside the mesh dimension");

  double tol = 0;
  for (int a : periodic_axes)
    tol = std::max(tol, 1e-8 * (upper[a] - lower[a]));
  // Only a mesh that spans the period has dofs to tie across it. A cell's own mesh
  // inside the domain, ending on one side (the side is then a cut edge of it) or reaching
  // across it (a wrapped patch, compat/Patch.h) has none: the axis constrains nothing there.
  const auto [mesh_lower, mesh_upper] = compat::bounding_box(*V->mesh());
  std::vector<int> axes;
  for (int a : periodic_axes)
    if (mesh_lower[a] < lower[a] + tol && std::abs(mesh_upper[a] - upper[a]) < tol)
      axes.push_back(a);
  if (axes.empty())
    return;
  auto on_max = [=](const auto& x, std::size_t i)
  {
    return std::any_of(axes.begin(), axes.end(),
                       [&](int a) { return std::abs(x(a, i) - upper[a]) < tol; });
  };
  auto on_min = [=](const auto& x, std::size_t i)
  {
    return std::any_of(axes.begin(), axes.end(),
                       [&](int a) { return std::abs(x(a, i) - lower[a]) < tol; });
  };
  // Moves the coordinates on the max (min) faces to the min (max) faces. A dof on several
  // max faces (an edge, a corner) maps straight to the min corner, which is no slave.
  auto move = [=](const xt::xtensor<double, 2>& x, bool to_min)
  {
    xt::xarray<double> y = x;
    for (std::size_t i = 0; i < x.shape(1); ++i)
      for (int a : axes)
        if (std::abs(x(a, i) - (to_min ? upper[a] : lower[a])) < tol)
          y(a, i) = to_min ? lower[a] : upper[a];
    return y;
  };
  auto to_min = [=](const xt::xtensor<double, 2>& x) { return move(x, true); };
  auto to_max = [=](const xt::xtensor<double, 2>& x) { return move(x, false); };
  auto max_face = [=](const xt::xtensor<double, 2>& x)
  {
    xt::xtensor<bool, 1> marked = xt::zeros<bool>({x.shape(1)});
    for (std::size_t i = 0; i < x.shape(1); ++i)
      marked(i) = on_max(x, i);
    return marked;
  };

  std::vector<std::shared_ptr<const Space>> pieces;
  scalar_subspaces(V, pieces);
  dolfinx_mpc::mpc_data all;
  all.offsets = {0};
  for (const auto& piece : pieces)
  {
    // collapse = true for sub-spaces: dofs are located in the collapsed space and
    // returned in the numbering of the root space.
    const bool sub = piece.get() != V.get();
    // 1. Every dof on a max face is a slave of the point it maps to on the min faces.
    periodic::append(all, dolfinx_mpc::create_periodic_condition_geometrical(
                              piece, max_face, to_min, bcs, 1.0, sub));
    // 2. Where the min face is finer than the max face (local refinement), its extra dofs
    //    have no partner; left free they would see a one-sided (natural) condition. They
    //    become slaves of the max face point, i.e. (after resolve_chains) of the min-face
    //    dofs that do have partners, so both traces are the same coarse polynomial.
    const auto partners = periodic::max_face_points(piece, sub, max_face, tol);
    auto unmatched_min = [=, &partners](const xt::xtensor<double, 2>& x)
    {
      xt::xtensor<bool, 1> marked = xt::zeros<bool>({x.shape(1)});
      const auto image = to_max(x);
      for (std::size_t i = 0; i < x.shape(1); ++i)
        marked(i) = on_min(x, i) && !on_max(x, i)
                    && !partners.count(periodic::point_key(image, i, tol));
      return marked;
    };
    periodic::append(all, dolfinx_mpc::create_periodic_condition_geometrical(
                              piece, unmatched_min, to_max, bcs, 1.0, sub));
  }
  auto resolved = periodic::resolve_chains(*V, all, bcs);
  all = std::move(resolved.data);
  mpc_ = std::make_shared<dolfinx_mpc::MultiPointConstraint<T>>(V, all.slaves, all.masters,
                                                                all.coeffs, all.owners, all.offsets);
  constants_ = std::move(resolved.constants);
  int any_constants = !constants_.empty();
  MPI_Allreduce(MPI_IN_PLACE, &any_constants, 1, MPI_INT, MPI_MAX, V->mesh()->comm());
  if (any_constants)
  {
    // The constants enter the right-hand side like Dirichlet values on the slave columns
    // (lifting: b -= K^T A r), and the solution in backsubstitute. Created on all ranks:
    // a Function's vector sets up a neighbourhood communicator (collective).
    auto r = std::make_shared<Function>(V);
    r->x()->set(0.0);
    std::vector<std::int32_t> dofs;
    for (auto [slave, value] : constants_)
      r->x()->mutable_array()[slave] = value, dofs.push_back(slave);
    std::sort(dofs.begin(), dofs.end());
    constants_lift_ = std::make_shared<const DirichletBC>(
        r, std::array<std::vector<std::int32_t>, 2>{dofs, dofs}, V);
  }
  std::int64_t local = mpc_->num_local_slaves();
  MPI_Allreduce(&local, &num_slaves_, 1, MPI_INT64_T, MPI_SUM, V->mesh()->comm());
}

PeriodicConstraint::~PeriodicConstraint() = default;

la::petsc::Matrix PeriodicConstraint::create_matrix(const Form& a) const
{
  if (mpc_)
    return dolfinx_mpc::create_matrix(a, mpc_);
  return la::petsc::Matrix(fem::petsc::create_matrix(a), false);
}

void PeriodicConstraint::assemble_matrix(Mat A, const Form& a, const BCs& bcs) const
{
  // Element entries added at the positions recorded by the first assembly of a into A
  // (solve/RecordedAssembly).
  auto assemble = [&](const RecordedAssembly::AddFn& add_block, const RecordedAssembly::AddFn& add)
  {
    if (mpc_)
      // Puts 1 on the diagonal of the (owned) slave rows itself.
      dolfinx_mpc::assemble_matrix(add_block, add, a, mpc_, mpc_, bcs, 1.0);
    else
      fem::assemble_matrix(add_block, a, bcs);
  };
  auto finalise = [&] { finish_matrix(A, *V_, bcs); };
  recorded_->assemble(A, &a, assemble, finalise);
}

la::Vector<T> PeriodicConstraint::create_vector() const
{
  // The constrained space has the same owned dofs; its ghosts add the remote masters.
  auto map = mpc_ ? mpc_->function_space()->dofmap()->index_map : V_->dofmap()->index_map;
  return la::Vector<T>(map, V_->dofmap()->index_map_bs());
}

void PeriodicConstraint::assemble_vector(la::Vector<T>& b, const Form& L,
                                         std::shared_ptr<const Form> a, const BCs& bcs) const
{
  b.set(0.0);
  add_load(b, L);
  add_lifting(b, a, bcs);
  b.scatter_rev(std::plus<T>());
  fem::set_bc<T>(b.mutable_array(), bcs);
}

void PeriodicConstraint::assemble_vector(la::Vector<T>& b, const Form& L,
                                         const la::Vector<T>& lifting, const BCs& bcs) const
{
  assemble_local(b, L, &lifting);
  finish(b, bcs, 1.0);
}

void PeriodicConstraint::assemble_local(la::Vector<T>& b, const Form& L,
                                        const la::Vector<T>* lifting) const
{
  b.set(0.0);
  add_load(b, L);
  if (lifting)
    std::transform(b.array().begin(), b.array().end(), lifting->array().begin(),
                   b.mutable_array().begin(), std::plus<T>());
}

void PeriodicConstraint::finish(la::Vector<T>& b, const BCs& bcs, double bc_scale) const
{
  b.scatter_rev(std::plus<T>());
  fem::set_bc<T>(b.mutable_array(), bcs, bc_scale);
}

void PeriodicConstraint::lifting(la::Vector<T>& l, std::shared_ptr<const Form> a,
                                 const BCs& bcs) const
{
  l.set(0.0);
  add_lifting(l, a, bcs);
}

void PeriodicConstraint::add_load(la::Vector<T>& b, const Form& L) const
{
  if (mpc_)
    dolfinx_mpc::assemble_vector(b.mutable_array(), L, mpc_);
  else
    fem::assemble_vector(b.mutable_array(), L);
}

void PeriodicConstraint::add_lifting(la::Vector<T>& b, std::shared_ptr<const Form> a,
                                     const BCs& bcs) const
{
  if (mpc_)
  {
    BCs lifted = bcs;
    if (constants_lift_)
      lifted.push_back(constants_lift_);
    dolfinx_mpc::apply_lifting(b.mutable_array(), {a}, {lifted}, {}, 1.0, mpc_);
  }
  else
    fem::apply_lifting<T>(b.mutable_array(), {a}, {bcs}, {}, 1.0);
}

void PeriodicConstraint::backsubstitute(la::Vector<T>& x, bool homogeneous) const
{
  if (!mpc_)
    return;
  x.scatter_fwd(); // masters owned elsewhere are ghosts of x
  // backsubstitution adds to the slave value, so start from zero.
  mpc_->homogenize(x.mutable_array());
  mpc_->backsubstitution(x.mutable_array());
  if (!homogeneous)
    for (auto [slave, value] : constants_)
      x.mutable_array()[slave] += value;
}

void PeriodicConstraint::backsubstitute(la::Vector<T>& x, Function& u) const
{
  backsubstitute(x, false);
  // The constrained index map extends V's ghosts at the end: V's part is a prefix.
  auto out = u.x()->mutable_array();
  std::copy_n(x.array().begin(), out.size(), out.begin());
}
} // namespace cellphase
