// Matching refinement of periodic faces. A periodic constraint ties each dof on a max face
// to the min face; where one face is refined and the other is not, the fine side can only
// take the coarse side's trace, and a diffuse interface crossing there is resolved at the
// coarse spacing (a cell crossing x = 160 in the polar-gel splay scene changed its speed by
// half). AdaptiveMesh refines both faces alike with these two functions.
#pragma once
#include "compat/Dolfinx.h"
#include "scene/Scene.h"
#include <vector>

namespace cellphase
{
/// Points (rows of 3, the same on all ranks) where one periodic face of `mesh` has a vertex
/// and the face it is identified with has none. Collective.
std::vector<double> unmatched_periodic_points(const Mesh& mesh, const scene::Domain& domain);

/// Local owned cells of `coarse` with an edge whose midpoint is one of `points`: refining
/// them (all their edges are split) puts a vertex at those points. Plaza refinement only
/// adds edge midpoints, so every unmatched vertex of a refinement of `coarse` is one.
std::vector<std::int32_t> cells_splitting_at(const Mesh& coarse, const std::vector<double>& points,
                                             const scene::Domain& domain);
} // namespace cellphase
