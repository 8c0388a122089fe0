#include "mesh/AdaptiveMesh.h"
#include "mesh/BaseMesh.h"
#include "mesh/PeriodicFaces.h"
#include "mesh/PointLookup.h"
#include "scene/Resolution.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cellphase
{
AdaptiveMesh::AdaptiveMesh(const scene::Scene& scene, MPI_Comm comm)
    : AdaptiveMesh(scene, create_partitioned_base_mesh(scene, comm))
{
}

AdaptiveMesh::AdaptiveMesh(const scene::Scene& scene, std::shared_ptr<Mesh> base)
    : base_(base), domain_(scene.domain),
      levels_(scene::required_levels(scene)), h_base_(scene::base_cell_size(scene.domain)),
      threshold_(scene.numerics.mesh.refine_threshold),
      band_(2 * std::sqrt(2.0) * std::atanh(threshold_) * scene.numerics.epsilon),
      inside_(scene.numerics.mesh.refine_inside.value_or(false)),
      inside_levels_(levels_ - scene.numerics.mesh.inside_coarser_by)
{
}

std::shared_ptr<Mesh> AdaptiveMesh::build(const PointEvaluator& phi)
{
  auto mesh = base_;
  history_.assign(levels_, {});
  double h = h_base_;
  for (int level = 0; level < levels_; ++level, h /= 2)
  {
    auto marked = mark(*mesh, phi, h, inside_ && level < inside_levels_);
    auto refined = refine_matching_faces(*mesh, marked);
    for (std::int32_t c : marked)
      for (double x : compat::cell_centroid(*mesh, c))
        history_[level].push_back(x);
    mesh = refined;
  }
  return mesh;
}

std::shared_ptr<Mesh> AdaptiveMesh::refine_matching_faces(Mesh& mesh,
                                                          std::vector<std::int32_t>& marked) const
{
  auto refined = compat::refine_cells(mesh, marked);
  // Each round splits the edges of the other face where one face got a vertex; those
  // splits may add vertices elsewhere on the faces (conformity), hence the rounds. A round
  // that finds no edge to split (a patch of the base mesh that holds one face only) ends it.
  for (int round = 0; round < 10 && !domain_.periodic.empty(); ++round)
  {
    const auto points = unmatched_periodic_points(*refined, domain_);
    if (points.empty())
      break;
    const auto extra = cells_splitting_at(mesh, points, domain_);
    std::int64_t found = extra.size();
    MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPI_INT64_T, MPI_SUM, mesh.comm());
    if (found == 0)
      break;
    marked.insert(marked.end(), extra.begin(), extra.end());
    std::sort(marked.begin(), marked.end());
    marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
    refined = compat::refine_cells(mesh, marked);
  }
  return refined;
}

std::shared_ptr<Mesh> AdaptiveMesh::replay(const std::vector<std::vector<double>>& history)
{
  if (int(history.size()) != levels_)
    throw std::runtime_error("the checkpoint's mesh has " + std::to_string(history.size())
                             + " refinement levels, the scene gives "
                             + std::to_string(levels_));
  auto mesh = base_;
  history_.assign(levels_, {});
  double h = h_base_;
  for (int level = 0; level < levels_; ++level, h /= 2)
  {
    // Centroids of distinct cells of this level are at least ~h/6 apart.
    PointLookup refined(history[level], 1e-6 * h);
    std::vector<std::int32_t> marked;
    for (std::int32_t c = 0; c < compat::num_owned_cells(*mesh); ++c)
    {
      const auto x = compat::cell_centroid(*mesh, c);
      if (refined.find(x.data()) >= 0)
      {
        marked.push_back(c);
        history_[level].insert(history_[level].end(), x.begin(), x.end());
      }
    }
    std::int64_t found = marked.size(), stored = history[level].size() / 3;
    MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPI_INT64_T, MPI_SUM, mesh->comm());
    if (found != stored)
      throw std::runtime_error("the checkpoint's mesh does not fit the scene's base mesh: "
                               + std::to_string(stored) + " cells refined at level "
                               + std::to_string(level) + ", " + std::to_string(found)
                               + " of them found");
    mesh = compat::refine_cells(*mesh, marked);
  }
  return mesh;
}

std::vector<std::int32_t> AdaptiveMesh::mark(const Mesh& mesh, const PointEvaluator& phi,
                                             double h, bool inside) const
{
  // Sample each cell on a barycentric lattice fine enough (spacing below half the band
  // width) that a thin interface passing between the vertices of a coarse cell is seen.
  const int n = std::max(1, int(std::ceil(2 * h / band_)));
  const int tdim = mesh.topology().dim();
  std::vector<std::array<int, 3>> lattice;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j)
      for (int k = 0; k <= (tdim == 3 ? n - i - j : 0); ++k)
        lattice.push_back({i, j, k});
  const std::int32_t ncells = compat::num_owned_cells(mesh);
  std::vector<double> pts;
  pts.reserve(std::size_t(ncells) * lattice.size() * 3);
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    const auto v = compat::cell_vertex_coordinates(mesh, c);
    for (const auto& [i, j, k] : lattice)
      for (int d = 0; d < 3; ++d)
      {
        double x = v[d] + i * (v[3 + d] - v[d]) / n + j * (v[6 + d] - v[d]) / n;
        if (tdim == 3)
          x += k * (v[9 + d] - v[d]) / n;
        pts.push_back(x);
      }
  }
  std::vector<double> values(pts.size() / 3);
  phi(pts, values);
  std::vector<std::int32_t> marked;
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    double lo = 1e300, hi = -1e300, amin = 1e300;
    for (std::size_t p = 0; p < lattice.size(); ++p)
    {
      const double val = values[c * lattice.size() + p];
      lo = std::min(lo, val), hi = std::max(hi, val), amin = std::min(amin, std::abs(val));
    }
    if (amin < threshold_ || (lo < 0 && hi > 0) || (inside && hi > -threshold_))
      marked.push_back(c);
  }
  return marked;
}
} // namespace cellphase
