#include "compat/Patch.h"
#include "compat/AllToAll.h"
#include "compat/PeriodicImages.h"
#include <algorithm>
#include <cmath>
#include <map>
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

/// A patch wrapped across periodic sides: the base nodes below `split` along a wrapped
/// axis move up by the period, and the nodes on a lower side are replaced by their
/// partners on the upper side (`partner`, by global node number), so that the patch is
/// one piece across the side.
struct Wrap
{
  std::array<double, 3> split{};
  std::array<bool, 3> axis{false, false, false};
  std::map<std::int64_t, std::int64_t> partner;
  /// Cells (positions in the list of cells) with a node on a side: ghosted on every rank,
  /// since ghost_ranks sees a node and its partner as two.
  std::vector<char> on_side;
};

/// `cells` (owned cells of `base`) as a mesh of their own, cell i on rank dest[i].
std::shared_ptr<Mesh> mesh_of_cells(const Mesh& base, std::span<const std::int32_t> cells,
                                    std::span<const int> dest, const Wrap* wrap = nullptr)
{
  auto ghosts = ghost_ranks(base, cells, dest);
  if (wrap)
  {
    int size = 1;
    MPI_Comm_size(base.comm(), &size);
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (wrap->on_side[i])
        for (int r = 0; r < size; ++r)
          if (r != dest[i])
            add_once(ghosts[i], r);
  }

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
    if (wrap)
      for (auto& g : global)
        if (auto it = wrap->partner.find(g); it != wrap->partner.end())
          g = it->second;
    nodes.insert(nodes.end(), global.begin(), global.end());
    offsets.push_back(std::int32_t(nodes.size()));
  }
  const std::size_t owned_nodes = node_map->size_local();
  std::vector<double> x(owned_nodes * gdim);
  for (std::size_t i = 0; i < owned_nodes; ++i)
    for (int d = 0; d < gdim; ++d)
    {
      x[gdim * i + d] = geometry.x()[3 * i + d];
      if (wrap && wrap->axis[d] && x[gdim * i + d] < wrap->split[d])
        x[gdim * i + d] += periods()[d];
    }

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
  const auto [lo, hi] = bounding_box(base);
  Wrap wrap;
  std::vector<int> wrapped; // axes along which the box reaches beyond the upper side
  for (int a = 0; a < 3; ++a)
  {
    const double L = periods()[a];
    if (L <= 0 || box[3 + a] <= hi[a] + 1e-9 * L || box[a] <= lo[a] + 1e-9 * L)
      continue; // inside the domain along a, or the whole of it
    wrap.axis[a] = true;
    wrap.split[a] = (box[3 + a] - L + box[a]) / 2;
    wrapped.push_back(a);
  }
  if (wrapped.empty())
    return create_patch(base, cells_meeting(base, box));

  // The cells meeting the box or one of its images a period down along wrapped axes.
  std::vector<std::int32_t> cells;
  for (unsigned mask = 0; mask < (1u << wrapped.size()); ++mask)
  {
    Box image = box;
    for (std::size_t k = 0; k < wrapped.size(); ++k)
      if (mask & (1u << k))
        image[wrapped[k]] -= periods()[wrapped[k]], image[3 + wrapped[k]] -= periods()[wrapped[k]];
    for (auto c : cells_meeting(base, image))
      cells.push_back(c);
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  // Every cell lies on one side of the split (the box's two parts are a cell apart), or a
  // node would be needed both where it is and a period up.
  for (auto c : cells)
  {
    const auto v = cell_vertex_coordinates(base, c);
    for (int a : wrapped)
    {
      int below = 0, n = 0;
      for (std::size_t i = a; i < v.size(); i += 3, ++n)
        below += v[i] < wrap.split[a];
      if (below != 0 && below != n)
        throw std::invalid_argument("create_patch: the box is too long to wrap across a periodic side");
    }
  }

  // Nodes on an upper side, from every rank: the partners of the nodes on the lower side.
  const auto& geometry = base.geometry();
  auto node_map = geometry.index_map();
  const auto x = geometry.x();
  auto on = [&](const double* p, int a, double side)
  { return std::abs(p[a] - side) <= 1e-9 * periods()[a]; };
  std::vector<double> mine; // rows of x, y, z, global number
  const std::int32_t num_nodes = node_map->size_local() + node_map->num_ghosts();
  for (std::int32_t i = 0; i < num_nodes; ++i)
    for (int a : wrapped)
      if (on(&x[3 * i], a, hi[a]))
      {
        std::int64_t g = 0;
        node_map->local_to_global(std::span(&i, 1), std::span(&g, 1));
        mine.insert(mine.end(), {x[3 * i], x[3 * i + 1], x[3 * i + 2], double(g)});
        break;
      }
  int size = 1;
  MPI_Comm_size(base.comm(), &size);
  std::vector<int> counts(size), offsets(size + 1, 0);
  const int count = int(mine.size());
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, base.comm());
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> upper(offsets[size]);
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, upper.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, base.comm());

  const auto& dofmap = geometry.dofmap();
  wrap.on_side.assign(cells.size(), 0);
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (std::int32_t node : dofmap.links(cells[i]))
    {
      const double* p = &x[3 * node];
      std::array<double, 3> q{p[0], p[1], p[2]}; // the partner's position
      bool lower_side = false;
      for (int a : wrapped)
      {
        wrap.on_side[i] = wrap.on_side[i] || on(p, a, lo[a]) || on(p, a, hi[a]);
        if (on(p, a, lo[a]))
          q[a] = hi[a], lower_side = true;
      }
      if (!lower_side)
        continue;
      std::int64_t g = 0;
      node_map->local_to_global(std::span(&node, 1), std::span(&g, 1));
      for (std::size_t k = 0; k < upper.size(); k += 4)
        if (std::abs(upper[k] - q[0]) + std::abs(upper[k + 1] - q[1]) + std::abs(upper[k + 2] - q[2])
            <= 1e-9 * (hi[0] - lo[0] + hi[1] - lo[1] + hi[2] - lo[2]))
        {
          wrap.partner[g] = std::int64_t(upper[k + 3]);
          break;
        }
      if (!wrap.partner.count(g))
        throw std::runtime_error("create_patch: a node on a periodic side has no partner");
    }
  int rank = 0;
  MPI_Comm_rank(base.comm(), &rank);
  return mesh_of_cells(base, cells, std::vector<int>(cells.size(), rank), &wrap);
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
