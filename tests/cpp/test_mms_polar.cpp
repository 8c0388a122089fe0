// Manufactured solution on fixed uniform meshes for the orientation-field step of
// forms/polar_gel.py (6.16)-(6.17), vector P2 for P and P#: one step from the exact state
// with the source of tests/forms/mms_polar_gel.py (the step of P with P# eliminated, then
// P# projected from the new P, as the program does) must give errors falling at the P2
// mixed method's rates (P in L2 order 3, P# in L2 order 2 at least: it holds the Laplacian
// of P). With the stabilisation S (P#^{n+1} - P#^n) the step stays consistent (P#^n exact).
#include "compat/Dolfinx.h"
#include "mms_polar_gel.h"
#include "mpi_main.h"
#include "solve/Assemble.h"
#include "solve/L2Projection.h"
#include "solve/LinearSolver.h"
#include <cmath>
#include <numbers>

using namespace cellphase;
namespace
{
constexpr double pi = std::numbers::pi;
constexpr double Pa = 0.7, c1 = 5, beta = 0.3, xi = 1.1, kappa = 1.65;

std::array<double, 3> P_ex(double x, double y)
{
  return {0.8 * std::cos(pi * x) * std::cos(pi * y), 0.6 * std::cos(2 * pi * x) * std::cos(pi * y), 0};
}

/// (6.17) of P_ex by hand: Lap P = (-2 pi^2 P_x, -5 pi^2 P_y).
std::array<double, 3> Psharp_ex(double x, double y)
{
  const auto P = P_ex(x, y);
  const double phi = 0.9 * std::cos(pi * x) * std::cos(pi * y);
  const double gx = -0.9 * pi * std::sin(pi * x) * std::cos(pi * y);
  const double gy = -0.9 * pi * std::cos(pi * x) * std::sin(pi * y);
  const double P2 = P[0] * P[0] + P[1] * P[1];
  return {(2 * pi * pi * P[0] + c1 * P2 * P[0] - c1 * phi * P[0] + beta * gx) / Pa,
          (5 * pi * pi * P[1] + c1 * P2 * P[1] - c1 * phi * P[1] + beta * gy) / Pa, 0};
}

struct Errors
{
  double P, Ps;
};

/// u <- the solution of a u = L (fixed mesh, natural boundary conditions only).
void solve_linear(std::shared_ptr<const Form> a, const Form& L, Function& u)
{
  auto A = create_matrix(*a);
  assemble_matrix(A->mat(), *a, {});
  dolfinx::la::Vector<T> b(u.function_space()->dofmap()->index_map,
                           u.function_space()->dofmap()->index_map_bs());
  assemble_rhs(b, L, a, {});
  LinearSolver solver(MPI_COMM_WORLD, "mms_", {});
  solver.set_operator(A->mat());
  solver.solve(b, *u.x(), "mms P");
}

Errors solve_mms(int n, double S)
{
  scene::Domain d;
  d.resolution = {n, n, 0};
  auto mesh = compat::create_base_mesh(MPI_COMM_WORLD, d);
  auto V = compat::create_space(functionspace_form_mms_polar_gel_a, "Pi", mesh);
  auto P0 = std::make_shared<Function>(V), Ps0 = std::make_shared<Function>(V);
  compat::interpolate_vector(*Ps0, [](double x, double y, double) { return Psharp_ex(x, y); });
  compat::interpolate_vector(*P0, [](double x, double y, double) { return P_ex(x, y); });
  auto phi = std::make_shared<Function>(compat::create_space(functionspace_form_mms_polar_gel_a, "phi", mesh));
  compat::interpolate(*phi, [](double x, double y, double) { return 0.9 * std::cos(pi * x) * std::cos(pi * y); });
  auto v = std::make_shared<Function>(compat::create_space(functionspace_form_mms_polar_gel_a, "v", mesh));
  compat::interpolate_vector(*v, [](double x, double y, double)
  {
    return std::array<double, 3>{std::sin(pi * x) * std::cos(pi * y) / 2,
                                 -std::cos(pi * x) * std::sin(pi * y) / 2, 0};
  });
  ConstantMap c;
  for (auto [k, val] : std::map<std::string, double>{{"dt", 0.1}, {"Pa", Pa}, {"c1", c1},
                                                     {"beta", beta}, {"xi", xi}, {"kappa", kappa},
                                                     {"activity", 0.0}, {"S", S}})
    c[k] = std::make_shared<Constant>(val);
  auto uh = std::make_shared<Function>(V), Psh = std::make_shared<Function>(V);
  const CoefficientMap coeffs{{"Pi", P0}, {"Psi", Ps0}, {"phi", phi}, {"v", v}, {"uh", uh}, {"Psh", Psh}};
  solve_linear(compat::create_form(*form_mms_polar_gel_a, {V, V}, coeffs, c),
               *compat::create_form(*form_mms_polar_gel_L_mms, {V}, coeffs, c), *uh);
  // P# of the new P as the program makes it (PolarGelSubProblem::project_sharp).
  L2Projection(*compat::create_form(*form_mms_polar_gel_mass, {V, V}, coeffs, c), scene::Domain{}, MPI_COMM_WORLD,
               "mms_sharp_")
      .project(*compat::create_form(*form_mms_polar_gel_L_sharp_h, {V}, coeffs, c), *Psh, "mms P#");
  auto eP = compat::create_form(*form_mms_polar_gel_error_P, {}, coeffs, c, mesh);
  auto eS = compat::create_form(*form_mms_polar_gel_error_Ps, {}, coeffs, c, mesh);
  return {std::sqrt(compat::assemble_scalar(*eP)), std::sqrt(compat::assemble_scalar(*eS))};
}

void check_orders(double S)
{
  std::vector<int> ns{8, 16, 32};
  std::vector<Errors> e;
  for (int n : ns)
    e.push_back(solve_mms(n, S));
  for (std::size_t i = 1; i < ns.size(); ++i)
  {
    const double rate_P = std::log2(e[i - 1].P / e[i].P);
    const double rate_Ps = std::log2(e[i - 1].Ps / e[i].Ps);
    std::printf("  S = %g, n = %3d: |e_P| = %.3e (rate %.2f), |e_P#| = %.3e (rate %.2f)\n", S,
                ns[i], e[i].P, rate_P, e[i].Ps, rate_Ps);
    // 0.2 below the asymptotic rates (3 for P; 2 for P#, which carries Lap P) allows
    // pre-asymptotic effects on the coarse meshes.
    EXPECT_GT(rate_P, 2.8);
    EXPECT_GT(rate_Ps, 1.8);
  }
}
} // namespace

TEST(ManufacturedSolution, OrientationFieldConvergesAtP2Rates) { check_orders(0.0); }
TEST(ManufacturedSolution, StabilisedOrientationFieldConvergesAtP2Rates) { check_orders(2.0); }
