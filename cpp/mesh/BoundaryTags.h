// Named boundary tags of a mesh-file domain on its base mesh and on every refinement of
// it. DOLFINx 0.5 refinement does not carry facet tags; a boundary facet instead gets
// the tags of the file facets its midpoint lies on (scene::MeshDomain::on_tags), which
// bisection preserves. Rank-local: every rank holds the file's (few) tagged facets.
#pragma once
#include "compat/Dolfinx.h"
#include "scene/MeshDomain.h"
#include <string>
#include <vector>

namespace cellphase
{
/// Owned exterior facets of `mesh` on the tags (scene::MeshDomain::untagged: boundary
/// facets of the file without a tag).
std::vector<std::int32_t> tagged_facets(const Mesh& mesh, const scene::MeshDomain& domain,
                                        const std::vector<int>& tags);

/// Tag numbers of tag names (names the scene has checked).
std::vector<int> tag_numbers(const scene::MeshDomain& domain,
                             const std::vector<std::string>& names);
} // namespace cellphase
