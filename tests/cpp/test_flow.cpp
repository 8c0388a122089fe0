// The flow module (forms/flow.py, FlowModule) on fixed meshes:
// * manufactured solutions with variable viscosity (and density) converge at the
//   Taylor-Hood rates: velocity L2 order 3, pressure L2 order 2;
// * Poiseuille and Couette flows lie in P2 x P1 and are reproduced to round-off;
// * the factorisation is reused while the matrix cannot have changed;
// * energy decay, the membrane force input and Laplace's law for the capillary force.
#include "compat/Dolfinx.h"
#include "mms_flow.h"
#include "mpi_main.h"
#include "physics/FlowModule.h"
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

using namespace cellphase;
namespace
{
constexpr double pi = std::numbers::pi;

std::shared_ptr<Mesh> box_mesh(std::array<double, 3> upper, std::array<int, 3> n, int dim = 2)
{
  scene::Domain d;
  d.dim = dim;
  d.upper = upper;
  d.resolution = n;
  return compat::create_base_mesh(MPI_COMM_WORLD, d);
}

/// max |u - f| over the dofs of u (nodal values of Lagrange elements), over all ranks.
double max_nodal_error(const Function& u, const VectorPointFunction& f)
{
  Function exact(u.function_space());
  if (u.function_space()->dofmap()->index_map_bs() > 1)
    compat::interpolate_vector(exact, f);
  else
    compat::interpolate(exact, [&f](double x, double y, double z) { return f(x, y, z)[0]; });
  auto a = u.x()->array(), b = exact.x()->array();
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    m = std::max(m, std::abs(a[i] - b[i]));
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return m;
}

/// Value of a scalar Lagrange function at its node (x, y), from the rank that owns it.
double nodal_value(const Function& u, double x, double y)
{
  auto V = u.function_space();
  const auto X = V->tabulate_dof_coordinates(false);
  const std::int32_t owned = V->dofmap()->index_map->size_local();
  double value = std::numeric_limits<double>::lowest();
  for (std::int32_t i = 0; i < owned; ++i)
    if (std::hypot(X[3 * i] - x, X[3 * i + 1] - y) < 1e-12)
      value = u.x()->array()[i];
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return value;
}

std::vector<Wall> closed_box(std::vector<Wall> walls, int dim = 2)
{
  // The remaining sides become no-slip walls.
  for (int s = 0; s < 2 * dim; ++s)
  {
    bool given = false;
    for (const auto& w : walls)
      given = given || int(w.side) == s;
    if (!given)
      walls.push_back({Side(s), WallKind::no_slip});
  }
  return walls;
}

// ---- manufactured solutions (tests/forms/mms_flow.py) ----

FlowForms mms_forms()
{
  FlowForms f;
  f.a = form_mms_flow_a;
  f.L = form_mms_flow_L_mms;
  f.kinetic_energy = form_mms_flow_kinetic_energy;
  f.divergence_sq = form_mms_flow_divergence_sq;
  f.phase_weight = form_mms_flow_phase_weight;
  f.phase_velocity = {form_mms_flow_phase_velocity_0, form_mms_flow_phase_velocity_1, nullptr};
  f.pressure_integral = form_mms_flow_pressure_integral;
  f.domain_volume = form_mms_flow_domain_volume;
  f.space = functionspace_form_mms_flow_a;
  return f;
}

struct Errors
{
  double v, p;
};

Errors solve_mms(int n, const FlowParameters& params, int steps)
{
  auto mesh = box_mesh({1, 1, 0}, {n, n, 0});
  auto V = compat::create_space(functionspace_form_mms_flow_a, "phi", mesh);
  auto phi = std::make_shared<Function>(V), mu = std::make_shared<Function>(V);
  compat::interpolate(*phi, [](double x, double y, double)
                      { return 0.8 * std::sin(2 * pi * x) * std::cos(pi * y); });
  compat::interpolate(*mu, [](double x, double y, double)
                      { return std::cos(pi * x) * std::sin(2 * pi * y); });
  FlowModule flow(params, MPI_COMM_WORLD, mms_forms());
  flow.attach(mesh, phi, mu);
  // v^0 = interpolated exact v (steady), from the stream function sin^2(pi x) sin^2(pi y)
  compat::interpolate_vector(*flow.velocity(), [](double x, double y, double) {
    const double sx = std::sin(pi * x), sy = std::sin(pi * y);
    return std::array<double, 3>{2 * pi * sx * sx * sy * std::cos(pi * y),
                                 -2 * pi * sy * sy * sx * std::cos(pi * x), 0};
  });
  for (int k = 0; k < steps; ++k)
    flow.step(0.05);
  EXPECT_TRUE(flow.pressure_pinned());
  CoefficientMap c{{"v0", flow.velocity()}, {"p_h", flow.pressure()}};
  auto ev = compat::create_form(*form_mms_flow_error_v, {}, c, ConstantMap{}, mesh);
  auto ep = compat::create_form(*form_mms_flow_error_p, {}, c, ConstantMap{}, mesh);
  return {std::sqrt(compat::assemble_scalar(*ev)), std::sqrt(compat::assemble_scalar(*ep))};
}

void check_rates(const FlowParameters& params, int steps)
{
  std::vector<int> ns{8, 16, 32};
  std::vector<Errors> e;
  for (int n : ns)
    e.push_back(solve_mms(n, params, steps));
  std::printf("  n = %3d: |e_v| = %.3e, |e_p| = %.3e\n", ns[0], e[0].v, e[0].p);
  for (std::size_t i = 1; i < ns.size(); ++i)
  {
    const double rate_v = std::log2(e[i - 1].v / e[i].v);
    const double rate_p = std::log2(e[i - 1].p / e[i].p);
    std::printf("  n = %3d: |e_v| = %.3e (rate %.2f), |e_p| = %.3e (rate %.2f)\n", ns[i], e[i].v,
                rate_v, e[i].p, rate_p);
    // Taylor-Hood: O(h^3) for v and O(h^2) for p in L2. 0.3 below these allows the
    // pre-asymptotic range of meshes with 8..32 cells per unit length.
    EXPECT_GT(rate_v, 2.7);
    EXPECT_GT(rate_p, 1.7);
  }
}

FlowParameters all_walls_no_slip()
{
  FlowParameters p;
  p.walls = closed_box({});
  return p;
}
} // namespace

