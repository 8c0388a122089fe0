#include "mesh/AdaptiveMesh.h"
#include "scene/Resolution.h"
#include <cmath>

namespace cellphase
{
AdaptiveMesh::AdaptiveMesh(const scene::Scene& scene, MPI_Comm comm)
    : base_(compat::create_base_mesh(comm, scene.domain)),
      levels_(scene::required_levels(scene)), h_base_(scene::base_cell_size(scene.domain)),
      threshold_(scene.numerics.mesh.refine_threshold),
      band_(2 * std::sqrt(2.0) * std::atanh(threshold_) * scene.numerics.epsilon)
{
}

std::shared_ptr<Mesh> AdaptiveMesh::build(const PointEvaluator& phi) const
{
  auto mesh = base_;
  double h = h_base_;
  for (int level = 0; level < levels_; ++level, h /= 2)
    mesh = compat::refine_cells(*mesh, mark(*mesh, phi, h));
  return mesh;
}

std::vector<std::int32_t> AdaptiveMesh::mark(const Mesh& mesh, const PointEvaluator& phi,
                                             double h) const
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
    if (amin < threshold_ || (lo < 0 && hi > 0))
      marked.push_back(c);
  }
  return marked;
}
} // namespace cellphase
