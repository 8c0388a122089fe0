// Constraint data of dolfinx_mpc 0.5 (mpc_data: local slaves, global masters) joined and
// repaired across ranks before the MultiPointConstraint is built; see compat/Periodic.
#pragma once
#include "compat/Dolfinx.h"
#include <array>
#include <dolfinx_mpc/utils.h>
#include <functional>
#include <set>
#include <xtensor/xarray.hpp>

namespace cellphase::periodic
{
/// Appends one constraint's data to the union of all (offsets shifted past earlier masters).
void append(dolfinx_mpc::mpc_data& all, const dolfinx_mpc::mpc_data& d);

/// A point (column i of 3 rows of coordinates) rounded to multiples of tol, for lookups.
using PointKey = std::array<std::int64_t, 3>;
PointKey point_key(const xt::xarray<double>& x, std::size_t i, double tol);

/// Positions of the dofs of a scalar (sub-)space (sub: a sub-space, collapsed here) that
/// `max_face` marks, from all ranks.
std::set<PointKey> max_face_points(
    std::shared_ptr<const Space> piece, bool sub,
    const std::function<xt::xtensor<bool, 1>(const xt::xtensor<double, 2>&)>& max_face,
    double tol);

/// dolfinx_mpc 0.5 assumes that masters are free dofs. Where the two faces do not match
/// (local refinement), a slave point can fall in a cell of the min face with a slave dof of
/// another axis (near an edge or corner) or a Dirichlet dof. Masters that are slaves are
/// replaced by their own masters; Dirichlet masters (values as in bcs now) leave the
/// master list and add a constant to the slave: u_s = sum c_m u_m + constant.
struct Resolved
{
  dolfinx_mpc::mpc_data data;
  std::vector<std::pair<std::int32_t, T>> constants; ///< (local slave, constant)
};
Resolved resolve_chains(const Space& V, const dolfinx_mpc::mpc_data& d, const BCs& bcs);
} // namespace cellphase::periodic
