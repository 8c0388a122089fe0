// Which candidate cell holds a point (internal to compat/): the test of
// dolfinx::geometry::compute_colliding_cells (squared distance below 1e-20), answered for
// straight simplices by the point's distances to the lines or planes of the faces. That
// general test runs GJK on every candidate, most of a remesh's point location on meshes of
// many cells; here GJK is left for points within round-off of a face, so the same cell is
// chosen and the transfers stay the same bit for bit.
#pragma once
#include "compat/Dolfinx.h"
#include <dolfinx/geometry/utils.h>
#include <array>
#include <cmath>
#include <span>

namespace cellphase::compat::detail
{
class CellContains
{
public:
  explicit CellContains(const Mesh& mesh)
      : mesh_(mesh), tdim_(mesh.topology().dim()),
        // straight triangles and tetrahedra: affine simplices (as PointWeights::applicable)
        fast_(mesh.geometry().cmap().is_affine() && tdim_ >= 2 && mesh.geometry().dim() == tdim_)
  {
  }

  /// The first of `cells` within 1e-10 of the point p (x, y, z), or -1.
  std::int32_t first(std::span<const std::int32_t> cells, const double* p) const
  {
    for (std::int32_t c : cells)
      if (contains(c, p))
        return c;
    return -1;
  }

private:
  static constexpr double tolerance = 1e-10; // dolfinx's: squared distance below 1e-20

  bool contains(std::int32_t c, const double* p) const
  {
    if (fast_)
    {
      const double d = smallest_face_distance(c, p);
      if (d >= 0)
        return true; // inside: GJK's distance is round-off, far below the tolerance
      if (d < -2 * tolerance)
        return false; // the distance to the cell is at least that to a face's line/plane
    }
    const std::int32_t one[1] = {c};
    return dolfinx::geometry::squared_distance(mesh_, tdim_, one, std::span(p, 3))[0]
           < tolerance * tolerance;
  }

  /// min over the faces of the signed distance from p to the face's line (2D) or plane
  /// (3D), positive towards the opposite vertex.
  double smallest_face_distance(std::int32_t c, const double* p) const
  {
    auto nodes = mesh_.geometry().dofmap().links(c);
    auto x = mesh_.geometry().x();
    const int nv = tdim_ + 1;
    std::array<std::array<double, 3>, 4> v; // not cell_vertex_coordinates: no allocation here
    for (int k = 0; k < nv; ++k)
      for (int d = 0; d < 3; ++d)
        v[k][d] = x[3 * nodes[k] + d];
    double smallest = INFINITY;
    for (int k = 0; k < nv; ++k)
    {
      // the face opposite vertex k: its first vertex a and its normal n
      const auto& a = v[(k + 1) % nv];
      std::array<double, 3> n;
      if (tdim_ == 2)
      {
        const auto& b = v[(k + 2) % nv];
        n = {-(b[1] - a[1]), b[0] - a[0], 0};
      }
      else
      {
        const auto &b = v[(k + 2) % nv], &e = v[(k + 3) % nv];
        const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]},
            w{e[0] - a[0], e[1] - a[1], e[2] - a[2]};
        n = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      }
      double to_p = 0, to_k = 0, norm = 0;
      for (int d = 0; d < 3; ++d)
      {
        to_p += n[d] * (p[d] - a[d]);
        to_k += n[d] * (v[k][d] - a[d]);
        norm += n[d] * n[d];
      }
      const double signed_distance = (to_k > 0 ? to_p : -to_p) / std::sqrt(norm);
      smallest = std::min(smallest, signed_distance);
    }
    return smallest;
  }

  const Mesh& mesh_;
  const int tdim_;
  const bool fast_;
};
} // namespace cellphase::compat::detail