TEST(FlowManufactured, StokesVariableViscosityConvergesAtTaylorHoodRates)
{
  FlowParameters p = all_walls_no_slip();
  p.Re = 0;
  p.viscosity = {1.0, 4.0};
  p.density = {1.0, 3.0};    // enters only through rho(phi) g for Stokes
  p.gravity = {0.3, -1.0, 0};
  p.capillary = 0.7;
  p.force = {0.5, 0.2, 0};
  check_rates(p, 1);
}

TEST(FlowManufactured, NavierStokesVariableDensityAndViscosityConvergesAtTaylorHoodRates)
{
  // Three semi-implicit steps from the exact steady state, with every term of the form:
  // convection with rho(phi) v^n + J, variable eta and rho, gravity, capillary force.
  FlowParameters p = all_walls_no_slip();
  p.Re = 5;
  p.viscosity = {1.0, 4.0};
  p.density = {1.0, 3.0};
  p.mobility = 0.5;
  p.gravity = {0.3, -1.0, 0};
  p.capillary = 0.7;
  p.force = {0.5, 0.2, 0};
  check_rates(p, 3);
}

// ---- exact flows ----

TEST(FlowExact, PoiseuilleByBodyForceStokes)
{
  // v = (f/(2 eta) y (1-y), 0), p = 0 on [0,2]x[0,1]; in/outflow profiles prescribed.
  const double f = 3.0, eta = 0.7;
  auto profile = [=](double, double y, double) {
    return std::array<double, 3>{f / (2 * eta) * y * (1 - y), 0, 0};
  };
  FlowParameters p;
  p.viscosity = {eta, eta};
  p.force = {f, 0, 0};
  p.walls = {{Side::bottom, WallKind::no_slip}, {Side::top, WallKind::no_slip},
             {Side::left, WallKind::prescribed, {}, profile},
             {Side::right, WallKind::prescribed, {}, profile}};
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(box_mesh({2, 1, 0}, {4, 2, 0}));
  flow.step(0.1);
  const double ev = max_nodal_error(*flow.velocity(), profile);
  const double ep = max_nodal_error(*flow.pressure(), [](double, double, double) {
    return std::array<double, 3>{0, 0, 0};
  });
  std::printf("  Poiseuille (body force, Stokes): max |v - v_ex| = %.2e, max |p - p_ex| = %.2e\n",
              ev, ep);
  EXPECT_LT(ev, 1e-10);
  EXPECT_LT(ep, 1e-10);
  EXPECT_LT(flow.observables().divergence_l2, 1e-10);
}

