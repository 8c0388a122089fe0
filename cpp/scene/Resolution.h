// Mesh resolution implied by a scene: how many refinement levels put the requested
// number of mesh points across the diffuse interface.
#pragma once
#include "scene/Scene.h"

namespace cellphase::scene
{
/// Width of the diffuse interface: the band |phi| < 0.9 of the tanh profile (2.12),
/// 2 sqrt(2) atanh(0.9) eps ~ 4.16 eps.
double interface_width(double epsilon);
/// Largest base cell edge along the axes (the longest edge of a mesh file).
double base_cell_size(const Domain& d);
/// Refinement levels needed so that interface_width / h_min >= points_across_interface.
int required_levels(const Scene& s);
/// Smallest cell size after required_levels() bisections.
double finest_cell_size(const Scene& s);
} // namespace cellphase::scene
