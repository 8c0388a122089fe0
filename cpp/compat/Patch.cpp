#include "compat/Patch.h"
#include "compat/AllToAll.h"
#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace cellphase::compat
{
using namespace dolfinx;

namespace
{
/// Owned cells of `base` whose vertices' bounding box meets `box`.
std::vector<std::int32_t> cells_meeting(const Mesh& base, const Box& box)
{
  std::vector<std::int32_t> cells;
  for (std::int32_t c = 0; c < num_owned_cells(base); ++c)
  {
    const auto v = cell_vertex_coordinates(base, c);
    bool meets = true;
    for (int d = 0; d < 3 && meets; ++d)
    {
      double lo = 1e300, hi = -1e300;
      for (std::size_t i = d; i < v.size(); i += 3)
        lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
      meets = hi >= box[d] && lo <= box[3 + d];
    }
    if (meets)
      cells.push_back(c);
  }
  return cells;
}

void add_once(std::vector<int>& ranks, int r)
{
  if (std::find(ranks.begin(), ranks.end(), r) == ranks.end())
    ranks.push_back(r);
}

/// For each of `cells` (owned cells of `base`) going to rank dest[i] of a new mesh: the
/// other ranks of the new mesh with cells at one of its vertices, which must ghost it.
/// create_mesh of DOLFINx 0.5.2 finds the vertices shared between ranks only where owned
/// and ghost cells meet, so every rank with cells at a vertex needs a ghost cell at it
/// from every other such rank. Facet neighbours are not enough: at a pinch (cells that
/// meet at a vertex only) the vertex would be made twice. The base mesh has no ghost
/// cells: the owner of each shared base vertex collects the destinations of the cells at
/// it from the ranks that hold such cells, and tells those ranks.
std::vector<std::vector<int>> ghost_ranks(const Mesh& base, std::span<const std::int32_t> cells,
                                          std::span<const int> dest)
{
  const MPI_Comm comm = base.comm();
  int size = 1;
  MPI_Comm_size(comm, &size);
  const auto c2v = base.topology().connectivity(base.topology().dim(), 0);
  const auto vertices = base.topology().index_map(0);
  const std::int32_t owned = vertices->size_local();
  const std::int64_t first = vertices->local_range()[0];
  const auto& ghosts = vertices->ghosts();
  const auto& ghost_owners = vertices->owners();

  // at[v]: the destinations of the cells at vertex v.
  std::vector<std::vector<int>> at(owned + ghosts.size());
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (auto v : c2v->links(cells[i]))
      add_once(at[v], dest[i]);

  // Ghost copies send (vertex, destination) to their owners, which then know them all.
  std::vector<std::vector<std::int64_t>> to_owner(size);
  for (std::size_t i = 0; i < ghosts.size(); ++i)
    for (int d : at[owned + i])
      to_owner[ghost_owners[i]].insert(to_owner[ghost_owners[i]].end(), {ghosts[i], std::int64_t(d)});
  const auto told = detail::all_to_all(comm, to_owner);
  std::vector<std::vector<int>> holders(owned); // other ranks with cells at the vertex
  for (int r = 0; r < size; ++r)
    for (std::size_t k = 0; k < told[r].size(); k += 2)
    {
      const auto v = std::int32_t(told[r][k] - first);
      add_once(at[v], int(told[r][k + 1]));
      add_once(holders[v], r);
    }

  // The owners send them back to the ranks that hold cells at the vertex.
  std::vector<std::vector<std::int64_t>> to_holder(size);
  for (std::int32_t v = 0; v < owned; ++v)
    if (at[v].size() > 1)
      for (int r : holders[v])
        for (int d : at[v])
          to_holder[r].insert(to_holder[r].end(), {first + v, std::int64_t(d)});
  const auto back = detail::all_to_all(comm, to_holder);
  std::vector<std::int64_t> global;
  std::vector<int> from;
  for (int r = 0; r < size; ++r)
    for (std::size_t k = 0; k < back[r].size(); k += 2)
      global.push_back(back[r][k]), from.push_back(int(back[r][k + 1]));
  std::vector<std::int32_t> local(global.size());
  vertices->global_to_local(global, local);
  for (std::size_t k = 0; k < global.size(); ++k)
    add_once(at[local[k]], from[k]);

  std::vector<std::vector<int>> ranks(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (auto v : c2v->links(cells[i]))
      for (int d : at[v])
        if (d != dest[i])
          add_once(ranks[i], d);
  return ranks;
}

/// `cells` (owned cells of `base`) as a mesh of their own, cell i on rank dest[i].
std::shared_ptr<Mesh> mesh_of_cells(const Mesh& base, std::span<const std::int32_t> cells,
                                    std::span<const int> dest)
{
  const auto ghosts = ghost_ranks(base, cells, dest);

  // The cells by the base geometry's global node numbers, and the coordinates of the
  // nodes this rank owns (create_mesh reads node i from the rank whose block holds it).
  const auto& geometry = base.geometry();
  const auto& dofmap = geometry.dofmap();
  auto node_map = geometry.index_map();
  const int gdim = geometry.dim();
  std::vector<std::int64_t> nodes;
  std::vector<std::int32_t> offsets{0};
  for (auto c : cells)
  {
    const auto local = dofmap.links(c);
    std::vector<std::int64_t> global(local.size());
    node_map->local_to_global(local, global);
    nodes.insert(nodes.end(), global.begin(), global.end());
    offsets.push_back(std::int32_t(nodes.size()));
  }
  const std::size_t owned_nodes = node_map->size_local();
  std::vector<double> x(owned_nodes * gdim);
  for (std::size_t i = 0; i < owned_nodes; ++i)
    for (int d = 0; d < gdim; ++d)
      x[gdim * i + d] = geometry.x()[3 * i + d];

  mesh::CellPartitionFunction to_dest
      = [&](MPI_Comm, int, int, const graph::AdjacencyList<std::int64_t>& c, mesh::GhostMode)
  {
    std::vector<std::int32_t> ranks, rank_offsets{0};
    for (std::int32_t i = 0; i < c.num_nodes(); ++i)
    {
      ranks.push_back(dest[i]);
      ranks.insert(ranks.end(), ghosts[i].begin(), ghosts[i].end());
      rank_offsets.push_back(std::int32_t(ranks.size()));
    }
    return graph::AdjacencyList<std::int32_t>(std::move(ranks), std::move(rank_offsets));
  };
  graph::AdjacencyList<std::int64_t> topology(std::move(nodes), std::move(offsets));
  return std::make_shared<Mesh>(mesh::create_mesh(base.comm(), topology, geometry.cmap(), x,
                                                  {owned_nodes, std::size_t(gdim)},
                                                  mesh::GhostMode::none, to_dest));
}
} // namespace

std::shared_ptr<Mesh> create_patch(const Mesh& base, const Box& box)
{
  return create_patch(base, cells_meeting(base, box));
}

std::shared_ptr<Mesh> create_patch(const Mesh& base, std::span<const std::int32_t> cells)
{
  // Every cell stays on this rank: fields move between the meshes rank-locally.
  int rank = 0;
  MPI_Comm_rank(base.comm(), &rank);
  return mesh_of_cells(base, cells, std::vector<int>(cells.size(), rank));
}

std::shared_ptr<Mesh> redistribute(const Mesh& mesh, std::span<const int> dest)
{
  if (dest.size() != std::size_t(num_owned_cells(mesh)))
    throw std::invalid_argument("redistribute: one destination per owned cell expected");
  std::vector<std::int32_t> all(dest.size());
  std::iota(all.begin(), all.end(), 0);
  return mesh_of_cells(mesh, all, dest);
}
} // namespace cellphase::compat
