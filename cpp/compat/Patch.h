// A patch of the base mesh as a mesh of its own (a cell's own mesh, section 7.2), made on
// any number of MPI ranks: each patch cell stays on its base cell's rank, so fields move
// between the patch's refinements and the shared mesh's rank-locally.
#pragma once
#include "compat/Resample.h"

namespace cellphase::compat
{
/// The owned cells of `base` that meet `box`, as a mesh of their own. Built by create_mesh
/// from the base's global node numbers, so nodes and edges on a rank boundary are shared
/// as in any DOLFINx mesh (DOLFINx 0.5.2's create_submesh does not share them).
std::shared_ptr<Mesh> create_patch(const Mesh& base, const Box& box);

/// The given owned cells of `base` (local indices) as a mesh of their own. Cells on two
/// ranks that touch at a vertex only share that vertex, as cells that share a facet do.
std::shared_ptr<Mesh> create_patch(const Mesh& base, std::span<const std::int32_t> cells);
} // namespace cellphase::compat
