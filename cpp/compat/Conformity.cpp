#include "compat/Conformity.h"
#include <array>
#include <cmath>
#include <set>

namespace cellphase::compat
{
namespace
{
using Key = std::array<std::int64_t, 3>;

/// Coordinates on a grid of spacing `tol`.
Key quantise(const double* x, double tol)
{
  return {std::llround(x[0] / tol), std::llround(x[1] / tol), std::llround(x[2] / tol)};
}
} // namespace

std::int64_t hanging_vertices(Mesh& mesh)
{
  const int tdim = mesh.topology().dim();
  auto& topology = mesh.topology_mutable();
  topology.create_entities(tdim - 1);
  topology.create_connectivity(tdim - 1, tdim);
  topology.create_connectivity(tdim - 1, 0);
  const auto f_to_c = mesh.topology().connectivity(tdim - 1, tdim);
  const auto f_to_v = mesh.topology().connectivity(tdim - 1, 0);

  // Facets with one cell on this rank: the domain's boundary and the rank boundary. Only
  // their vertices can hang over another rank's edge.
  std::vector<std::int32_t> facets;
  for (std::int32_t f = 0; f < f_to_c->num_nodes(); ++f)
    if (f_to_c->links(f).size() == 1)
      facets.push_back(f);
  const auto nodes = mesh::entities_to_geometry(mesh, tdim - 1, facets, false);
  const auto x = mesh.geometry().x();

  // Spacing of the lookup grid: far below any edge of the mesh.
  double extent = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    extent = std::max(extent, std::abs(x[i]));
  MPI_Allreduce(MPI_IN_PLACE, &extent, 1, MPI_DOUBLE, MPI_MAX, mesh.comm());
  const double tol = 1e-9 * std::max(extent, 1.0);

  // Every rank's boundary vertices, to every rank.
  std::vector<double> mine;
  for (std::int32_t node : nodes)
    mine.insert(mine.end(), x.data() + 3 * node, x.data() + 3 * node + 3);
  const int ranks = dolfinx::MPI::size(mesh.comm()), rank = dolfinx::MPI::rank(mesh.comm());
  std::vector<int> counts(ranks), offsets(ranks + 1, 0);
  const int count = int(mine.size());
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, mesh.comm());
  for (int r = 0; r < ranks; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(offsets[ranks]);
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, mesh.comm());
  std::set<Key> others;
  for (int r = 0; r < ranks; ++r)
    if (r != rank)
      for (int i = offsets[r]; i < offsets[r + 1]; i += 3)
        others.insert(quantise(all.data() + i, tol));

  auto is_vertex_of_another_rank = [&](const std::array<double, 3>& p)
  {
    const Key k = quantise(p.data(), tol);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (others.count({k[0] + dx, k[1] + dy, k[2] + dz}))
            return true;
    return false;
  };

  // In a conforming mesh no vertex lies inside an edge; a neighbour refined once more than
  // its unsplit neighbour puts one at the edge's midpoint.
  std::int64_t hanging = 0;
  const int nv = tdim; // vertices per facet of a simplex
  for (std::size_t f = 0; f < facets.size(); ++f)
    for (int a = 0; a < nv; ++a)
      for (int b = a + 1; b < nv; ++b)
      {
        const double* xa = x.data() + 3 * nodes[nv * f + a];
        const double* xb = x.data() + 3 * nodes[nv * f + b];
        const std::array<double, 3> mid{(xa[0] + xb[0]) / 2, (xa[1] + xb[1]) / 2,
                                        (xa[2] + xb[2]) / 2};
        if (is_vertex_of_another_rank(mid))
          ++hanging;
      }
  MPI_Allreduce(MPI_IN_PLACE, &hanging, 1, MPI_INT64_T, MPI_SUM, mesh.comm());
  return hanging;
}
} // namespace cellphase::compat
