#include "compat/PeriodicData.h"
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>
#include <xtensor/xadapt.hpp>
#include <xtensor/xview.hpp>

namespace cellphase::periodic
{
using namespace dolfinx;

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

namespace
{
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
} // namespace

PointKey point_key(const xt::xarray<double>& x, std::size_t i, double tol)
{
  auto r = [&](int d) { return std::int64_t(std::llround(x(d, i) / tol)); };
  return {r(0), r(1), r(2)};
}

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

Resolved resolve_chains(const Space& V, const dolfinx_mpc::mpc_data& d, const BCs& bcs)
{
  MPI_Comm comm = V.mesh()->comm();
  const int bs = V.dofmap()->index_map_bs();
  const std::int32_t num_owned = V.dofmap()->index_map->size_local() * bs;
  const std::int32_t num_local = num_owned + V.dofmap()->index_map->num_ghosts() * bs;
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
    coeffs.insert(coeffs.end(), d.coeffs.begin() + d.offsets[i],
                  d.coeffs.begin() + d.offsets[i + 1]);
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
  // Dirichlet dofs of all ranks with their values (boundary only).
  std::unordered_map<std::int64_t, T> bc_values;
  {
    std::vector<std::int8_t> marker(num_local, 0);
    std::vector<T> values(num_local, 0);
    for (const auto& bc : bcs)
    {
      bc->mark_dofs(marker);
      bc->dof_values(values);
    }
    std::vector<std::int32_t> owned_bc;
    std::vector<T> owned_values;
    for (std::int32_t i = 0; i < num_owned; ++i)
      if (marker[i])
        owned_bc.push_back(i), owned_values.push_back(values[i]);
    const auto all_dofs = all_gather(to_global(V, owned_bc), comm);
    const auto all_values = all_gather(owned_values, comm);
    for (std::size_t k = 0; k < all_dofs.size(); ++k)
      bc_values[all_dofs[k]] = all_values[k];
  }

  Resolved out;
  out.data.slaves = d.slaves;
  out.data.offsets = {0};
  std::vector<Term> terms;
  T constant = 0;
  bool has_constant = false;
  bool cycle = false;
  std::function<void(const Term&, int)> expand = [&](const Term& t, int depth)
  {
    if (auto it = table.find(t.master); it != table.end())
    {
      if (depth > 3)
        cycle = true;
      else
        for (const auto& u : it->second)
          expand({u.master, t.coeff * u.coeff, u.owner}, depth + 1);
    }
    else if (auto bc = bc_values.find(t.master); bc != bc_values.end())
    {
      constant += t.coeff * bc->second;
      has_constant = true;
    }
    else if (auto same = std::find_if(terms.begin(), terms.end(),
                                      [&](const Term& u) { return u.master == t.master; });
             same != terms.end())
      same->coeff += t.coeff;
    else
      terms.push_back(t);
  };
  for (std::size_t i = 0; i < d.slaves.size(); ++i)
  {
    terms.clear();
    constant = 0;
    has_constant = false;
    for (auto k = d.offsets[i]; k < d.offsets[i + 1]; ++k)
      expand({d.masters[k], d.coeffs[k], d.owners[k]}, 0);
    for (const auto& t : terms)
    {
      out.data.masters.push_back(t.master);
      out.data.coeffs.push_back(t.coeff);
      out.data.owners.push_back(t.owner);
    }
    out.data.offsets.push_back(out.data.masters.size());
    if (has_constant)
      out.constants.emplace_back(d.slaves[i], constant);
  }
  // Raised on all ranks together: the constructor that follows is collective.
  int failed = cycle;
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, comm);
  if (failed)
    throw std::runtime_error("periodic constraint: a slave-master chain does not end");
  return out;
}
} // namespace cellphase::periodic
