// Manufactured solutions on fixed uniform meshes for the split operators of
// forms/helfrich_l2.py (3.27)+(3.23) and forms/cahn_hilliard.py (2.25), P2 elements.
// One step of the Taylor-linearised scheme from the exact state with a source that makes
// the exact state steady; the errors must fall at the rates of the P2 mixed method:
//   phi and mu in L2: order 3 (P2 optimal; seen: 3.00 and 2.99 from n = 16 to 32).
#include "compat/Dolfinx.h"
#include "mms_cahn_hilliard.h"
#include "mms_helfrich.h"
#include "mpi_main.h"
#include "solve/LinearSolver.h"
#include <cmath>
#include <numbers>

using namespace cellphase;
namespace
{
constexpr double pi = std::numbers::pi;
constexpr double eps = 0.5, H0 = 0.3, gamma_ = 1.0, Be = 2.0;

struct Errors
{
  double phi, mu;
};

Errors solve_mms(int n, bool helfrich)
{
  scene::Domain d;
  d.resolution = {n, n, 0};
  auto mesh = compat::create_base_mesh(MPI_COMM_WORLD, d);
  auto W = compat::create_space(helfrich ? functionspace_form_mms_helfrich_a
                                         : functionspace_form_mms_cahn_hilliard_a,
                                "v_0", mesh);
  auto u0 = std::make_shared<Function>(W);
  auto phi_ex = [](double x, double y, double) { return std::cos(pi * x) * std::cos(pi * y); };
  auto mu_ex = [&](double x, double y, double z)
  {
    const double p = phi_ex(x, y, z), lap = -2 * pi * pi * p;
    return helfrich ? eps * lap - (p * p - 1) * (p + std::sqrt(2.0) * H0 * eps) / eps
                    : -eps * lap + (p * p - 1) * p / eps;
  };
  auto sub0 = u0->sub(0), sub1 = u0->sub(1);
  compat::interpolate(sub0, phi_ex);
  compat::interpolate(sub1, mu_ex);

  ConstantMap c;
  for (auto [k, v] : std::map<std::string, double>{{"dt", 0.1}, {"eps", eps}, {"gamma", gamma_},
                                                   {"Be", Be}, {"H0", H0}, {"S", 2.0},
                                                   {"lam_v", 0.0}, {"lam_a", 0.0},
                                                   // no surface tension, constant mobility,
                                                   // natural condition at the walls
                                                   {"sigma", 0.0}, {"degenerate", 0.0},
                                                   {"cos_theta", 0.0},
                                                   // the Taylor rows, unscaled
                                                   {"row_psi", 1.0},
                                                   // phi advected (the shared mesh)
                                                   {"own_mesh", 0.0}})
    c[k] = std::make_shared<Constant>(v);
  // No flow: the advection velocity is zero.
  auto v = std::make_shared<Function>(
      compat::create_space(helfrich ? functionspace_form_mms_helfrich_a
                                    : functionspace_form_mms_cahn_hilliard_a,
                           "v", mesh));
  v->x()->set(0.0);
  CoefficientMap coeffs{{"u0", u0}, {"v", v}};
  auto a = compat::create_form(helfrich ? *form_mms_helfrich_a : *form_mms_cahn_hilliard_a,
                               {W, W}, coeffs, c);
  auto L = compat::create_form(helfrich ? *form_mms_helfrich_L_mms : *form_mms_cahn_hilliard_L_mms,
                               {W}, coeffs, c);
  dolfinx::la::petsc::Matrix A(dolfinx::fem::petsc::create_matrix(*a), false);
  MatZeroEntries(A.mat());
  dolfinx::fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(A.mat(), ADD_VALUES), *a, {});
  MatAssemblyBegin(A.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FINAL_ASSEMBLY);
  dolfinx::la::Vector<T> b(W->dofmap()->index_map, 1);
  b.set(0);
  dolfinx::fem::assemble_vector(b.mutable_array(), *L);
  b.scatter_rev(std::plus<T>());
  auto uh = std::make_shared<Function>(W);
  LinearSolver solver(MPI_COMM_WORLD, "mms_", {});
  solver.set_operator(A.mat());
  solver.solve(b, *uh->x(), "mms");

  auto ep = compat::create_form(helfrich ? *form_mms_helfrich_error_phi : *form_mms_cahn_hilliard_error_phi,
                                {}, {{"uh", uh}}, c, mesh);
  auto em = compat::create_form(helfrich ? *form_mms_helfrich_error_mu : *form_mms_cahn_hilliard_error_mu,
                                {}, {{"uh", uh}}, c, mesh);
  return {std::sqrt(compat::assemble_scalar(*ep)), std::sqrt(compat::assemble_scalar(*em))};
}

void check_orders(bool helfrich)
{
  std::vector<int> ns{8, 16, 32};
  std::vector<Errors> e;
  for (int n : ns)
    e.push_back(solve_mms(n, helfrich));
  for (std::size_t i = 1; i < ns.size(); ++i)
  {
    const double rate_phi = std::log2(e[i - 1].phi / e[i].phi);
    const double rate_mu = std::log2(e[i - 1].mu / e[i].mu);
    std::printf("  n = %3d: |e_phi| = %.3e (rate %.2f), |e_mu| = %.3e (rate %.2f)\n", ns[i],
                e[i].phi, rate_phi, e[i].mu, rate_mu);
    // Tolerance 0.2 below the asymptotic rate 3 allows pre-asymptotic effects on the
    // coarse meshes (8..32 cells per unit length).
    EXPECT_GT(rate_phi, 2.8);
    EXPECT_GT(rate_mu, 2.8);
  }
}
} // namespace

TEST(ManufacturedSolution, HelfrichSplitOperatorConvergesAtP2Rates) { check_orders(true); }
TEST(ManufacturedSolution, CahnHilliardConvergesAtP2Rates) { check_orders(false); }
