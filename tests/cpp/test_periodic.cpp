// Periodic boundary conditions (compat/Periodic.h, dolfinx_mpc) with P2 manufactured solutions:
//  - -Lap u = f periodic in x with Dirichlet data at y = 0, 1, and -Lap u + u = f periodic
//    in x and y (also on tetrahedra in x, y, z, and for a P2 vector field): L2 errors fall
//    at order 3, values on opposite faces agree to round-off;
//  - the same on meshes refined next to one periodic face only (non-matching faces);
//  - a mixed P2 pair (u - dt Lap w = f, w = -Lap u + u) periodic in x and y, so that the
//    constraint acts on sub-spaces;
//  - Taylor-Hood Stokes flow in a channel periodic in x: the parabola to round-off.
// Also run on two ranks (tests/CMakeLists.txt), where slaves and masters are on different ranks.
#include "compat/Periodic.h"
#include "mpi_main.h"
#include "periodic_mixed.h"
#include "periodic_poisson.h"
#include "periodic_poisson_3d.h"
#include "periodic_stokes.h"
#include "periodic_vector.h"
#include "solve/LinearSolver.h"
#include "solve/RecordedAssembly.h"
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <xtensor/xview.hpp>

using namespace cellphase;
namespace
{
constexpr double pi = std::numbers::pi;
const std::array<double, 3> lower{0, 0, 0}, upper{1, 1, 0};

std::shared_ptr<Mesh> unit_square(int n)
{
  scene::Domain d;
  d.resolution = {n, n, 0};
  return compat::create_base_mesh(MPI_COMM_WORLD, d);
}

ConstantMap constants(const std::map<std::string, double>& values)
{
  ConstantMap c;
  for (const auto& [k, v] : values)
    c[k] = std::make_shared<Constant>(v);
  return c;
}

/// Facets on y = 0 and y = 1.
std::vector<std::int32_t> bottom_top_facets(Mesh& mesh)
{
  mesh.topology_mutable().create_connectivity(1, 2);
  return dolfinx::mesh::locate_entities_boundary(
      mesh, 1,
      [](const xt::xtensor<double, 2>& x) -> xt::xtensor<bool, 1>
      { return xt::isclose(xt::row(x, 1), 0.0) || xt::isclose(xt::row(x, 1), 1.0); });
}

/// Dirichlet data of u_x = cos(2 pi x + 0.3) exp(y) at y = 0, 1.
BCs bottom_top_dirichlet(Mesh& mesh, std::shared_ptr<const Space> V)
{
  auto g = std::make_shared<Function>(V);
  compat::interpolate(*g, [](double x, double y, double)
                      { return std::cos(2 * pi * x + 0.3) * std::exp(y); });
  auto facets = bottom_top_facets(mesh);
  return {std::make_shared<DirichletBC>(
      g, dolfinx::fem::locate_dofs_topological(*V, 1, std::span<const std::int32_t>(facets)))};
}

/// Constrained (or, with no axes in pc, plain) assembly and LU solve; returns u on W.
std::shared_ptr<Function> solve(const PeriodicConstraint& pc, std::shared_ptr<const Space> W,
                                std::shared_ptr<const Form> a, const Form& L, const BCs& bcs)
{
  auto A = pc.create_matrix(*a);
  pc.assemble_matrix(A.mat(), *a, bcs);
  auto b = pc.create_vector();
  auto x = pc.create_vector();
  pc.assemble_vector(b, L, a, bcs);
  LinearSolver solver(MPI_COMM_WORLD, "periodic_", {});
  solver.set_operator(A.mat());
  solver.solve(b, x, "periodic test");
  auto u = std::make_shared<Function>(W);
  pc.backsubstitute(x, *u);
  return u;
}

/// Largest |u(min face) - u(max face)| of a scalar function over the dof points that
/// match across the faces normal to `axis`, from all ranks, and the largest |u| there (a
/// jump of 0 between zeros proves nothing). Checks that every max-face dof has a partner.
struct Jump
{
  double jump = 0, size = 0;
};

Jump periodic_jump(const Function& u, int axis, double hi = 1.0)
{
  auto V = u.function_space();
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  const std::int32_t n = V->dofmap()->index_map->size_local();
  auto values = u.x()->array();
  // (face 0/1, the two other coordinates, value) per owned dof on the faces 0 and hi
  std::vector<double> mine;
  for (std::int32_t i = 0; i < n; ++i)
  {
    const double xa = X[3 * i + axis];
    if (std::abs(xa) < 1e-10 || std::abs(xa - hi) < 1e-10)
      mine.insert(mine.end(), {double(xa > 0.5 * hi), X[3 * i + (axis + 1) % 3],
                               X[3 * i + (axis + 2) % 3], values[i]});
  }
  int size, count = mine.size();
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<double> all(offsets.back());
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, MPI_COMM_WORLD);
  auto key = [&](std::size_t k)
  { return std::make_pair(std::llround(all[k + 1] * 1e9), std::llround(all[k + 2] * 1e9)); };
  std::map<std::pair<long long, long long>, double> min_face;
  for (std::size_t k = 0; k < all.size(); k += 4)
    if (all[k] == 0)
      min_face[key(k)] = all[k + 3];
  Jump r;
  int matched = 0;
  for (std::size_t k = 0; k < all.size(); k += 4)
    if (all[k] == 1)
    {
      auto it = min_face.find(key(k));
      EXPECT_NE(it, min_face.end()) << "no partner for the dof at " << all[k + 1] << ", "
                                    << all[k + 2];
      if (it != min_face.end())
      {
        r.jump = std::max(r.jump, std::abs(it->second - all[k + 3]));
        r.size = std::max(r.size, std::abs(all[k + 3]));
        ++matched;
      }
    }
  EXPECT_GT(matched, 0);
  return r;
}

