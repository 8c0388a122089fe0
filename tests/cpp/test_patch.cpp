// compat::create_patch on any number of ranks: a patch is the base mesh's cells as a mesh
// of their own, with every node once, however the base is partitioned. Run on 1 and on 2
// ranks (test_patch_mpi2), where the partition below puts a pinch on the rank boundary.
#include "compat/Patch.h"
#include "compat/PeriodicImages.h"
#include "mpi_main.h"
#include <basix/finite-element.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/generation.h>
#include <algorithm>
#include <functional>
#include <numeric>
#include <span>
#include <cmath>

using namespace cellphase;
using namespace dolfinx;

namespace
{
constexpr std::size_t n = 2; // the unit square in 2 x 2 squares of two triangles

/// Cells for which `on_rank_0` holds (given their P1 node numbers iy (nx + 1) + ix of
/// create_rectangle's input) go to rank 0, the others to the last rank. Every cell is
/// ghosted on every other rank, from which create_mesh finds the shared vertices (the base
/// mesh keeps no ghost cells).
graph::AdjacencyList<std::int32_t>
split_by(int parts, const graph::AdjacencyList<std::int64_t>& cells,
         const std::function<bool(std::span<const std::int64_t>)>& on_rank_0)
{
  std::vector<std::int32_t> dest, offsets{0};
  for (std::int32_t c = 0; c < cells.num_nodes(); ++c)
  {
    const int owner = on_rank_0(cells.links(c)) ? 0 : parts - 1;
    dest.push_back(owner);
    for (int r = 0; r < parts; ++r)
      if (r != owner)
        dest.push_back(r);
    offsets.push_back(std::int32_t(dest.size()));
  }
  return graph::AdjacencyList<std::int32_t>(std::move(dest), std::move(offsets));
}

/// The cells of the bottom-left square of the unit square on rank 0.
graph::AdjacencyList<std::int32_t> bottom_left_on_rank_0(MPI_Comm, int parts, int,
                                                        const graph::AdjacencyList<std::int64_t>& cells,
                                                        mesh::GhostMode)
{
  return split_by(parts, cells, [](std::span<const std::int64_t> nodes)
  {
    return std::all_of(nodes.begin(), nodes.end(), [](std::int64_t v)
                       { return std::size_t(v) % (n + 1) <= n / 2 && std::size_t(v) / (n + 1) <= n / 2; });
  });
}

/// The owned cells of `mesh` that have the node `at` and lie in the quadrant of their
/// midpoint's sign pattern `sx`, `sy` about it.
std::vector<std::int32_t> cells_at(const Mesh& mesh, std::array<double, 2> at, int sx, int sy)
{
  std::vector<std::int32_t> cells;
  for (std::int32_t c = 0; c < compat::num_owned_cells(mesh); ++c)
  {
    const auto x = compat::cell_vertex_coordinates(mesh, c);
    bool has = false;
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < x.size(); i += 3)
    {
      has = has || (std::abs(x[i] - at[0]) < 1e-12 && std::abs(x[i + 1] - at[1]) < 1e-12);
      mx += x[i] / 3, my += x[i + 1] / 3;
    }
    if (has && (mx - at[0]) * sx > 0 && (my - at[1]) * sy > 0)
      cells.push_back(c);
  }
  return cells;
}

/// The cells of the left half of a strip of nx squares in x on rank 0.
graph::AdjacencyList<std::int32_t> left_half_on_rank_0(int nx, int parts,
                                                      const graph::AdjacencyList<std::int64_t>& cells)
{
  return split_by(parts, cells, [nx](std::span<const std::int64_t> nodes)
  {
    return std::all_of(nodes.begin(), nodes.end(),
                       [nx](std::int64_t v) { return int(v % (nx + 1)) <= nx / 2; });
  });
}

std::int64_t global_vertices(const Mesh& m)
{
  return m.topology().index_map(0)->size_global();
}
} // namespace

// Two cells of the bottom-left square and two of the top-right one: the pairs meet at the
// centre only. On 2 ranks the pairs lie on different ranks, and the centre must still be
// one node (7 in all), or the patch would be cut in two there.
TEST(Patch, CellsMeetingAtAVertexOnlyShareIt)
{
  auto base = std::make_shared<Mesh>(mesh::create_rectangle(
      MPI_COMM_WORLD, {{{0, 0}, {1, 1}}}, {n, n}, mesh::CellType::triangle,
      mesh::GhostMode::none, bottom_left_on_rank_0));
  auto cells = cells_at(*base, {0.5, 0.5}, -1, -1);
  const auto top_right = cells_at(*base, {0.5, 0.5}, 1, 1);
  cells.insert(cells.end(), top_right.begin(), top_right.end());
  auto patch = compat::create_patch(*base, cells);
  EXPECT_EQ(patch->topology().index_map(2)->size_global(), 4);
  EXPECT_EQ(global_vertices(*patch), 7);
  // P1 on the patch: one dof per node, so a field is continuous through the pinch.
  auto p1 = basix::create_element(basix::element::family::P, basix::cell::type::triangle, 1,
                                  basix::element::lagrange_variant::equispaced, false);
  auto space = fem::create_functionspace(patch, p1, 1);
  EXPECT_EQ(space.dofmap()->index_map->size_global(), 7);
}

