// Field transfer between meshes refined differently from the same base mesh: a quadratic
// vector field (the velocity after a remesh) and a scalar one arrive exactly, since both
// lie in P2 on either mesh.
#include "compat/Dolfinx.h"
#include "compat/CellContains.h"
#include "compat/PointLocator.h"
#include "compat/PointWeights.h"
#include "mesh/FieldTransfer.h"
#include "mpi_main.h"
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <cmath>

using namespace cellphase;

namespace
{
std::array<double, 3> quadratic(double x, double y, double)
{
  return {1 + x * y - 0.5 * y * y, x * x - 2 * y, 0};
}

/// The base mesh refined once in the cells whose midpoint satisfies `where`.
std::shared_ptr<Mesh> refined(const scene::Domain& d, bool left)
{
  auto base = compat::create_base_mesh(MPI_COMM_WORLD, d);
  std::vector<std::int32_t> cells;
  for (std::int32_t c = 0; c < compat::num_owned_cells(*base); ++c)
  {
    auto x = compat::cell_vertex_coordinates(*base, c);
    const double mx = (x[0] + x[3] + x[6]) / 3;
    if ((mx < 0.5) == left)
      cells.push_back(c);
  }
  return compat::refine_cells(*base, cells);
}
} // namespace

TEST(Transfer, VectorAndScalarP2FieldsAreExact)
{
  scene::Domain d;
  d.resolution = {4, 4, 0};
  auto from_mesh = refined(d, true), to_mesh = refined(d, false);
  auto from = std::make_shared<Function>(create_vector_p2_space(from_mesh, 2));
  compat::interpolate_vector(*from, quadratic);
  Function to(create_vector_p2_space(to_mesh, 2));
  compat::transfer(from, to);
  Function exact(to.function_space());
  compat::interpolate_vector(exact, quadratic);
  auto a = to.x()->array(), b = exact.x()->array();
  ASSERT_EQ(a.size(), b.size());
  double err = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    err = std::max(err, std::abs(a[i] - b[i]));
  EXPECT_LT(err, 1e-12);

  // A scalar field takes the same path with one value per point.
  auto s = std::make_shared<Function>(create_p2_space(from_mesh, 2));
  compat::interpolate(*s, [](double x, double y, double) { return x * x + 3 * x * y; });
  Function t(create_p2_space(to_mesh, 2));
  compat::transfer(s, t);
  Function u(t.function_space());
  compat::interpolate(u, [](double x, double y, double) { return x * x + 3 * x * y; });
  double serr = 0;
  for (std::size_t i = 0; i < t.x()->array().size(); ++i)
    serr = std::max(serr, std::abs(t.x()->array()[i] - u.x()->array()[i]));
  EXPECT_LT(serr, 1e-12);

  // Different value sizes are refused.
  EXPECT_THROW(compat::transfer(s, to), std::invalid_argument);
}

// The weights of compat/PointWeights.h give Function::eval's values at fixed points: exact
// for a quadratic (scalar P2 in 2D and 3D, vector P2 in 2D), at points anywhere in a cell.
namespace
{
double max_weights_error(std::shared_ptr<Function> u, int dim)
{
  const Mesh& mesh = *u->function_space()->mesh();
  const int bs = u->function_space()->element()->value_size();
  std::vector<double> points;
  std::vector<std::int32_t> cells;
  unsigned seed = 7;
  auto random = [&]() { seed = seed * 1103515245u + 12345u; return double(seed % 1000) / 1000; };
  for (std::int32_t c = 0; c < compat::num_owned_cells(mesh); ++c)
  {
    const auto v = compat::cell_vertex_coordinates(mesh, c);
    std::vector<double> lam(dim + 1);
    double sum = 0;
    for (auto& l : lam)
      sum += (l = 0.1 + random());
    std::array<double, 3> p{0, 0, 0};
    for (int k = 0; k <= dim; ++k)
      for (int d = 0; d < 3; ++d)
        p[d] += lam[k] / sum * v[3 * k + d];
    points.insert(points.end(), p.begin(), p.end());
    cells.push_back(c);
  }
  cells.back() = -1; // a point without a cell keeps its value
  const std::size_t n = cells.size();
  std::vector<double> by_eval(n * bs, 0.0), by_weights(n * bs, 42.0);
  u->eval(points, {n, 3}, cells, by_eval, {n, std::size_t(bs)});
  EXPECT_TRUE(compat::PointWeights::applicable(*u->function_space()));
  compat::PointWeights(*u->function_space(), points, cells).eval(*u, by_weights);
  double err = 0;
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (int k = 0; k < bs; ++k)
      err = std::max(err, std::abs(by_eval[i * bs + k] - by_weights[i * bs + k]));
  EXPECT_EQ(by_weights[(n - 1) * bs], 42.0);
  return err;
}
} // namespace