std::vector<int> ns{8, 16, 32};

void expect_rate_3(const std::vector<double>& e, const std::string& what)
{
  for (std::size_t i = 1; i < e.size(); ++i)
  {
    const double rate = std::log2(e[i - 1] / e[i]);
    std::printf("  %s n = %2d: |e| = %.3e (rate %.2f)\n", what.c_str(), ns[i], e[i], rate);
    EXPECT_GT(rate, 2.8) << what; // P2 in L2, pre-asymptotic slack as in test_mms
  }
}

/// Scalar Poisson/Helmholtz problem: L2 error, left/right and bottom/top jumps.
struct ScalarResult
{
  double error, jump_x, jump_y, error_unconstrained;
};

ScalarResult solve_scalar(int n, bool xy)
{
  auto mesh = unit_square(n);
  auto V = compat::create_space(functionspace_form_periodic_poisson_a, "u", mesh);
  auto c = constants({{"c", xy ? 1.0 : 0.0}});
  // Dirichlet data (lifted into b) for the problem periodic in x only.
  const BCs bcs = xy ? BCs{} : bottom_top_dirichlet(*mesh, V);
  PeriodicConstraint pc(V, lower, upper, xy ? std::vector<int>{0, 1} : std::vector<int>{0}, bcs);
  // Dofs on the max faces (P2: 2n+1 per face), less the Dirichlet corners / the shared corner.
  EXPECT_EQ(pc.num_slaves(), xy ? 4 * n + 1 : 2 * n - 1);
  auto a = compat::create_form(*form_periodic_poisson_a, {V, V}, {}, c);
  auto L = compat::create_form(xy ? *form_periodic_poisson_L_xy : *form_periodic_poisson_L_x, {V},
                               {}, c);
  auto error = [&](std::shared_ptr<Function> uh)
  {
    auto e = compat::create_form(xy ? *form_periodic_poisson_error_xy
                                    : *form_periodic_poisson_error_x,
                                 {}, {{"uh", uh}}, c, mesh);
    return std::sqrt(compat::assemble_scalar(*e));
  };
  auto uh = solve(pc, V, a, *L, bcs);
  ScalarResult r{error(uh), periodic_jump(*uh, 0).jump, periodic_jump(*uh, 1).jump, 0};
  if (!xy) // the same system without the constraint: natural conditions on x = 0, 1
    r.error_unconstrained = error(solve(PeriodicConstraint(V, lower, upper, {}), V, a, *L, bcs));
  return r;
}

