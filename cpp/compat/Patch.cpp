#include "compat/Patch.h"
#include "compat/AllToAll.h"
#include <algorithm>

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

/// For each of the patch's `cells` (owned cells of `base`): the other ranks with patch
/// cells at one of its vertices, which must ghost it. create_mesh of DOLFINx 0.5.2 finds
/// the vertices shared between ranks only where owned and ghost cells meet, so every rank
/// with patch cells at a vertex needs a ghost cell at it from every other such rank. Facet
/// neighbours are not enough: at a pinch (patch cells that meet at a vertex only) the
/// vertex would be made twice. The base mesh has no ghost cells: the owner of each shared
/// vertex collects the ranks with patch cells there and tells them.
std::vector<std::vector<int>> vertex_neighbour_ranks(const Mesh& base,
                                                     std::span<const std::int32_t> cells)
{
  const MPI_Comm comm = base.comm();
  int size = 1, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const auto c2v = base.topology().connectivity(base.topology().dim(), 0);
  const auto vertices = base.topology().index_map(0);
  const std::int32_t owned = vertices->size_local();
  const std::int64_t first = vertices->local_range()[0];
  const auto& ghosts = vertices->ghosts();
  const auto& ghost_owners = vertices->owners();

  // at[v]: the ranks with patch cells at vertex v (this one included).
  std::vector<std::vector<int>> at(owned + ghosts.size());
  for (auto c : cells)
    for (auto v : c2v->links(c))
      if (at[v].empty())
        at[v].push_back(rank);

  // Ghost copies tell their owners, which then know every rank at their vertices.
  std::vector<std::vector<std::int64_t>> to_owner(size);
  for (std::size_t i = 0; i < ghosts.size(); ++i)
    if (!at[owned + i].empty())
      to_owner[ghost_owners[i]].push_back(ghosts[i]);
  const auto told = detail::all_to_all(comm, to_owner);
  for (int r = 0; r < size; ++r)
    for (auto g : told[r])
      at[g - first].push_back(r);

  // The owners send (vertex, rank) for every rank at a vertex to the other ranks there.
  std::vector<std::vector<std::int64_t>> to_sharer(size);
  for (std::int32_t v = 0; v < owned; ++v)
    if (at[v].size() > 1)
      for (int r : at[v])
        if (r != rank)
          for (int s : at[v])
            to_sharer[r].insert(to_sharer[r].end(), {first + v, std::int64_t(s)});
  const auto back = detail::all_to_all(comm, to_sharer);
  std::vector<std::int64_t> global;
  std::vector<int> from;
  for (int r = 0; r < size; ++r)
    for (std::size_t k = 0; k < back[r].size(); k += 2)
      global.push_back(back[r][k]), from.push_back(int(back[r][k + 1]));
  std::vector<std::int32_t> local(global.size());
  vertices->global_to_local(global, local);
  for (std::size_t k = 0; k < global.size(); ++k)
    if (std::find(at[local[k]].begin(), at[local[k]].end(), from[k]) == at[local[k]].end())
      at[local[k]].push_back(from[k]);

  std::vector<std::vector<int>> ranks(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (auto v : c2v->links(cells[i]))
      for (int r : at[v])
        if (r != rank && std::find(ranks[i].begin(), ranks[i].end(), r) == ranks[i].end())
          ranks[i].push_back(r);
  return ranks;
}
} // namespace

std::shared_ptr<Mesh> create_patch(const Mesh& base, const Box& box)
{
  return create_patch(base, cells_meeting(base, box));
}

std::shared_ptr<Mesh> create_patch(const Mesh& base, std::span<const std::int32_t> cells)
{
  const auto ranks = vertex_neighbour_ranks(base, cells);
  int rank = 0;
  MPI_Comm_rank(base.comm(), &rank);

  // The patch's cells by the base geometry's global node numbers, and the coordinates of
  // the nodes this rank owns (create_mesh reads node i from the rank whose block holds it).
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

  // Every cell stays on this rank (fields move between meshes rank-locally), ghosted on
  // the ranks with patch cells at its vertices.
  mesh::CellPartitionFunction keep_rank
      = [&](MPI_Comm, int, int, const graph::AdjacencyList<std::int64_t>& c, mesh::GhostMode)
  {
    std::vector<std::int32_t> dest, dest_offsets{0};
    for (std::int32_t i = 0; i < c.num_nodes(); ++i)
    {
      dest.push_back(rank);
      dest.insert(dest.end(), ranks[i].begin(), ranks[i].end());
      dest_offsets.push_back(std::int32_t(dest.size()));
    }
    return graph::AdjacencyList<std::int32_t>(std::move(dest), std::move(dest_offsets));
  };
  graph::AdjacencyList<std::int64_t> topology(std::move(nodes), std::move(offsets));
  return std::make_shared<Mesh>(mesh::create_mesh(base.comm(), topology, geometry.cmap(), x,
                                                  {owned_nodes, std::size_t(gdim)},
                                                  mesh::GhostMode::none, keep_rank));
}
} // namespace cellphase::compat