TEST(Transfer, PointWeightsGiveTheValuesOfEval)
{
  scene::Domain d2;
  d2.resolution = {5, 4, 0};
  auto mesh2 = refined(d2, true);
  auto s = std::make_shared<Function>(create_p2_space(mesh2, 2));
  compat::interpolate(*s, [](double x, double y, double) { return x * x + 3 * x * y - y; });
  EXPECT_LT(max_weights_error(s, 2), 1e-13);
  auto v = std::make_shared<Function>(create_vector_p2_space(mesh2, 2));
  compat::interpolate_vector(*v, quadratic);
  EXPECT_LT(max_weights_error(v, 2), 1e-13);

  scene::Domain d3;
  d3.dim = 3;
  d3.upper = {1, 1, 1};
  d3.resolution = {3, 2, 2};
  auto mesh3 = compat::create_base_mesh(MPI_COMM_WORLD, d3);
  auto s3 = std::make_shared<Function>(create_p2_space(mesh3, 3));
  compat::interpolate(*s3, [](double x, double y, double z) { return x * z + y * y - 2 * z; });
  EXPECT_LT(max_weights_error(s3, 3), 1e-13);
}

namespace
{
/// Points where the choice of cell is delicate: every node of the mesh (on several cells),
/// midpoints of the cells' edges, points just outside the domain (by less and by more than
/// dolfinx's 1e-10) and points inside the cells. Returns how many CellContains placed in
/// another cell than dolfinx::geometry::compute_colliding_cells does.
int cells_chosen_differently(const Mesh& mesh)
{
  const int tdim = mesh.topology().dim();
  std::vector<double> pts;
  auto x = mesh.geometry().x();
  pts.insert(pts.end(), x.begin(), x.end());
  for (std::int32_t c = 0; c < compat::num_owned_cells(mesh); ++c)
  {
    auto v = mesh.geometry().dofmap().links(c);
    for (int d = 0; d < 3; ++d) // a point inside
      pts.push_back((x[3 * v[0] + d] + x[3 * v[1] + d] + 2 * x[3 * v[2] + d]) / 4);
    for (int d = 0; d < 3; ++d) // an edge's midpoint
      pts.push_back((x[3 * v[0] + d] + x[3 * v[1] + d]) / 2);
  }
  const std::size_t nodes = x.size() / 3;
  for (double shift : {0.4e-10, 0.9e-10, 1.1e-10, 1.9e-10, 2.1e-10, 5e-10})
    for (std::size_t k = 0; k < nodes; ++k)
      if (x[3 * k] == 0) // a node on the face x = 0, moved out of the domain
        pts.insert(pts.end(), {-shift, x[3 * k + 1] + 1e-3 * shift, x[3 * k + 2]});
  dolfinx::geometry::BoundingBoxTree tree(mesh, tdim, compat::detail::all_local_cells(mesh), 1e-10);
  auto candidates = dolfinx::geometry::compute_collisions(tree, pts);
  auto colliding = dolfinx::geometry::compute_colliding_cells(mesh, candidates, pts);
  const compat::detail::CellContains contains(mesh);
  int differ = 0, outside = 0;
  for (std::size_t i = 0; i < pts.size() / 3; ++i)
  {
    const std::int32_t theirs = colliding.num_links(i) ? colliding.links(i)[0] : -1;
    differ += contains.first(candidates.links(i), pts.data() + 3 * i) != theirs;
    outside += theirs < 0;
  }
  EXPECT_GT(outside, 0); // the test reaches the points beyond the tolerance
  return differ;
}
} // namespace

TEST(Transfer, CellContainsChoosesTheCellDolfinxChooses)
{
  scene::Domain d2;
  d2.resolution = {5, 4, 0};
  EXPECT_EQ(cells_chosen_differently(*refined(d2, true)), 0);
  scene::Domain d3;
  d3.dim = 3;
  d3.upper = {1, 1, 1};
  d3.resolution = {3, 2, 2};
  EXPECT_EQ(cells_chosen_differently(*compat::create_base_mesh(MPI_COMM_WORLD, d3)), 0);
}