void check_scalar(bool xy)
{
  std::vector<double> errors;
  for (int n : ns)
  {
    auto r = solve_scalar(n, xy);
    errors.push_back(r.error);
    std::printf("  n = %2d: jump left/right %.1e", n, r.jump_x);
    std::printf(xy ? ", bottom/top %.1e\n" : "\n", r.jump_y);
    EXPECT_LT(r.jump_x, 1e-12);
    if (xy)
      EXPECT_LT(r.jump_y, 1e-12);
    else
    {
      std::printf("  n = %2d: error without the constraint %.3e\n", n, r.error_unconstrained);
      EXPECT_GT(r.error_unconstrained, 100 * r.error);
    }
  }
  expect_rate_3(errors, xy ? "periodic x, y" : "periodic x");
}
} // namespace

TEST(Periodic, PoissonPeriodicInXConvergesAtP2Rate) { check_scalar(false); }
TEST(Periodic, HelmholtzPeriodicInXAndYConvergesAtP2Rate) { check_scalar(true); }

namespace
{
/// 16 x 16 mesh refined once in the cells next to x = 1 (near_max) or x = 0, as the
/// adaptive mesh does near an interface that crosses the boundary: the faces do not match.
std::shared_ptr<Mesh> refined_square(bool near_max)
{
  auto base = unit_square(16);
  std::vector<std::int32_t> cells;
  for (std::int32_t c = 0; c < compat::num_owned_cells(*base); ++c)
  {
    const auto X = compat::cell_vertex_coordinates(*base, c);
    const double xm = (X[0] + X[3] + X[6]) / 3;
    if (near_max ? xm > 0.75 : xm < 0.25)
      cells.push_back(c);
  }
  return compat::refine_cells(*base, cells);
}

/// On a refined_square: -Lap u + u = f periodic in x and y, or (dirichlet) -Lap u = f
/// periodic in x with Dirichlet data at y = 0, 1. Returns the L2 error and the largest
/// |u(0, y) - u(1, y)| at 401 heights (-1 on several ranks: point evaluation is rank-local).
std::pair<double, double> solve_nonmatching(bool fine_slave_side, bool dirichlet)
{
  auto mesh = refined_square(fine_slave_side);
  auto V = compat::create_space(functionspace_form_periodic_poisson_a, "u", mesh);
  auto c = constants({{"c", dirichlet ? 0.0 : 1.0}});
  const BCs bcs = dirichlet ? bottom_top_dirichlet(*mesh, V) : BCs{};
  PeriodicConstraint pc(V, lower, upper, dirichlet ? std::vector<int>{0} : std::vector<int>{0, 1},
                        bcs);
  auto a = compat::create_form(*form_periodic_poisson_a, {V, V}, {}, c);
  auto L = compat::create_form(dirichlet ? *form_periodic_poisson_L_x : *form_periodic_poisson_L_xy,
                               {V}, {}, c);
  auto uh = solve(pc, V, a, *L, bcs);
  auto e = compat::create_form(
      dirichlet ? *form_periodic_poisson_error_x : *form_periodic_poisson_error_xy, {},
      {{"uh", uh}}, c, mesh);
  const double error = std::sqrt(compat::assemble_scalar(*e));
  int size;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1)
    return {error, -1};
  const int m = 401;
  std::vector<double> pts(6 * m), values(2 * m);
  for (int k = 0; k < m; ++k)
  {
    pts[6 * k + 1] = pts[6 * k + 4] = double(k) / (m - 1);
    pts[6 * k + 3] = 1.0;
  }
  compat::make_evaluator(uh)(pts, values);
  double jump = 0;
  for (int k = 0; k < m; ++k)
    jump = std::max(jump, std::abs(values[2 * k] - values[2 * k + 1]));
  return {error, jump};
}

