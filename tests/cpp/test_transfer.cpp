// Field transfer between meshes refined differently from the same base mesh: a quadratic
// vector field (the velocity after a remesh) and a scalar one arrive exactly, since both
// lie in P2 on either mesh.
#include "compat/Dolfinx.h"
#include "mesh/FieldTransfer.h"
#include "mpi_main.h"
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
