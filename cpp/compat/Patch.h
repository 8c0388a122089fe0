// Meshes made of a mesh's cells on any number of MPI ranks: a patch of the base mesh as a
// mesh of its own (a cell's own mesh, section 7.2), whose cells stay on their base cells'
// ranks so that fields move between the patch's refinements and the shared mesh
// rank-locally; and the base mesh itself dealt to the ranks in another way.
#pragma once
#include "compat/Resample.h"

namespace cellphase::compat
{
/// The owned cells of `base` that meet `box`, as a mesh of their own. Built by create_mesh
/// from the base's global node numbers, so nodes and edges on a rank boundary are shared
/// as in any DOLFINx mesh (DOLFINx 0.5.2's create_submesh does not share them). A box
/// that reaches beyond the base's upper side along a periodic axis (compat::set_periods)
/// gives a wrapped patch: the cells meeting its image a period down are moved up a period
/// and joined to the others at the side, one piece across it. The box must then be at
/// least two base cells shorter than the period.
std::shared_ptr<Mesh> create_patch(const Mesh& base, const Box& box);

/// The given owned cells of `base` (local indices) as a mesh of their own. Cells on two
/// ranks that touch at a vertex only share that vertex, as cells that share a facet do.
std::shared_ptr<Mesh> create_patch(const Mesh& base, std::span<const std::int32_t> cells);

/// The same mesh with its owned cell c moved to rank dest[c] (collective; the nodes keep
/// their coordinates bit for bit). Nothing refined from `mesh` moves with it.
std::shared_ptr<Mesh> redistribute(const Mesh& mesh, std::span<const int> dest);
} // namespace cellphase::compat