void check_nonmatching(bool dirichlet)
{
  const double uniform = solve_scalar(16, !dirichlet).error;
  for (bool fine_slaves : {true, false})
  {
    auto [error, jump] = solve_nonmatching(fine_slaves, dirichlet);
    std::printf("  fine %s side: |e| = %.3e (uniform 16 x 16: %.3e), max |u(0,y) - u(1,y)| = %.1e\n",
                fine_slaves ? "slave " : "master", error, uniform, jump);
    EXPECT_LT(error, 1.05 * uniform);
    // Both traces are the coarse side's polynomial: periodic at every point, not only at
    // the dofs.
    if (jump >= 0)
      EXPECT_LT(jump, 1e-12);
  }
}
} // namespace

// Without the repairs of PeriodicConstraint (periodic x, y; fine slave / fine master side):
// slaves of slaves near the corners gave |e| = 0.1; the unmatched dofs of a fine min face
// gave |e| = 3.4e-3 and jumps of 3.7e-2.
TEST(Periodic, NonMatchingFacesAfterLocalRefinement) { check_nonmatching(false); }

// Fine slaves next to y = 0 depend on the Dirichlet corner dof of the coarse side. As a
// dolfinx_mpc master it would get the slave's row (Dirichlet value lost: u(0,0) = 0.962
// instead of 0.955); PeriodicConstraint turns it into a constant of the slave instead.
TEST(Periodic, NonMatchingFacesNextToDirichletFace) { check_nonmatching(true); }

TEST(Periodic, VectorSpaceComponentsArePeriodic)
{
  // A blocked space (dofmap block size 2): its slaves are unrolled dofs.
  std::vector<double> errors;
  for (int n : ns)
  {
    auto mesh = unit_square(n);
    auto V = compat::create_space(functionspace_form_periodic_vector_a, "u", mesh);
    PeriodicConstraint pc(V, lower, upper, {0, 1});
    EXPECT_EQ(pc.num_slaves(), 2 * (4 * n + 1));
    auto a = compat::create_form(*form_periodic_vector_a, {V, V}, {}, {});
    auto L = compat::create_form(*form_periodic_vector_L, {V}, {}, {});
    auto uh = solve(pc, V, a, *L, {});
    errors.push_back(std::sqrt(compat::assemble_scalar(
        *compat::create_form(*form_periodic_vector_error, {}, {{"uh", uh}}, {}, mesh))));
    for (int k : {0, 1})
    {
      const Function component = uh->sub(k).collapse();
      const double jx = periodic_jump(component, 0).jump, jy = periodic_jump(component, 1).jump;
      std::printf("  n = %2d, u_%d: jump left/right %.1e, bottom/top %.1e\n", n, k, jx, jy);
      EXPECT_LT(jx, 1e-12);
      EXPECT_LT(jy, 1e-12);
    }
  }
  expect_rate_3(errors, "vector");
}

