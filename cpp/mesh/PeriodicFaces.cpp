#include "mesh/PeriodicFaces.h"
#include "mesh/PointLookup.h"
#include <algorithm>
#include <cmath>
#include <numeric>

namespace cellphase
{
namespace
{
/// All ranks' points (rows of 3) gathered on every rank.
std::vector<double> all_gather(const std::vector<double>& local, MPI_Comm comm)
{
  int size = 0;
  MPI_Comm_size(comm, &size);
  int n = int(local.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<double> all(offsets.back());
  MPI_Allgatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, comm);
  return all;
}

double tolerance(const scene::Domain& domain) { return 1e-9 * domain.largest_extent(); }
} // namespace

std::vector<double> unmatched_periodic_points(const Mesh& mesh, const scene::Domain& domain)
{
  std::vector<double> unmatched;
  if (domain.periodic.empty())
    return unmatched;
  const double tol = tolerance(domain);
  const auto x = mesh.geometry().x(); // P1 geometry: the nodes are the vertices
  for (int a : domain.periodic)
  {
    const double length = domain.upper[a] - domain.lower[a];
    std::vector<double> on_min, on_max;
    for (std::size_t i = 0; i < x.size() / 3; ++i)
    {
      const double* p = &x[3 * i];
      if (std::abs(p[a] - domain.lower[a]) < tol)
        on_min.insert(on_min.end(), p, p + 3);
      else if (std::abs(p[a] - domain.upper[a]) < tol)
        on_max.insert(on_max.end(), p, p + 3);
    }
    on_min = all_gather(on_min, mesh.comm());
    on_max = all_gather(on_max, mesh.comm());
    // Each face's vertices moved onto the other face; those without a partner there are
    // where the other face needs a vertex. (Duplicates from ghosts do no harm.)
    auto add_missing = [&](const std::vector<double>& from, const std::vector<double>& onto,
                           double shift)
    {
      PointLookup partners(onto, tol);
      for (std::size_t i = 0; i < from.size() / 3; ++i)
      {
        std::array<double, 3> image{from[3 * i], from[3 * i + 1], from[3 * i + 2]};
        image[a] += shift;
        if (partners.find(image.data()) < 0)
          unmatched.insert(unmatched.end(), image.begin(), image.end());
      }
    };
    add_missing(on_min, on_max, length);
    add_missing(on_max, on_min, -length);
  }
  return unmatched;
}

std::vector<std::int32_t> cells_splitting_at(const Mesh& coarse, const std::vector<double>& points,
                                             const scene::Domain& domain)
{
  std::vector<std::int32_t> cells;
  if (points.empty())
    return cells;
  PointLookup lookup(points, tolerance(domain));
  for (std::int32_t c = 0; c < compat::num_owned_cells(coarse); ++c)
  {
    const auto v = compat::cell_vertex_coordinates(coarse, c);
    const std::size_t nv = v.size() / 3;
    bool found = false;
    for (std::size_t i = 0; i < nv && !found; ++i)
      for (std::size_t j = i + 1; j < nv && !found; ++j)
      {
        const double mid[3] = {0.5 * (v[3 * i] + v[3 * j]), 0.5 * (v[3 * i + 1] + v[3 * j + 1]),
                               0.5 * (v[3 * i + 2] + v[3 * j + 2])};
        found = lookup.find(mid) >= 0;
      }
    if (found)
      cells.push_back(c);
  }
  return cells;
}
} // namespace cellphase
