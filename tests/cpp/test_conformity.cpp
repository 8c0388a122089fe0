// compat::refine_cells stops on a refinement that is not conforming across the MPI ranks
// (DOLFINx 0.5.2 leaves hanging vertices on some partitions), and passes the default one.
#include "compat/Conformity.h"
#include "compat/Dolfinx.h"
#include "mpi_main.h"
#include <cmath>

using namespace cellphase;

namespace
{
constexpr int N = 26;              // squares per side of [-4, 6] x [-5, 5]
constexpr double X0 = -4, Y0 = -5, H = 10.0 / N;

/// The crossed grid (four triangles per square, around its centre) on rank 0; x_cut >= 0:
/// cells left of x = x_cut on rank 0, the others on the last rank, else the default
/// graph partitioner.
Mesh crossed_grid(MPI_Comm comm, double x_cut)
{
  std::vector<double> x;
  std::vector<std::int64_t> cells;
  if (dolfinx::MPI::rank(comm) == 0)
  {
    for (int j = 0; j <= N; ++j)
      for (int i = 0; i <= N; ++i)
        x.insert(x.end(), {X0 + i * H, Y0 + j * H});
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        const std::int64_t c = (N + 1) * (N + 1) + j * N + i;
        x.insert(x.end(), {X0 + (i + 0.5) * H, Y0 + (j + 0.5) * H});
        const std::int64_t v00 = j * (N + 1) + i, v10 = v00 + 1, v01 = v00 + N + 1,
                           v11 = v01 + 1;
        cells.insert(cells.end(), {v00, v10, c, v10, v11, c, v11, v01, c, v01, v00, c});
      }
  }
  std::vector<std::int32_t> offsets(cells.size() / 3 + 1);
  for (std::size_t i = 0; i < offsets.size(); ++i)
    offsets[i] = std::int32_t(3 * i);
  dolfinx::graph::AdjacencyList<std::int64_t> topology(cells, offsets);
  const dolfinx::fem::CoordinateElement element(dolfinx::mesh::CellType::triangle, 1);
  const std::array<std::size_t, 2> shape{x.size() / 2, 2};
  if (x_cut < 0)
    return dolfinx::mesh::create_mesh(comm, topology, element, x, shape,
                                      dolfinx::mesh::GhostMode::none);
  auto strips = [&x, x_cut](MPI_Comm, int parts, int,
                            const dolfinx::graph::AdjacencyList<std::int64_t>& cs,
                            dolfinx::mesh::GhostMode)
  {
    std::vector<std::int32_t> dest, off{0};
    for (std::int32_t c = 0; c < cs.num_nodes(); ++c)
    {
      double cx = 0;
      for (auto v : cs.links(c))
        cx += x[2 * v] / 3;
      dest.push_back(cx < x_cut ? 0 : parts - 1);
      off.push_back(off.back() + 1);
    }
    return dolfinx::graph::AdjacencyList<std::int32_t>(std::move(dest), std::move(off));
  };
  return dolfinx::mesh::create_mesh(comm, topology, element, x, shape,
                                    dolfinx::mesh::GhostMode::none, strips);
}

/// Refine four times the cells that a band of half-width 0.1 around the unit circle
/// touches (as the adaptive mesh does around an interface).
std::shared_ptr<Mesh> refine_around_circle(std::shared_ptr<Mesh> mesh)
{
  for (int level = 0; level < 4; ++level)
  {
    std::vector<std::int32_t> marked;
    for (std::int32_t c = 0; c < compat::num_owned_cells(*mesh); ++c)
    {
      const auto v = compat::cell_vertex_coordinates(*mesh, c);
      double lo = 1e300, hi = -1e300;
      for (int k = 0; k < 3; ++k)
      {
        const double d = std::hypot(v[3 * k], v[3 * k + 1]) - 1;
        lo = std::min(lo, d), hi = std::max(hi, d);
      }
      if (lo < 0.1 && hi > -0.1)
        marked.push_back(c);
    }
    mesh = compat::refine_cells(*mesh, marked);
  }
  return mesh;
}
} // namespace

TEST(Conformity, DefaultPartitionRefinesConformingly)
{
  auto mesh = refine_around_circle(std::make_shared<Mesh>(crossed_grid(MPI_COMM_WORLD, -1)));
  EXPECT_EQ(compat::hanging_vertices(*mesh), 0);
}

TEST(Conformity, StripPartitionAcrossTheBandIsRefused)
{
  if (dolfinx::MPI::size(MPI_COMM_WORLD) < 2)
    GTEST_SKIP() << "needs two ranks (ctest conformity_mpi2)";
  auto base = std::make_shared<Mesh>(crossed_grid(MPI_COMM_WORLD, 0.23));
  try
  {
    refine_around_circle(base);
    FAIL() << "a strip partition cutting the band obliquely refined without hanging vertices";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("not conforming across the MPI ranks"),
              std::string::npos)
        << e.what();
  }
}
