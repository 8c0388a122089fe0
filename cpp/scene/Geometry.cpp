#include "scene/Geometry.h"
#include "scene/YamlRead.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{

int check_grid_points(int dim) { return dim == 2 ? 201 : 61; }

double interface_measure(const Domain& d, const SignedDistance& r)
{
  const int n = d.dim == 2 ? 801 : 121;
  double cell_volume = 1, delta = 0;
  for (int a = 0; a < d.dim; ++a)
  {
    const double h = (d.upper[a] - d.lower[a]) / (n - 1);
    cell_volume *= h;
    delta = std::max(delta, h);
  }
  long count = 0;
  for_each_grid_point(d, n, [&](const Point& p)
                      { count += std::abs(r(p[0], p[1], p[2])) < delta; });
  return count * cell_volume / (2 * delta);
}

std::string point_text(const Point& p, int dim)
{
  std::string s = "(";
  for (int a = 0; a < dim; ++a)
    s += (a ? ", " : "") + yaml::fmt(p[a]);
  return s + ")";
}

} // namespace cellphase::scene
