// Sampling signed distances over the domain: used to validate cell placement and to
// estimate interface sizes for `cellphase check`.
#pragma once
#include "scene/Scene.h"
#include "scene/Shapes.h"
#include <array>

namespace cellphase::scene
{

using Point = std::array<double, 3>;

/// Calls f(p) at the n^dim points of a regular grid spanning the domain, boundary included.
template <typename F>
void for_each_grid_point(const Domain& d, int n, F&& f)
{
  std::array<double, 3> h{0, 0, 0};
  for (int a = 0; a < d.dim; ++a)
    h[a] = (d.upper[a] - d.lower[a]) / (n - 1);
  const int nz = d.dim == 3 ? n : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        f(Point{d.lower[0] + i * h[0], d.lower[1] + j * h[1],
                d.dim == 3 ? d.lower[2] + k * h[2] : 0.0});
}

/// Grid points per axis for placement checks: fine in 2D, coarser in 3D to stay cheap.
int check_grid_points(int dim);

/// Length (2D) or area (3D) of a cell's zero level set inside the domain, estimated from
/// samples of r near zero (coarea formula). An estimate, not a measurement.
double interface_measure(const Domain& d, const SignedDistance& r);

/// Area (2D) or volume (3D) inside a cell's zero level set (r < 0) within the domain,
/// from the same samples. An estimate, not a measurement.
double enclosed_measure(const Domain& d, const SignedDistance& r);

/// "(0.5, -1)" or "(0.5, -1, 2)".
std::string point_text(const Point& p, int dim);

} // namespace cellphase::scene
