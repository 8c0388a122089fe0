// The interaction functions of section 7.1.2 at a value of phi, as forms/cellphase_ufl.py
// writes them in UFL: B(phi) = (phi^2 - 1)^2 / eps and the Lennard-Jones-like w-bar of
// Fig. 7.7 of the signed distance d = -(eps/sqrt2) ln((1 + phi)/(1 - phi)) (7.3), which is
// the Gaussian (7.2) for r1 = r2 = 1, a1 = 0. Zero outside the diffuse interface.
#pragma once
#include "scene/Scene.h"
#include <cmath>

namespace cellphase
{
using InteractionShape = scene::InteractionPotential;

inline double interaction_B(double phi, double eps) { return (phi * phi - 1) * (phi * phi - 1) / eps; }

inline double interaction_w(double phi, double eps, const InteractionShape& s)
{
  if (std::abs(phi) >= 1 - 1e-12)
    return 0;
  const double d = -eps / std::sqrt(2.0) * std::log((1 + phi) / (1 - phi));
  return s.r1 * std::exp(-d * d / (s.r2 * eps * eps))
         - s.a1 * std::exp(-(d - s.a2 * eps) * (d - s.a2 * eps) / (s.a3 * eps * eps));
}
} // namespace cellphase
