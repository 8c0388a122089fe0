#include "compat/Periodic.h"
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
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <xtensor/xadapt.hpp>
#include <xtensor/xview.hpp>
#include <stdexcept>
#include <unordered_set>

namespace cellphase
{
using namespace dolfinx;

namespace
{
/// The scalar pieces of a space: dolfinx_mpc 0.5 makes only scalar spaces periodic
/// ("not implemented for vector valued spaces"), so vectors go component by component.
void scalar_subspaces(std::shared_ptr<const Space> V, std::vector<std::shared_ptr<const Space>>& out)
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

/// Appends one constraint's data to the union of all (offsets shifted past earlier masters).
void append(dolfinx_mpc::mpc_data& all, const dolfinx_mpc::mpc_data& d)
{
  const std::int32_t shift = all.masters.size();
  all.slaves.insert(all.slaves.end(), d.slaves.begin(), d.slaves.end());
  all.masters.insert(all.masters.end(), d.masters.begin(), d.masters.end());
  all.coeffs.insert(all.coeffs.end(), d.coeffs.begin(), d.coeffs.end());
  all.owners.insert(all.owners.end(), d.owners.begin(), d.owners.end());
  for (std::size_t i = 1; i < d.offsets.size(); ++i)
    all.offsets.push_back(d.offsets[i] + shift);
}
/// Global (unrolled) indices of local (unrolled) dofs of V.
std::vector<std::int64_t> to_global(const Space& V, const std::vector<std::int32_t>& local)
{
  const int bs = V.dofmap()->index_map_bs();
  std::vector<std::int32_t> blocks(local.size());
  std::vector<std::int64_t> global(local.size());
  for (std::size_t i = 0; i < local.size(); ++i)
    blocks[i] = local[i] / bs;
  V.dofmap()->index_map->local_to_global(blocks, global);
  for (std::size_t i = 0; i < local.size(); ++i)
    global[i] = global[i] * bs + local[i] % bs;
  return global;
}

template <typename U>
std::vector<U> all_gather(const std::vector<U>& mine, MPI_Comm comm)
{
  int size, count = mine.size();
  MPI_Comm_size(comm, &size);
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<U> all(offsets.back());
  MPI_Allgatherv(mine.data(), count, dolfinx::MPI::mpi_type<U>(), all.data(), counts.data(),
                 offsets.data(), dolfinx::MPI::mpi_type<U>(), comm);
  return all;
}

using PointKey = std::array<std::int64_t, 3>;
PointKey point_key(const xt::xarray<double>& x, std::size_t i, double tol)
{
  auto r = [&](int d) { return std::int64_t(std::llround(x(d, i) / tol)); };
  return {r(0), r(1), r(2)};
}

/// Positions of the dofs of a scalar (sub-)space on the max faces, from all ranks.
std::set<PointKey> max_face_points(
    std::shared_ptr<const Space> piece, bool sub,
    const std::function<xt::xtensor<bool, 1>(const xt::xtensor<double, 2>&)>& max_face, double tol)
{
  auto V = sub ? std::make_shared<const Space>(piece->collapse().first) : piece;
  const std::vector<double> X = V->tabulate_dof_coordinates(true); // 3 rows
  const std::size_t n = X.size() / 3, owned = V->dofmap()->index_map->size_local();
  xt::xarray<double> x = xt::adapt(X, std::vector<std::size_t>{3, n});
  const xt::xtensor<double, 2> x_owned = xt::view(x, xt::all(), xt::range(0, owned));
  const auto marked = max_face(x_owned);
  std::vector<std::int64_t> mine;
  for (std::size_t i = 0; i < owned; ++i)
    if (marked(i))
    {
      const auto k = point_key(x, i, tol);
      mine.insert(mine.end(), k.begin(), k.end());
    }
  const auto all = all_gather(mine, V->mesh()->comm());
  std::set<PointKey> keys;
  for (std::size_t k = 0; k < all.size(); k += 3)
    keys.insert({all[k], all[k + 1], all[k + 2]});
  return keys;
}

/// dolfinx_mpc 0.5 assumes masters are free dofs, which fails where the two faces do not
/// match (after local refinement): a slave point may fall in a cell of the min face whose
/// dofs include a slave of another axis (near an edge/corner) or a Dirichlet dof.
/// Masters that are slaves are replaced by their own masters (all ranks' slaves are
/// gathered; they live on the boundary only). A Dirichlet master would need an
/// inhomogeneous constraint, which dolfinx_mpc 0.5 lacks: that is an error.
dolfinx_mpc::mpc_data resolve_chains(const Space& V, const dolfinx_mpc::mpc_data& d,
                                     const BCs& bcs)
{
  MPI_Comm comm = V.mesh()->comm();
  const std::int32_t num_owned = V.dofmap()->index_map->size_local() * V.dofmap()->index_map_bs();
  const auto slaves_global = to_global(V, d.slaves);
  // Owned slaves of all ranks as (slave, n, masters, owners) and their coefficients.
  std::vector<std::int64_t> ints;
  std::vector<T> coeffs;
  for (std::size_t i = 0; i < d.slaves.size(); ++i)
  {
    if (d.slaves[i] >= num_owned)
      continue;
    ints.push_back(slaves_global[i]);
    ints.push_back(d.offsets[i + 1] - d.offsets[i]);
    for (auto k = d.offsets[i]; k < d.offsets[i + 1]; ++k)
      ints.insert(ints.end(), {d.masters[k], std::int64_t(d.owners[k])});
    coeffs.insert(coeffs.end(), d.coeffs.begin() + d.offsets[i], d.coeffs.begin() + d.offsets[i + 1]);
  }
  struct Term
  {
    std::int64_t master;
    T coeff;
    std::int32_t owner;
  };
  std::map<std::int64_t, std::vector<Term>> table;
  {
    const auto all_ints = all_gather(ints, comm);
    const auto all_coeffs = all_gather(coeffs, comm);
    std::size_t c = 0;
    for (std::size_t k = 0; k < all_ints.size();)
    {
      auto& terms = table[all_ints[k]];
      const std::int64_t n = all_ints[k + 1];
      k += 2;
      for (std::int64_t j = 0; j < n; ++j, k += 2)
        terms.push_back({all_ints[k], all_coeffs[c++], std::int32_t(all_ints[k + 1])});
    }
  }
  std::unordered_set<std::int64_t> bc_dofs;
  {
    std::vector<std::int8_t> marker(num_owned + V.dofmap()->index_map->num_ghosts()
                                                    * V.dofmap()->index_map_bs(), 0);
    for (const auto& bc : bcs)
      bc->mark_dofs(marker);
    std::vector<std::int32_t> owned_bc;
    for (std::int32_t i = 0; i < num_owned; ++i)
      if (marker[i])
        owned_bc.push_back(i);
    for (auto g : all_gather(to_global(V, owned_bc), comm))
      bc_dofs.insert(g);
  }

  dolfinx_mpc::mpc_data out;
  out.slaves = d.slaves;
  out.offsets = {0};
  std::vector<Term> terms;
  // Failures are collected and raised on all ranks together: the constructor that
  // follows is collective.
  int failure[2] = {0, 0}; // a Dirichlet master; a chain that does not end
  std::function<void(const Term&, int)> expand = [&](const Term& t, int depth)
  {
    auto it = table.find(t.master);
    if (it == table.end())
    {
      failure[0] |= int(bc_dofs.count(t.master) > 0);
      auto same = std::find_if(terms.begin(), terms.end(),
                               [&](const Term& u) { return u.master == t.master; });
      if (same != terms.end())
        same->coeff += t.coeff;
      else
        terms.push_back(t);
    }
    else if (depth > 3)
      failure[1] = 1;
    else
      for (const auto& u : it->second)
        expand({u.master, t.coeff * u.coeff, u.owner}, depth + 1);
  };
  for (std::size_t i = 0; i < d.slaves.size(); ++i)
  {
    terms.clear();
    for (auto k = d.offsets[i]; k < d.offsets[i + 1]; ++k)
      expand({d.masters[k], d.coeffs[k], d.owners[k]}, 0);
    for (const auto& t : terms)
    {
      out.masters.push_back(t.master);
      out.coeffs.push_back(t.coeff);
      out.owners.push_back(t.owner);
    }
    out.offsets.push_back(out.masters.size());
  }
  MPI_Allreduce(MPI_IN_PLACE, failure, 2, MPI_INT, MPI_MAX, comm);
  if (failure[0])
    throw std::runtime_error(
        "periodic constraint: a slave depends on a Dirichlet dof (the periodic faces are "
        "refined differently next to a Dirichlet face), which dolfinx_mpc 0.5 cannot express");
  if (failure[1])
    throw std::runtime_error("periodic constraint: a slave-master chain does not end");
  return out;
}
} // namespace

PeriodicConstraint::PeriodicConstraint(std::shared_ptr<const Space> V,
                                       const std::array<double, 3>& lower,
                                       const std::array<double, 3>& upper,
                                       const std::vector<int>& axes, const BCs& bcs)
    : V_(V)
{
  if (axes.empty())
    return;
  const int gdim = V->mesh()->geometry().dim();
  for (int a : axes)
    if (a < 0 || a >= gdim)
      throw std::runtime_error("periodic axis " + std::to_string(a) + " outside the mesh dimension");

  double tol = 0;
  for (int a : axes)
    tol = std::max(tol, 1e-8 * (upper[a] - lower[a]));
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
    append(all, dolfinx_mpc::create_periodic_condition_geometrical(piece, max_face, to_min, bcs,
                                                                   1.0, sub));
    // 2. Where the min face is finer than the max face (local refinement), its extra dofs
    //    have no partner; left free they would see a one-sided (natural) condition. They
    //    become slaves of the max face point, i.e. (after resolve_chains) of the min-face
    //    dofs that do have partners, so both traces are the same coarse polynomial.
    const auto partners = max_face_points(piece, sub, max_face, tol);
    auto unmatched_min = [=, &partners](const xt::xtensor<double, 2>& x)
    {
      xt::xtensor<bool, 1> marked = xt::zeros<bool>({x.shape(1)});
      const auto image = to_max(x);
      for (std::size_t i = 0; i < x.shape(1); ++i)
        marked(i) = on_min(x, i) && !on_max(x, i)
                    && !partners.count(point_key(image, i, tol));
      return marked;
    };
    append(all, dolfinx_mpc::create_periodic_condition_geometrical(piece, unmatched_min, to_max,
                                                                   bcs, 1.0, sub));
  }
  all = resolve_chains(*V, all, bcs);
  mpc_ = std::make_shared<dolfinx_mpc::MultiPointConstraint<T>>(V, all.slaves, all.masters,
                                                                all.coeffs, all.owners, all.offsets);
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
  MatZeroEntries(A);
  auto add_block = la::petsc::Matrix::set_block_fn(A, ADD_VALUES);
  auto add = la::petsc::Matrix::set_fn(A, ADD_VALUES);
  if (mpc_)
    // Puts 1 on the diagonal of the (owned) slave rows itself.
    dolfinx_mpc::assemble_matrix(add_block, add, a, mpc_, mpc_, bcs, 1.0);
  else
    fem::assemble_matrix(add_block, a, bcs);
  // BC rows and columns were skipped above, so ADD of the diagonal needs no flush.
  fem::set_diagonal<T>(add, *V_, bcs);
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
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
  if (mpc_)
  {
    dolfinx_mpc::assemble_vector(b.mutable_array(), L, mpc_);
    dolfinx_mpc::apply_lifting(b.mutable_array(), {a}, {bcs}, {}, 1.0, mpc_);
  }
  else
  {
    fem::assemble_vector(b.mutable_array(), L);
    fem::apply_lifting<T>(b.mutable_array(), {a}, {bcs}, {}, 1.0);
  }
  b.scatter_rev(std::plus<T>());
  fem::set_bc<T>(b.mutable_array(), bcs);
}

void PeriodicConstraint::backsubstitute(la::Vector<T>& x, Function& u) const
{
  if (mpc_)
  {
    x.scatter_fwd(); // masters owned elsewhere are ghosts of x
    // backsubstitution adds to the slave value, so start from zero.
    mpc_->homogenize(x.mutable_array());
    mpc_->backsubstitution(x.mutable_array());
  }
  // The constrained index map extends V's ghosts at the end: V's part is a prefix.
  auto out = u.x()->mutable_array();
  std::copy_n(x.array().begin(), out.size(), out.begin());
}
} // namespace cellphase