TEST(Periodic, MixedSpaceSubspacesArePeriodic)
{
  std::vector<double> eu, ew;
  for (int n : ns)
  {
    auto mesh = unit_square(n);
    auto W = compat::create_space(functionspace_form_periodic_mixed_a, "v_0", mesh);
    auto c = constants({{"dt", 0.01}});
    PeriodicConstraint pc(W, lower, upper, {0, 1});
    EXPECT_EQ(pc.num_slaves(), 2 * (4 * n + 1));
    auto a = compat::create_form(*form_periodic_mixed_a, {W, W}, {}, c);
    auto L = compat::create_form(*form_periodic_mixed_L, {W}, {}, c);
    auto uh = solve(pc, W, a, *L, {});
    auto err = [&](const ufcx_form& f)
    { return std::sqrt(compat::assemble_scalar(*compat::create_form(f, {}, {{"uh", uh}}, c, mesh))); };
    eu.push_back(err(*form_periodic_mixed_error_u));
    ew.push_back(err(*form_periodic_mixed_error_w));
    for (int field : {0, 1})
    {
      const Function f = uh->sub(field).collapse();
      const double jx = periodic_jump(f, 0).jump, jy = periodic_jump(f, 1).jump;
      std::printf("  n = %2d, field %d: jump left/right %.1e, bottom/top %.1e\n", n, field, jx, jy);
      EXPECT_LT(jx, 1e-11);
      EXPECT_LT(jy, 1e-11);
    }
  }
  expect_rate_3(eu, "u");
  expect_rate_3(ew, "w");
}

TEST(Periodic, HelmholtzPeriodicInXYZOnTetrahedra)
{
  const std::vector<int> ns3{4, 8, 16};
  std::vector<double> errors;
  for (int n : ns3)
  {
    scene::Domain d;
    d.dim = 3;
    d.upper = {1, 1, 1};
    d.resolution = {n, n, n};
    auto mesh = compat::create_base_mesh(MPI_COMM_WORLD, d);
    auto V = compat::create_space(functionspace_form_periodic_poisson_3d_a, "u", mesh);
    PeriodicConstraint pc(V, {0, 0, 0}, {1, 1, 1}, {0, 1, 2});
    // All dofs on the three max faces.
    EXPECT_EQ(pc.num_slaves(), std::pow(2 * n + 1, 3) - std::pow(2 * n, 3));
    auto a = compat::create_form(*form_periodic_poisson_3d_a, {V, V}, {}, {});
    auto L = compat::create_form(*form_periodic_poisson_3d_L, {V}, {}, {});
    auto uh = solve(pc, V, a, *L, {});
    errors.push_back(std::sqrt(compat::assemble_scalar(
        *compat::create_form(*form_periodic_poisson_3d_error, {}, {{"uh", uh}}, {}, mesh))));
    for (int axis : {0, 1, 2})
    {
      const auto j = periodic_jump(*uh, axis);
      std::printf("  n = %d, axis %d: jump %.1e\n", n, axis, j.jump);
      EXPECT_LT(j.jump, 1e-12);
    }
  }
  // P2 in L2: the rate 3 of docs/architecture.md, held on the pair 8/16 to 0.2 below (as in
  // 2D); the pair 4/8 is pre-asymptotic (2.5 or better).
  const double coarse = std::log2(errors[0] / errors[1]), fine = std::log2(errors[1] / errors[2]);
  std::printf("  3D n = 8: |e| = %.3e (rate %.2f), n = 16: |e| = %.3e (rate %.2f)\n", errors[1],
              coarse, errors[2], fine);
  EXPECT_GT(coarse, 2.5);
  EXPECT_GT(fine, 2.8);
}

