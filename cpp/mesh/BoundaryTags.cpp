#include "mesh/BoundaryTags.h"

namespace cellphase
{
std::vector<std::int32_t> tagged_facets(const Mesh& mesh, const scene::MeshDomain& domain,
                                        const std::vector<int>& tags)
{
  return compat::boundary_facets_by_midpoint(mesh, [&](double x, double y, double z)
                                             {
                                               const double m[3] = {x, y, z};
                                               return domain.on_tags(m, tags);
                                             });
}

std::vector<int> tag_numbers(const scene::MeshDomain& domain,
                             const std::vector<std::string>& names)
{
  std::vector<int> out;
  for (const auto& n : names)
    out.push_back(domain.tag(n));
  return out;
}
} // namespace cellphase