TEST(FlowExact, PoiseuilleByPressureNavierStokes)
{
  // v = (4 U y (1-y), 0), p = -8 eta U (x - 1) (zero mean on [0,2]x[0,1]); the pressure
  // drop comes from the solve. (v.grad) v = 0, so Re and the steps do not matter.
  const double U = 1.5, eta = 0.4;
  auto profile = [=](double, double y, double) {
    return std::array<double, 3>{4 * U * y * (1 - y), 0, 0};
  };
  FlowParameters p;
  p.Re = 10;
  p.viscosity = {eta, eta};
  p.walls = {{Side::bottom, WallKind::no_slip}, {Side::top, WallKind::no_slip},
             {Side::left, WallKind::prescribed, {}, profile},
             {Side::right, WallKind::prescribed, {}, profile}};
  auto mesh = box_mesh({2, 1, 0}, {4, 2, 0});
  // Initial velocity on a space of our own: attach copies it into its dof order.
  auto v0 = std::make_shared<Function>(compat::create_space(flow_forms(2).space, "v0", mesh));
  compat::interpolate_vector(*v0, profile);
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(mesh, nullptr, nullptr, v0);
  for (int k = 0; k < 3; ++k)
    flow.step(0.1);
  const double ev = max_nodal_error(*flow.velocity(), profile);
  const double ep = max_nodal_error(*flow.pressure(), [=](double x, double, double) {
    return std::array<double, 3>{-8 * eta * U * (x - 1), 0, 0};
  });
  std::printf("  Poiseuille (pressure, Navier-Stokes): max |v - v_ex| = %.2e, max |p - p_ex| = %.2e\n",
              ev, ep);
  EXPECT_LT(ev, 1e-10);
  EXPECT_LT(ep, 1e-10);
  // Re = 10 with convection: v^n enters the matrix, but it stays the same here.
  EXPECT_LE(flow.factorisations(), 3);
}

TEST(FlowExact, CouetteMovingTopWallReusesTheFactorisation)
{
  // v = (U y / H, 0), p = 0: top wall moving with U, bottom at rest, linear profile at the
  // ends. Stokes with one viscosity: the matrix is factorised once for all steps.
  const double U = 2.0, H = 1.0;
  auto profile = [=](double, double y, double) { return std::array<double, 3>{U * y / H, 0, 0}; };
  FlowParameters p;
  p.viscosity = {1.3, 1.3};
  p.walls = {{Side::bottom, WallKind::no_slip},
             {Side::top, WallKind::moving, {U, 0.7 /* normal part, dropped */, 0}},
             {Side::left, WallKind::prescribed, {}, profile},
             {Side::right, WallKind::prescribed, {}, profile}};
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(box_mesh({3, H, 0}, {3, 2, 0}));
  for (int k = 0; k < 5; ++k)
  {
    auto t = flow.step(0.1);
    EXPECT_EQ(t.factorised, k == 0);
  }
  EXPECT_EQ(flow.factorisations(), 1);
  const double ev = max_nodal_error(*flow.velocity(), profile);
  const double ep = max_nodal_error(*flow.pressure(), [](double, double, double) {
    return std::array<double, 3>{0, 0, 0};
  });
  std::printf("  Couette: max |v - v_ex| = %.2e, max |p| = %.2e, factorisations %d\n", ev, ep,
              flow.factorisations());
  EXPECT_LT(ev, 1e-10);
  EXPECT_LT(ep, 1e-10);
  // Kinetic energy 1/2 rho int (U y/H)^2 = rho U^2 L H / 6 with rho = 1, L = 3.
  EXPECT_NEAR(flow.observables().kinetic_energy, U * U * 3 * H / 6, 1e-10);
}