namespace
{
/// Taylor-Hood channel: error against the parabola, divergence, jumps of (u_x, u_y, p).
struct StokesResult
{
  double error_u, divergence;
  std::array<Jump, 3> jumps;
};

StokesResult solve_stokes(int n, double beta)
{
  auto mesh = unit_square(n);
  auto W = compat::create_space(functionspace_form_periodic_stokes_a, "v_0", mesh);
  auto c = constants({{"nu", 0.5}, {"beta", beta}});
  BCs bcs;
  // No slip at y = 0, 1.
  auto V = std::make_shared<Space>(W->sub({0})->collapse().first);
  auto facets = bottom_top_facets(*mesh);
  auto zero_u = std::make_shared<Function>(V);
  zero_u->x()->set(0.0);
  bcs.push_back(std::make_shared<DirichletBC>(
      zero_u,
      dolfinx::fem::locate_dofs_topological({*W->sub({0}), *V}, 1,
                                            std::span<const std::int32_t>(facets)),
      W->sub({0})));
  // Pressure fixed at the centre (an interior vertex, so no slave and no master).
  auto Q = std::make_shared<Space>(W->sub({1})->collapse().first);
  auto zero_p = std::make_shared<Function>(Q);
  zero_p->x()->set(0.0);
  auto centre = dolfinx::fem::locate_dofs_geometrical(
      {*W->sub({1}), *Q},
      [](const xt::xtensor<double, 2>& x) -> xt::xtensor<bool, 1>
      { return xt::isclose(xt::row(x, 0), 0.5) && xt::isclose(xt::row(x, 1), 0.5); });
  bcs.push_back(std::make_shared<DirichletBC>(zero_p, std::move(centre), W->sub({1})));

  PeriodicConstraint pc(W, lower, upper, {0}, bcs);
  // Per velocity component 2n+1 dofs on x = 1 less the two no-slip corners; P1 pressure n+1.
  EXPECT_EQ(pc.num_slaves(), 2 * (2 * n - 1) + n + 1);
  auto a = compat::create_form(*form_periodic_stokes_a, {W, W}, {}, c);
  auto L = compat::create_form(*form_periodic_stokes_L, {W}, {}, c);
  auto uh = solve(pc, W, a, *L, bcs);
  auto functional = [&](const ufcx_form& f)
  { return std::sqrt(compat::assemble_scalar(*compat::create_form(f, {}, {{"uh", uh}}, c, mesh))); };
  StokesResult r{functional(*form_periodic_stokes_error_u),
                 functional(*form_periodic_stokes_divergence), {}};
  auto velocity = uh->sub(0);
  for (int k : {0, 1})
    r.jumps[k] = periodic_jump(velocity.sub(k).collapse(), 0);
  r.jumps[2] = periodic_jump(uh->sub(1).collapse(), 0);
  return r;
}

void print(const StokesResult& r)
{
  std::printf("  |u - parabola| = %.2e, |div u| = %.2e\n", r.error_u, r.divergence);
  for (int k = 0; k < 3; ++k)
    std::printf("  %s on x = 0, 1: max |value| %.2e, jump %.1e\n", k == 2 ? "p  " : k ? "u_y" : "u_x",
                r.jumps[k].size, r.jumps[k].jump);
}
} // namespace

TEST(Periodic, StokesChannelIsTheParabola)
{
  auto r = solve_stokes(16, 0.0);
  print(r);
  EXPECT_LT(r.error_u, 1e-11);
  EXPECT_LT(r.divergence, 1e-10);
  for (const auto& j : r.jumps)
    EXPECT_LT(j.jump, 1e-11);
}

TEST(Periodic, StokesChannelWithCrossForceStaysPeriodic)
{
  // A force that varies along the channel: the flow is no parabola any more, but its
  // velocity components and pressure still match across x = 0 and x = 1.
  auto r = solve_stokes(16, 5.0);
  print(r);
  EXPECT_GT(r.error_u, 1e-3);
  for (const auto& j : r.jumps) // u_y and p are nonzero on the faces too
    EXPECT_GT(j.size, 1e-3);
  for (const auto& j : r.jumps)
    EXPECT_LT(j.jump, 1e-11);
}

