#include "compat/Patch.h"
#include <dolfinx/la/Vector.h>
#include <functional>

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

/// For each owned cell of `base` in the patch: the ranks of its facet neighbours that are
/// in the patch on another rank. create_mesh needs them (it ghosts cells by facet and
/// finds the vertices shared between ranks from those ghosts), and the base mesh has no
/// ghost cells, so each side of a rank boundary tells the other whether its cell is in.
std::vector<std::vector<int>> neighbour_ranks(Mesh& base, const std::vector<std::int32_t>& cells)
{
  const int tdim = base.topology().dim();
  auto& topology = base.topology_mutable();
  topology.create_entities(tdim - 1);
  topology.create_connectivity(tdim, tdim - 1);
  topology.create_connectivity(tdim - 1, tdim);
  auto facet_map = topology.index_map(tdim - 1);
  const auto c2f = topology.connectivity(tdim, tdim - 1);
  const auto f2c = topology.connectivity(tdim - 1, tdim);
  const std::int32_t owned = facet_map->size_local();

  std::vector<char> in_patch(num_owned_cells(base), 0);
  for (auto c : cells)
    in_patch[c] = 1;

  // mine: this side's flag on every facet. theirs: the other side's. Owners get the
  // ghosts' flags by a reverse scatter, ghosts get the owners' by a forward scatter.
  la::Vector<double> to_owner(facet_map, 1), to_ghost(facet_map, 1);
  auto rev = to_owner.mutable_array();
  auto fwd = to_ghost.mutable_array();
  std::vector<double> mine(rev.size());
  for (std::size_t f = 0; f < mine.size(); ++f)
    mine[f] = f2c->num_links(f) == 1 && in_patch[f2c->links(f)[0]] ? 1.0 : 0.0;
  std::fill(rev.begin(), rev.end(), 0.0);
  std::copy(mine.begin() + owned, mine.end(), rev.begin() + owned);
  to_owner.scatter_rev(std::plus<double>());
  std::copy(mine.begin(), mine.begin() + owned, fwd.begin());
  to_ghost.scatter_fwd();
  auto theirs = [&](std::int32_t f) { return f < owned ? rev[f] : fwd[f]; };

  // The rank across each shared facet: the owner of a ghost facet, or the rank that
  // ghosts an owned one (one rank in both cases: a facet joins two cells).
  std::vector<int> across(mine.size(), -1);
  const auto& ghost_owners = facet_map->owners();
  for (std::size_t i = 0; i < ghost_owners.size(); ++i)
    across[owned + i] = ghost_owners[i];
  const auto shared = facet_map->index_to_dest_ranks();
  for (std::int32_t f = 0; f < owned; ++f)
    if (shared.num_links(f) > 0)
      across[f] = shared.links(f)[0];

  std::vector<std::vector<int>> ranks(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (auto f : c2f->links(cells[i]))
      if (across[f] >= 0 && theirs(f) > 0.5
          && std::find(ranks[i].begin(), ranks[i].end(), across[f]) == ranks[i].end())
        ranks[i].push_back(across[f]);
  return ranks;
}
} // namespace

std::shared_ptr<Mesh> create_patch(const Mesh& base_in, const Box& box)
{
  auto& base = const_cast<Mesh&>(base_in); // only connectivity is added
  const std::vector<std::int32_t> cells = cells_meeting(base, box);
  const auto ranks = neighbour_ranks(base, cells);
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
  // the ranks of its neighbours in the patch.
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