// A box reaching beyond the upper side of a periodic axis gives one piece across it: the
// base cells meeting the box's image a period down move up a period, and the nodes on the
// lower side are the upper side's. On 2 ranks the two sides' cells lie on different ranks.
TEST(Patch, BoxAcrossAPeriodicSideGivesAWrappedPatch)
{
  constexpr int nx = 8; // [0, 4] x [0, 1] in 8 x 2 squares: the period is 4
  auto base = std::make_shared<Mesh>(mesh::create_rectangle(
      MPI_COMM_WORLD, {{{0, 0}, {4, 1}}}, {nx, 2}, mesh::CellType::triangle, mesh::GhostMode::none,
      [](MPI_Comm, int parts, int, const graph::AdjacencyList<std::int64_t>& cells, mesh::GhostMode)
      { return left_half_on_rank_0(nx, parts, cells); }));
  compat::set_periods({4, 0, 0});
  // Columns [3, 4] and [0, 1] (moved to [4, 5]): 4 columns of 2 squares.
  auto patch = compat::create_patch(*base, compat::Box{3.2, 0, 0, 4.8, 1, 0});
  compat::set_periods({0, 0, 0});
  EXPECT_EQ(patch->topology().index_map(2)->size_global(), 16);
  EXPECT_EQ(global_vertices(*patch), 5 * 3); // x = 3, 3.5, 4, 4.5, 5: the side once
  const auto [lo, hi] = compat::bounding_box(*patch);
  EXPECT_NEAR(lo[0], 3, 1e-14);
  EXPECT_NEAR(hi[0], 5, 1e-14);
  // Its area: 2, each cell once.
  double area = 0;
  for (std::int32_t c = 0; c < compat::num_owned_cells(*patch); ++c)
  {
    const auto x = compat::cell_vertex_coordinates(*patch, c);
    area += std::abs((x[3] - x[0]) * (x[7] - x[1]) - (x[6] - x[0]) * (x[4] - x[1])) / 2;
  }
  MPI_Allreduce(MPI_IN_PLACE, &area, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_NEAR(area, 2, 1e-12);
}

// The whole base mesh as a patch has the base's nodes (on any partition).
TEST(Patch, AllCellsGiveTheBaseMesh)
{
  auto base = std::make_shared<Mesh>(mesh::create_rectangle(
      MPI_COMM_WORLD, {{{0, 0}, {1, 1}}}, {n, n}, mesh::CellType::triangle,
      mesh::GhostMode::none, bottom_left_on_rank_0));
  std::vector<std::int32_t> all(compat::num_owned_cells(*base));
  std::iota(all.begin(), all.end(), 0);
  auto patch = compat::create_patch(*base, all);
  EXPECT_EQ(global_vertices(*patch), global_vertices(*base));
  EXPECT_EQ(patch->topology().index_map(2)->size_global(), 8);
}

// redistribute deals the owned cells to the given ranks and keeps the mesh: its cells,
// its nodes (shared across the new rank boundary) and their coordinates.
TEST(Patch, RedistributeMovesCellsToTheirRanks)
{
  auto base = std::make_shared<Mesh>(mesh::create_rectangle(
      MPI_COMM_WORLD, {{{0, 0}, {1, 1}}}, {n, n}, mesh::CellType::triangle,
      mesh::GhostMode::none, bottom_left_on_rank_0));
  int size = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // The cells of the left half to the last rank, the others to rank 0.
  auto left = [](const Mesh& m, std::int32_t c)
  {
    const auto x = compat::cell_vertex_coordinates(m, c);
    return (x[0] + x[3] + x[6]) / 3 < 0.5;
  };
  std::vector<int> dest(compat::num_owned_cells(*base));
  for (std::int32_t c = 0; c < std::int32_t(dest.size()); ++c)
    dest[c] = left(*base, c) ? size - 1 : 0;
  auto moved = compat::redistribute(*base, dest);
  for (std::int32_t c = 0; c < compat::num_owned_cells(*moved); ++c)
    EXPECT_EQ(left(*moved, c) ? size - 1 : 0, rank);
  EXPECT_EQ(moved->topology().index_map(2)->size_global(), 8);
  EXPECT_EQ(global_vertices(*moved), 9);
  // The same cells: the sums of their midpoints' coordinates over all ranks agree.
  auto midpoint_sum = [](const Mesh& m)
  {
    std::array<double, 2> s{0, 0};
    for (std::int32_t c = 0; c < compat::num_owned_cells(m); ++c)
    {
      const auto x = compat::cell_vertex_coordinates(m, c);
      s[0] += (x[0] + x[3] + x[6]) / 3, s[1] += (x[1] + x[4] + x[7]) / 3;
    }
    MPI_Allreduce(MPI_IN_PLACE, s.data(), 2, MPI_DOUBLE, MPI_SUM, m.comm());
    return s;
  };
  const auto before = midpoint_sum(*base), after = midpoint_sum(*moved);
  EXPECT_NEAR(after[0], before[0], 1e-14);
  EXPECT_NEAR(after[1], before[1], 1e-14);
}
