#include "scene/Units.h"
#include <cmath>

namespace cellphase::scene
{

DerivedFlags derivable_numbers(const PhysicalUnits& u)
{
  DerivedFlags f;
  f.Re = u.density && u.velocity && u.length && u.viscosity;
  f.Ca = u.viscosity && u.velocity && u.surface_tension;
  f.Be = u.viscosity && u.velocity && u.length && u.bending_rigidity;
  f.time_scale = u.length && u.velocity;
  f.Fa = u.viscosity && u.velocity && u.length && u.protrusion_coefficient;
  f.Pa = u.viscosity && u.velocity && u.length && u.frank_constant;
  return f;
}

Numbers derive_numbers(const PhysicalUnits& u)
{
  const DerivedFlags f = derivable_numbers(u);
  const double sqrt2 = std::sqrt(2.0);
  Numbers n;
  if (f.Re)
    n.Re = *u.density * *u.velocity * *u.length / *u.viscosity;
  if (f.Ca)
    n.Ca = 2 * sqrt2 * *u.viscosity * *u.velocity / (3 * *u.surface_tension);
  if (f.Be)
    n.Be = 4 * sqrt2 * *u.viscosity * *u.velocity * *u.length * *u.length
           / (3 * *u.bending_rigidity);
  if (f.Fa) // (5.8)
    n.Fa = *u.viscosity * *u.velocity / (*u.protrusion_coefficient * *u.length);
  if (f.Pa) // (6.4)
    n.Pa = *u.viscosity * *u.velocity * *u.length / *u.frank_constant;
  if (f.time_scale)
    n.time_scale_s = *u.length / *u.velocity;
  return n;
}

} // namespace cellphase::scene
