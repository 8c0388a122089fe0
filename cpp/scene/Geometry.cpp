#include "scene/Geometry.h"
#include "scene/YamlRead.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{

int check_grid_points(int dim) { return dim == 2 ? 201 : 61; }

double interface_measure(const Domain& d, const SignedDistance& r)
{
  // Coarea formula with a hat-shaped delta of half-width 2h: its samples along the normal
  // sum to one, so straight pieces of interface are measured exactly on any grid offset.
  const int n = d.dim == 2 ? 801 : 121;
  double cell_volume = 1, h = 0;
  for (int a = 0; a < d.dim; ++a)
  {
    const double ha = (d.upper[a] - d.lower[a]) / (n - 1);
    cell_volume *= ha;
    h = std::max(h, ha);
  }
  const double delta = 2 * h;
  double sum = 0;
  for_each_grid_point(d, n, [&](const Point& p)
                      { sum += std::max(0.0, 1 - std::abs(r(p[0], p[1], p[2])) / delta); });
  return sum * cell_volume / delta;
}

double enclosed_measure(const Domain& d, const SignedDistance& r)
{
  // A ramp of half-width 2h for the step: its error is odd across a straight interface, so
  // straight pieces are measured exactly on any grid offset (as the coarea estimate above).
  const int n = d.dim == 2 ? 801 : 121;
  double cell_volume = 1, h = 0;
  for (int a = 0; a < d.dim; ++a)
  {
    const double ha = (d.upper[a] - d.lower[a]) / (n - 1);
    cell_volume *= ha;
    h = std::max(h, ha);
  }
  const double delta = 2 * h;
  double sum = 0;
  for_each_grid_point(d, n, [&](const Point& p)
                      { sum += std::clamp(0.5 - r(p[0], p[1], p[2]) / (2 * delta), 0.0, 1.0); });
  return sum * cell_volume;
}

std::string point_text(const Point& p, int dim)
{
  std::string s = "(";
  for (int a = 0; a < dim; ++a)
    s += (a ? ", " : "") + yaml::fmt(p[a]);
  return s + ")";
}

} // namespace cellphase::scene
