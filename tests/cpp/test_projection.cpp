// solve/L2Projection onto vector P2 (forms/interface_force.py): the vector mass matrix of
// inner(u, w) dx is the scalar one per component, so only the scalar matrix is factorised
// and the components are solved as right-hand sides. With phi = a x + b y and mu in P2, the
// projected force capillary mu grad phi = capillary mu (a, b) lies in vector P2, so the
// projection reproduces it to round-off: both components, in their interleaved places, on a
// refined mesh (two cell sizes) and on two ranks (tests/CMakeLists.txt).
#include "compat/Dolfinx.h"
#include "mpi_main.h"
#include "physics/FormTable.h"
#include "solve/L2Projection.h"
#include <cmath>

using namespace cellphase;
namespace
{
std::shared_ptr<Mesh> refined_box()
{
  scene::Domain d;
  d.dim = 2;
  d.upper = {2, 1, 0};
  d.resolution = {12, 6, 1};
  auto mesh = compat::create_base_mesh(MPI_COMM_WORLD, d);
  std::vector<std::int32_t> left; // the cells left of x = 0.8 once more
  for (std::int32_t c = 0; c < compat::num_owned_cells(*mesh); ++c)
    if (compat::cell_centroid(*mesh, c)[0] < 0.8)
      left.push_back(c);
  return compat::refine_cells(*mesh, left);
}

double global_max(double v)
{
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return v;
}
} // namespace

TEST(L2Projection, VectorForceSolvedComponentwiseIsExact)
{
  auto mesh = refined_box();
  auto Vf = compat::create_space(flow_forms(2).space, "v0", mesh);
  auto V = compat::create_space(flow_forms(2).space, "phi", mesh);
  auto phi = std::make_shared<Function>(V), mu = std::make_shared<Function>(V);
  const double a = 0.7, b = -1.3, capillary = 2.5;
  compat::interpolate(*phi, [&](double x, double y, double) { return a * x + b * y; });
  auto g = [](double x, double y) { return 1 + x * x - 0.5 * x * y + 0.25 * y * y; }; // in P2
  compat::interpolate(*mu, [&](double x, double y, double) { return g(x, y); });

  const InterfaceForceForms forms = interface_force_forms(2);
  ConstantMap constants{{"capillary", std::make_shared<Constant>(capillary)}};
  auto L = compat::create_form(*forms.L, {Vf}, {{"phi", phi}, {"mu", mu}}, constants);
  L2Projection projection(*compat::create_form(*forms.a, {Vf, Vf}, {}, {}), MPI_COMM_WORLD,
                          "test_projection_");
  EXPECT_EQ(projection.components(), 2);

  Function force(Vf);
  projection.project(*L, force, "the test force");
  Function exact(Vf);
  compat::interpolate_vector(exact, [&](double x, double y, double) -> std::array<double, 3>
                             { return {capillary * a * g(x, y), capillary * b * g(x, y), 0}; });
  // Owned and ghost entries: the ghosts come from the owners' solution (scatter_fwd).
  auto u = force.x()->array(), e = exact.x()->array();
  double error = 0, scale = 0;
  for (std::size_t i = 0; i < u.size(); ++i)
  {
    error = std::max(error, std::abs(u[i] - e[i]));
    scale = std::max(scale, std::abs(e[i]));
  }
  // Round-off of a mass-matrix solve (condition number ~ 100 for P2 on two cell sizes).
  EXPECT_LT(global_max(error), 1e-12 * global_max(scale));
}
