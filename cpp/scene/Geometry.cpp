#include "scene/Geometry.h"
#include "scene/YamlRead.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{

int check_grid_points(int dim) { return dim == 2 ? 201 : 61; }

namespace
{
/// h * sum of f(r(p), delta) over the check grid (cell volume h^dim, half-width delta = 2h
/// of the smoothed delta and step below).
template <typename F>
double grid_integral(const Domain& d, const SignedDistance& r, F f)
{
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
  for_each_grid_point(d, n, [&](const Point& p) { sum += f(r(p[0], p[1], p[2]), delta); });
  return sum * cell_volume;
}
} // namespace

double interface_measure(const Domain& d, const SignedDistance& r)
{
  // Coarea formula with a hat-shaped delta of half-width 2h: its samples along the normal
  // sum to one, so straight pieces of interface are measured exactly on any grid offset.
  return grid_integral(d, r, [](double dist, double delta)
                       { return std::max(0.0, 1 - std::abs(dist) / delta) / delta; });
}

double enclosed_measure(const Domain& d, const SignedDistance& r)
{
  // A ramp of half-width 2h for the step: its error is odd across a straight interface, so
  // straight pieces are measured exactly on any grid offset (as the coarea estimate above).
  return grid_integral(d, r, [](double dist, double delta)
                       { return std::clamp(0.5 - dist / (2 * delta), 0.0, 1.0); });
}

std::string point_text(const Point& p, int dim)
{
  std::string s = "(";
  for (int a = 0; a < dim; ++a)
    s += (a ? ", " : "") + yaml::fmt(p[a]);
  return s + ")";
}

} // namespace cellphase::scene