TEST(FlowExact, CouetteIn3DWithFreeSlipFrontAndBack)
{
  // The 3D forms and free-slip walls: v = (U y, 0, 0) has no stress on z = const.
  const double U = 1.0;
  auto profile = [=](double, double y, double) { return std::array<double, 3>{U * y, 0, 0}; };
  FlowParameters p;
  p.walls = {{Side::bottom, WallKind::no_slip},
             {Side::top, WallKind::moving, {U, 0, 0}},
             {Side::left, WallKind::prescribed, {}, profile},
             {Side::right, WallKind::prescribed, {}, profile},
             {Side::front, WallKind::free_slip},
             {Side::back, WallKind::free_slip}};
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(box_mesh({1, 1, 1}, {2, 2, 2}, 3));
  flow.step(0.1);
  EXPECT_TRUE(flow.pressure_pinned());
  const double ev = max_nodal_error(*flow.velocity(), profile);
  std::printf("  Couette 3D: max |v - v_ex| = %.2e\n", ev);
  EXPECT_LT(ev, 1e-10);
}

// ---- reuse of factorisations ----

TEST(FlowReuse, TimeDependentStokesFactorisesOncePerTimeStepSize)
{
  // Re > 0 without convection: the matrix depends on dt only. A lid-driven cavity
  // accelerates, so the solution changes from step to step while the factors stay.
  FlowParameters p;
  p.Re = 1;
  p.convection = false;
  p.walls = closed_box({{Side::top, WallKind::moving, {1, 0, 0}}});
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(box_mesh({1, 1, 0}, {6, 6, 0}));
  std::vector<double> energy;
  for (int k = 0; k < 4; ++k)
  {
    flow.step(0.01);
    energy.push_back(flow.observables().kinetic_energy);
  }
  EXPECT_EQ(flow.factorisations(), 1);
  EXPECT_GT(energy[3], energy[0]); // spinning up
  flow.step(0.02);
  EXPECT_EQ(flow.factorisations(), 2);
  flow.step(0.02);
  EXPECT_EQ(flow.factorisations(), 2);
}

TEST(FlowReuse, NavierStokesRefactorisesEveryStep)
{
  FlowParameters p;
  p.Re = 100;
  p.walls = closed_box({{Side::top, WallKind::moving, {1, 0, 0}}});
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(box_mesh({1, 1, 0}, {6, 6, 0}));
  for (int k = 0; k < 3; ++k)
    flow.step(0.01);
  EXPECT_EQ(flow.factorisations(), 3);
}

TEST(FlowReuse, VariableViscosityRefactorisesOnlyWhenPhiChanges)
{
  // Stokes with eta(phi): the matrix follows phi, which a coupling updates in place.
  auto mesh = box_mesh({1, 1, 0}, {6, 6, 0});
  auto V = compat::create_space(flow_forms(2).space, "phi", mesh);
  auto phi = std::make_shared<Function>(V);
  compat::interpolate(*phi, [](double x, double y, double)
                      { return std::tanh((0.3 - std::hypot(x - 0.5, y - 0.5)) / 0.1); });
  FlowParameters p;
  p.viscosity = {1, 10};
  p.gravity = {0, -1, 0};
  p.density = {1, 2}; // a heavier cell sinks
  p.walls = closed_box({});
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(mesh, phi);
  flow.step(0.1);
  flow.step(0.1);
  EXPECT_EQ(flow.factorisations(), 1);
  auto o = flow.observables();
  std::printf("  sinking cell: velocity (%.3e, %.3e), kinetic energy %.3e\n", o.cell_velocity[0],
              o.cell_velocity[1], o.kinetic_energy);
  EXPECT_LT(o.cell_velocity[1], 0);
  EXPECT_NEAR(o.cell_velocity[0], 0, 1e-10); // symmetric about x = 1/2
  phi->x()->mutable_array()[0] += 0.01;
  flow.step(0.1);
  EXPECT_EQ(flow.factorisations(), 2);
}

// ---- physics ----

