#include "scene/Resolution.h"
#include "scene/MeshDomain.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{

double interface_width(double epsilon)
{
  return 2 * std::sqrt(2.0) * std::atanh(0.9) * epsilon;
}

double base_cell_size(const Domain& d)
{
  // A mesh file's cells vary in size: its longest edge, so that every cell gets the
  // requested resolution after the refinement levels.
  if (d.mesh)
    return d.mesh->longest_edge();
  double h = 0;
  for (int i = 0; i < d.dim; ++i)
    h = std::max(h, (d.upper[i] - d.lower[i]) / d.resolution[i]);
  return h;
}

int required_levels(const Scene& s)
{
  if (!s.numerics.mesh.adaptive)
    return 0; // the uniform base mesh
  const double w = interface_width(s.numerics.epsilon);
  const double p = s.numerics.mesh.points_across_interface;
  double h = base_cell_size(s.domain);
  // Bounded loop: a validated scene needs far fewer levels; the cap only guards nonsense.
  int level = 0;
  while (w / h < p && level < 60)
  {
    h /= 2;
    ++level;
  }
  return level;
}

double finest_cell_size(const Scene& s)
{
  return std::ldexp(base_cell_size(s.domain), -required_levels(s));
}

} // namespace cellphase::scene
