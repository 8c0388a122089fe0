// solve/L2Projection onto vector P2 (forms/interface_force.py): the vector mass matrix of
// inner(u, w) dx is the scalar one per component, so only the scalar matrix is factorised
// and the components are solved as right-hand sides. With phi = a x + b y and mu in P2, the
// projected force capillary mu grad phi = capillary mu (a, b) lies in vector P2, so the
// projection reproduces it to round-off: both components, in their interleaved places, on a
// refined mesh (two cell sizes) and on two ranks (tests/CMakeLists.txt).
//
// On a domain periodic in x the projection of mu = eps Lap phi - W0'(phi) / eps (3.23), whose
// load holds the weak Laplacian, is the same at the periodic face as in the interior: the
// profile phi(x - 1/2) gives at x = 1/2 what phi(x) gives at x = 0.
#include "compat/Dolfinx.h"
#include "mpi_main.h"
#include "physics/FormTable.h"
#include "solve/L2Projection.h"
#include <cmath>
#include <cstdio>
#include <map>

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
  L2Projection projection(*compat::create_form(*forms.a, {Vf, Vf}, {}, {}), scene::Domain{},
                          MPI_COMM_WORLD, "test_projection_");
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

namespace
{
/// mu projected from phi = tanh(sin(2 pi (x - shift)) / 0.3) on the unit square, periodic
/// in x when `periodic` (12 x 6 cells, so that a shift by 1/2 maps the mesh onto itself).
std::shared_ptr<Function> projected_mu(double shift, bool periodic)
{
  scene::Domain d;
  d.dim = 2;
  d.upper = {1, 1, 0};
  d.resolution = {12, 6, 1};
  if (periodic)
    d.periodic = {0};
  auto mesh = compat::create_base_mesh(MPI_COMM_WORLD, d);
  auto V = compat::create_space(flow_forms(2).space, "phi", mesh);
  auto phi = std::make_shared<Function>(V);
  compat::interpolate(*phi, [&](double x, double, double)
                      { return std::tanh(std::sin(2 * M_PI * (x - shift)) / 0.3); });
  const ModelForms forms = model_forms(scene::Model::helfrich_penalty, 2);
  ConstantMap c{{"eps", std::make_shared<Constant>(0.1)}, {"H0", std::make_shared<Constant>(0.0)}};
  auto mu = std::make_shared<Function>(V);
  L2Projection(*compat::create_form(*forms.a_mu, {V, V}, {}, c), d, MPI_COMM_WORLD, "test_mu_")
      .project(*compat::create_form(*forms.L_mu, {V}, {{"phi_init", phi}}, c), *mu, "test mu");
  return mu;
}

/// The largest |u(x, y) - v(x + 1/2, y)| over the dofs at x = 0 (as values at the same y).
double face_against_middle(const Function& u, const Function& v)
{
  std::map<long, double> at_face, at_middle; // keyed by y in units of 1e-9
  auto collect = [](const Function& f, double x0, std::map<long, double>& out)
  {
    const auto xs = f.function_space()->tabulate_dof_coordinates(false);
    const auto values = f.x()->array();
    for (std::size_t i = 0; i < xs.size() / 3; ++i) // rows of 3
      if (std::abs(xs[3 * i] - x0) < 1e-9)
        out[std::lround(xs[3 * i + 1] * 1e9)] = values[i];
  };
  collect(u, 0.0, at_face);
  collect(v, 0.5, at_middle);
  // Gather both maps on every rank (a few dozen entries).
  auto gather = [](const std::map<long, double>& m)
  {
    std::vector<double> flat;
    for (auto [k, val] : m)
      flat.insert(flat.end(), {double(k), val});
    int n = flat.size(), size = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    std::vector<int> counts(size), offsets(size + 1, 0);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0; r < size; ++r)
      offsets[r + 1] = offsets[r] + counts[r];
    std::vector<double> all(offsets.back());
    MPI_Allgatherv(flat.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, MPI_COMM_WORLD);
    std::map<long, double> out;
    for (std::size_t i = 0; i < all.size(); i += 2)
      out[long(all[i])] = all[i + 1];
    return out;
  };
  at_face = gather(at_face);
  at_middle = gather(at_middle);
  EXPECT_EQ(at_face.size(), 13u); // P2: the 7 vertices and 6 edge midpoints of x = 0
  double diff = 0;
  for (auto [y, value] : at_face)
    diff = std::max(diff, std::abs(value - at_middle.at(y)));
  return diff;
}
} // namespace

TEST(L2Projection, PeriodicFaceIsLikeTheInterior)
{
  const auto mu = projected_mu(0.0, true), shifted = projected_mu(0.5, true);
  const auto mu_walled = projected_mu(0.0, false);
  double scale = 0;
  for (double v : mu->x()->array())
    scale = std::max(scale, std::abs(v));
  scale = global_max(scale);
  const double periodic = face_against_middle(*mu, *shifted);
  const double walled = face_against_middle(*mu_walled, *shifted);
  std::printf("max |mu| %.3g; face against middle: %.2e periodic, %.2e unconstrained\n", scale,
              periodic, walled);
  // The two projections solve the same equations up to the numbering: round-off.
  EXPECT_LT(periodic, 1e-10 * scale);
  // Without the constraint the face sees one side, as if it were a wall (grad phi . n = 0
  // in the weak Laplacian): an error of the size of mu itself.
  EXPECT_GT(walled, 0.1 * scale);
}