TEST(FlowPhysics, KineticEnergyDecaysWithoutForcing)
{
  // Navier-Stokes with no force and resting walls: with the Temam term the linearised
  // convection does no work, so E_kin (2.54) must fall every step (energy law (2.61)).
  FlowParameters p;
  p.Re = 100;
  p.walls = closed_box({});
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(box_mesh({1, 1, 0}, {8, 8, 0}));
  compat::interpolate_vector(*flow.velocity(), [](double x, double y, double) {
    const double sx = std::sin(pi * x), sy = std::sin(pi * y);
    return std::array<double, 3>{sx * sx * std::sin(2 * pi * y), -sy * sy * std::sin(2 * pi * x), 0};
  });
  double before = flow.observables().kinetic_energy;
  for (int k = 0; k < 5; ++k)
  {
    flow.step(0.05);
    const double now = flow.observables().kinetic_energy;
    EXPECT_LT(now, before) << "step " << k;
    before = now;
  }
  std::printf("  kinetic energy after 5 steps: %.4e\n", before);
}

TEST(FlowPhysics, MembraneForceActsAsABodyForce)
{
  // f_membrane written by a coupling drives the Poiseuille flow like `force` does.
  const double f = 2.0;
  auto profile = [=](double, double y, double) {
    return std::array<double, 3>{f / 2 * y * (1 - y), 0, 0};
  };
  FlowParameters p;
  p.walls = {{Side::bottom, WallKind::no_slip}, {Side::top, WallKind::no_slip},
             {Side::left, WallKind::prescribed, {}, profile},
             {Side::right, WallKind::prescribed, {}, profile}};
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(box_mesh({2, 1, 0}, {4, 2, 0}));
  compat::interpolate_vector(*flow.membrane_force(),
                             [=](double, double, double) { return std::array<double, 3>{f, 0, 0}; });
  flow.step(0.1);
  EXPECT_LT(max_nodal_error(*flow.velocity(), profile), 1e-10);
}

TEST(FlowPhysics, CapillaryForceGivesTheLaplacePressureJump)
{
  // A circle of radius R with the tanh profile (2.12) and mu = (1 - phi^2)/(sqrt2 R), the
  // CH potential -eps Lap phi + W'(phi)/eps at the interface. mu grad phi is then a radial
  // gradient: v = 0, and the pressure jumps by capillary * 2 sqrt2 / (3 R) across the
  // interface (int (1 - phi^2)^2 dr = 4 sqrt2 eps / 3). With capillary = 3 sigma/(2 sqrt2)
  // (section 2.8) this is Laplace's law sigma / R.
  const double R = 0.3, eps = 0.04, sigma = 1.0;
  auto mesh = box_mesh({1, 1, 0}, {32, 32, 0});
  auto V = compat::create_space(flow_forms(2).space, "phi", mesh);
  auto phi = std::make_shared<Function>(V), mu = std::make_shared<Function>(V);
  auto profile = [=](double x, double y)
  { return std::tanh((R - std::hypot(x - 0.5, y - 0.5)) / (std::sqrt(2.0) * eps)); };
  compat::interpolate(*phi, [&](double x, double y, double) { return profile(x, y); });
  compat::interpolate(*mu, [&](double x, double y, double)
                      { return (1 - std::pow(profile(x, y), 2)) / (std::sqrt(2.0) * R); });
  FlowParameters p;
  p.capillary = 3 * sigma / (2 * std::sqrt(2.0));
  p.walls = closed_box({});
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(mesh, phi, mu);
  flow.step(0.1);

  const double jump = nodal_value(*flow.pressure(), 0.5, 0.5) - nodal_value(*flow.pressure(), 0, 0);
  double vmax = 0;
  for (double v : flow.velocity()->x()->array())
    vmax = std::max(vmax, std::abs(v));
  std::printf("  Laplace: p_in - p_out = %.5f (sigma/R = %.5f), max |v| = %.2e\n", jump,
              sigma / R, vmax);
  // The jump is exact up to the interpolation of phi and mu (~ (h/eps)^3); 1% is loose.
  EXPECT_NEAR(jump, sigma / R, 0.01 * sigma / R);
  // Spurious currents: only the discrete force mu_h grad phi_h is not a gradient.
  EXPECT_LT(vmax, 1e-3 * sigma / R);
}
