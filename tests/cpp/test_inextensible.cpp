// The inextensibility constraint of section 3.4.3 (forms/flow_inextensible.py) on fixed
// meshes:
// * the coupled (v, p, lambda) system converges at the rates of its P2/P1/P1 spaces on a
//   manufactured solution with a fixed phase field, its source written from the strong
//   form (tests/forms/mms_inextensible.py);
// * the union phase field (7.14) is the pointwise maximum.
#include "compat/Dolfinx.h"
#include "mms_inextensible.h"
#include "mpi_main.h"
#include "physics/FlowModule.h"
#include "physics/UnionPhaseField.h"
#include <cmath>
#include <cstdio>
#include <numbers>

using namespace cellphase;
namespace
{
constexpr double pi = std::numbers::pi;
constexpr double eps = 0.05;

std::shared_ptr<Mesh> unit_square(int n)
{
  scene::Domain d;
  d.dim = 2;
  d.upper = {1, 1, 0};
  d.resolution = {n, n, 0};
  return compat::create_base_mesh(MPI_COMM_WORLD, d);
}

/// A tanh profile (2.12) across the ellipse with semi-axes 0.36 x 0.24 around (0.5, 0.5):
/// q is about the signed distance near the interface, smooth everywhere.
double ellipse_phase(double x, double y, double)
{
  const double q = (0.09 - std::pow((x - 0.5) / 1.2, 2) - std::pow((y - 0.5) / 0.8, 2)) / 0.6;
  return std::tanh(q / (std::sqrt(2.0) * eps));
}

FlowForms mms_forms()
{
  FlowForms f;
  f.a = form_mms_inextensible_a;
  f.L = form_mms_inextensible_L_mms;
  f.kinetic_energy = form_mms_inextensible_kinetic_energy;
  f.divergence_sq = form_mms_inextensible_divergence_sq;
  f.phase_weight = form_mms_inextensible_phase_weight;
  f.phase_velocity = {form_mms_inextensible_phase_velocity_0,
                      form_mms_inextensible_phase_velocity_1, nullptr};
  f.pressure_integral = form_mms_inextensible_pressure_integral;
  f.domain_volume = form_mms_inextensible_domain_volume;
  f.space = functionspace_form_mms_inextensible_a;
  f.has_multiplier = true;
  f.membrane_delta = form_mms_inextensible_membrane_delta;
  f.energy_ch = form_mms_inextensible_energy_ch;
  f.lambda_dissipation = form_mms_inextensible_lambda_dissipation;
  f.lambda_membrane = form_mms_inextensible_lambda_membrane;
  return f;
}

FlowParameters stokes_in_closed_box()
{
  FlowParameters p;
  p.Re = 0;
  for (int s = 0; s < 4; ++s)
    p.walls.push_back({Side(s), WallKind::no_slip});
  p.inextensibility.enabled = true;
  p.inextensibility.xi = 1;
  p.inextensibility.epsilon = eps;
  return p;
}

struct Errors
{
  double v, p, lambda;
};

Errors solve_mms(int n)
{
  auto mesh = unit_square(n);
  auto phi = std::make_shared<Function>(
      compat::create_space(functionspace_form_mms_inextensible_a, "phi", mesh));
  compat::interpolate(*phi, ellipse_phase);
  FlowModule flow(stokes_in_closed_box(), MPI_COMM_WORLD, mms_forms());
  flow.attach(mesh, phi);
  flow.step(1.0);
  CoefficientMap c{{"v0", flow.velocity()}, {"p_h", flow.pressure()}, {"lam_h", flow.multiplier()}};
  auto error = [&](const ufcx_form* f)
  { return std::sqrt(compat::assemble_scalar(*compat::create_form(*f, {}, c, ConstantMap{}, mesh))); };
  return {error(form_mms_inextensible_error_v), error(form_mms_inextensible_error_p),
          error(form_mms_inextensible_error_lam)};
}
} // namespace

TEST(InextensibleManufactured, VelocityPressureAndMultiplierConvergeAtTheirRates)
{
  // The interface (width ~4 eps = 0.2) gets 6 to 26 cells across on these meshes: every
  // pair is in the asymptotic range.
  std::vector<int> ns{32, 64, 128};
  std::vector<Errors> e;
  for (int n : ns)
    e.push_back(solve_mms(n));
  for (std::size_t i = 0; i < ns.size(); ++i)
  {
    std::printf("  n = %3d: |e_v| = %.3e, |e_p| = %.3e, |e_lambda| = %.3e", ns[i], e[i].v, e[i].p,
                e[i].lambda);
    if (i > 0)
      std::printf("  (rates %.2f, %.2f, %.2f)", std::log2(e[i - 1].v / e[i].v),
                  std::log2(e[i - 1].p / e[i].p), std::log2(e[i - 1].lambda / e[i].lambda));
    std::printf("\n");
  }
  // L2 rates of the spaces: P2 velocity 3, P1 pressure 2, P1 multiplier 2, asserted on
  // every pair to 0.3 below (the source is the strong form, so a wrong or missing term of
  // (3.67)-(3.68) in the weak form leaves an O(1) error and the rates fall to about 0).
  for (std::size_t i = 1; i < ns.size(); ++i)
  {
    EXPECT_GT(std::log2(e[i - 1].v / e[i].v), 2.7) << "n = " << ns[i];
    EXPECT_GT(std::log2(e[i - 1].p / e[i].p), 1.7) << "n = " << ns[i];
    EXPECT_GT(std::log2(e[i - 1].lambda / e[i].lambda), 1.7) << "n = " << ns[i];
  }
}

TEST(UnionPhaseField, IsThePointwiseMaximumAndOneFieldIsItself)
{
  auto mesh = unit_square(4);
  auto V = compat::create_space(functionspace_form_mms_inextensible_a, "phi", mesh);
  auto a = std::make_shared<Function>(V), b = std::make_shared<Function>(V);
  compat::interpolate(*a, [](double x, double, double) { return 2 * x - 1; });
  compat::interpolate(*b, [](double, double y, double) { return 1 - 2 * y; });
  EXPECT_EQ(union_phase_field({a}), a);
  auto u = union_phase_field({a, b});
  auto ua = u->x()->array(), xa = a->x()->array(), xb = b->x()->array();
  for (std::size_t i = 0; i < ua.size(); ++i)
    EXPECT_EQ(ua[i], std::max(xa[i], xb[i]));
}
