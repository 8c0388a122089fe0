// The scene's base mesh, split among the MPI ranks as numerics.mesh.partition says. Every
// mesh of a run is refined from it or cut from it without redistribution, so this split
// is the split of all of them.
#pragma once
#include "compat/Dolfinx.h"
#include "scene/Scene.h"

namespace cellphase
{
/// The base mesh of scene.domain. With partition: stripes on several ranks, its cells are
/// dealt to the ranks in stripes across the domain's longest axis (stripe_width wide,
/// by default 2 base cell sizes): a cell's patch then spans several stripes, so every
/// rank assembles and factorises part of each cell's system instead of one rank all of it.
std::shared_ptr<Mesh> create_partitioned_base_mesh(const scene::Scene& scene, MPI_Comm comm);

/// Stripe width of the scene's partition (stripes or not).
double stripe_width(const scene::Scene& scene);

/// The axis across which the stripes lie: the domain's longest.
int stripe_axis(const scene::Domain& domain);
} // namespace cellphase
