// `cellphase check SCENE`: what a scene implies (mesh, steps, problem size) before running.
#pragma once
#include "scene/Scene.h"
#include <string>

namespace cellphase::scene
{
/// Problem size implied by a scene; the cell count is an estimate from the interface size.
struct SizeEstimate
{
  double interface_measure = 0; ///< total interface length (2D) or area (3D)
  double base_cells = 0;        ///< triangles / tetrahedra of the base mesh
  double refined_cells = 0;     ///< cells added by refining the band around the interfaces
  double dofs = 0;              ///< P2 degrees of freedom of all fields of the model
};
SizeEstimate estimate_size(const Scene& s);

/// Number of time steps, ceil(end_time / dt) (with a little tolerance for rounding).
long number_of_steps(const Scene& s);
/// Steps of numerics.dt from time `from` to end_time (the last one shortened to end there).
long steps_between(const Scene& s, double from);
/// Field writes: the initial state plus one every output.every steps (0 if every == 0).
long number_of_outputs(const Scene& s);
/// "" or why the stabilised scheme is far less accurate than Taylor's at the scene's dt
/// (measured guides per model, docs/scenes.md).
std::string stabilised_accuracy_warning(const Scene& s);

/// Multi-line human-readable summary of a validated scene.
std::string check_report(const Scene& s);
} // namespace cellphase::scene
