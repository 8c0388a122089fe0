// Sharp-interface measures of a P2 phase field, the limits the diffuse observables tend to
// as eps -> 0 (docs/scenes.md, "The columns of observables.csv"): the measure of the
// region phi > 0, the measure of the zero level set and the bending energy on it.
// Each cell is split on its P2 nodes into linear cells (4 triangles, 8 tetrahedra), where
// the zero level set of the linear interpolant is a segment (a triangle or a quadrilateral
// in 3D); the curvature kappa = div n, n = -grad phi / |grad phi| (the outer normal: phi is
// +1 inside), is the model's own at each piece's centroid: the diffuse curvature (3.24),
// -mu + sqrt2 H0 (1 - phi^2), over eps |grad phi| (for the equilibrium profile
// -eps Lap phi + W'(phi)/eps = eps kappa |grad phi|), from the P2 mu and grad phi of the
// parent cell; in 3D kappa is the sum of the principal curvatures.
#pragma once
#include "compat/Dolfinx.h"

namespace cellphase
{
struct SharpMeasures
{
  double inside = 0;  ///< area (2D) or volume (3D) of {phi > 0}
  double surface = 0; ///< length (2D) or area (3D) of {phi = 0}
  double bending = 0; ///< (1/2) int_{phi = 0} (kappa - H0)^2 ds
};

/// Over the owned cells of phi's mesh, summed over the ranks. phi and mu are scalar P2 on
/// the same space; without mu (models without bending) the bending stays 0.
SharpMeasures sharp_measures(const Function& phi, const Function* mu, double H0, double eps);
} // namespace cellphase