namespace
{
/// Entries of the owned rows of X and Y that differ in column or value (bit for bit),
/// summed over the ranks.
int differing_entries(Mat X, Mat Y)
{
  PetscInt first, last;
  MatGetOwnershipRange(X, &first, &last);
  int differ = 0;
  for (PetscInt row = first; row < last; ++row)
  {
    PetscInt nx, ny;
    const PetscInt *cx, *cy;
    const PetscScalar *vx, *vy;
    MatGetRow(X, row, &nx, &cx, &vx);
    std::vector<PetscInt> cols(cx, cx + nx);
    std::vector<PetscScalar> vals(vx, vx + nx);
    MatRestoreRow(X, row, &nx, &cx, &vx); // (sets nx to 0)
    MatGetRow(Y, row, &ny, &cy, &vy);
    if (ny != PetscInt(cols.size()))
      ++differ;
    else
      for (PetscInt k = 0; k < ny; ++k)
        differ += cols[k] != cy[k] || vals[k] != vy[k];
    MatRestoreRow(Y, row, &ny, &cy, &vy);
  }
  MPI_Allreduce(MPI_IN_PLACE, &differ, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  return differ;
}
} // namespace

// solve/RecordedAssembly: element entries added at recorded positions give PETSc's own
// sums bit for bit (rows of other ranks on two ranks); a form of its own or a call sequence
// that differs from the record goes through PETSc again. Then the same for the periodic
// constraint's assembly (dolfinx_mpc's, with slave rows and master columns).
TEST(Periodic, RecordedAssemblyGivesPetscsSumsBitForBit)
{
  auto mesh = unit_square(12);
  auto W = compat::create_space(functionspace_form_periodic_mixed_a, "v_0", mesh);
  auto dt = std::make_shared<Constant>(0.01);
  const ConstantMap c{{"dt", dt}};
  auto a = compat::create_form(*form_periodic_mixed_a, {W, W}, {}, c);
  auto a_again = compat::create_form(*form_periodic_mixed_a, {W, W}, {}, c);
  auto A = dolfinx::fem::petsc::create_matrix(*a), reference = dolfinx::fem::petsc::create_matrix(*a);
  // Assembly into M by `recorder`, leaving out the first element matrix if asked.
  auto assemble = [&](RecordedAssembly& recorder, Mat M, const Form& form, bool drop_first)
  {
    recorder.assemble(
        M, &form,
        [&](const RecordedAssembly::AddFn& add_block, const RecordedAssembly::AddFn&)
        {
          int call = 0;
          RecordedAssembly::AddFn add = [&](const auto& rows, const auto& cols, const auto& values)
          { return drop_first && call++ == 0 ? 0 : add_block(rows, cols, values); };
          dolfinx::fem::assemble_matrix(add, form, {});
        },
        [&]
        {
          MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY);
          MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY);
        });
  };
  // The reference goes through PETSc every time (a new recorder each time).
  auto through_petsc = [&](const Form& form, bool drop_first)
  {
    RecordedAssembly fresh;
    assemble(fresh, reference, form, drop_first);
    EXPECT_EQ(fresh.replays(), 0);
  };
  RecordedAssembly recorded;
  assemble(recorded, A, *a, false); // records
  for (double value : {0.02, 0.5})
  {
    dt->value[0] = value;
    assemble(recorded, A, *a, false);
    through_petsc(*a, false);
    EXPECT_EQ(differing_entries(A, reference), 0) << "dt " << value;
  }
  EXPECT_EQ(recorded.replays(), 2);
  assemble(recorded, A, *a_again, false); // another form: recorded anew
  EXPECT_EQ(recorded.replays(), 2);
  assemble(recorded, A, *a, true); // calls that do not match the record: through PETSc
  through_petsc(*a, true);
  EXPECT_EQ(recorded.replays(), 2);
  EXPECT_EQ(differing_entries(A, reference), 0);
  MatDestroy(&A);
  MatDestroy(&reference);

  for (const std::vector<int>& axes : {std::vector<int>{}, std::vector<int>{0, 1}})
  {
    PeriodicConstraint pc(W, lower, upper, axes);
    auto replayed = pc.create_matrix(*a), fresh = pc.create_matrix(*a);
    for (int k = 0; k < 3; ++k) // records, replays twice
      pc.assemble_matrix(replayed.mat(), *a, {});
    PeriodicConstraint(W, lower, upper, axes).assemble_matrix(fresh.mat(), *a, {});
    EXPECT_EQ(differing_entries(replayed.mat(), fresh.mat()), 0) << "axes " << axes.size();
  }
}
