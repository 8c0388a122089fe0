#include "scene/MeshDomain.h"
#include "scene/Sections.h"
#include <algorithm>
#include <filesystem>

namespace cellphase::scene
{
using namespace yaml;

namespace
{
/// domain.periodic: a list of distinct axis names of the domain's dimension.
void read_periodic(const Section& d, Domain& domain)
{
  domain.periodic.clear();
  if (!d.has("periodic"))
    return;
  const std::vector<std::string> names{"x", "y", "z"};
  const std::vector<std::string> allowed(names.begin(), names.begin() + domain.dim);
  const Value v = d.value("periodic");
  if (!v.node.IsSequence())
    v.fail("found " + v.found() + ", expected a list of axes out of " + join(allowed)
           + ", e.g. [x]");
  for (std::size_t i = 0; i < v.node.size(); ++i)
  {
    const Value e = v.element(i);
    const std::string axis = e.node.IsScalar() ? e.string() : "";
    const auto it = std::find(allowed.begin(), allowed.end(), axis);
    if (it == allowed.end())
      e.fail("found " + e.found() + ", expected one of the axes " + join(allowed) + " of this "
             + std::to_string(domain.dim) + "D domain");
    const int a = int(it - allowed.begin());
    if (std::find(domain.periodic.begin(), domain.periodic.end(), a) != domain.periodic.end())
      e.fail("axis " + axis + " is listed twice");
    domain.periodic.push_back(a);
  }
  std::sort(domain.periodic.begin(), domain.periodic.end());
}
/// Where domain.mesh is looked for: relative paths against the scene file's folder first,
/// then, for meshes/NAME.xdmf, the meshes generated from the repository's meshes/*.geo
/// at build time (<build>/meshes).
std::vector<std::string> mesh_candidates(const std::string& file, const std::string& scene)
{
  namespace fs = std::filesystem;
  const fs::path p(file);
  if (p.is_absolute())
    return {file};
  std::vector<std::string> out{(fs::path(scene).parent_path() / p).lexically_normal().string()};
#ifdef CELLPHASE_MESH_DIR
  auto it = p.begin();
  if (it != p.end() && *it == "meshes")
    out.push_back((fs::path(CELLPHASE_MESH_DIR) / p.lexically_relative("meshes")).string());
#endif
  return out;
}

/// domain.mesh: a 2D mesh with named facet tags instead of the box.
void read_mesh(const Section& d, Scene& s)
{
  for (const char* key : {"lower", "upper", "resolution"})
    if (d.has(key))
      d.fail(key, "is a setting of the box domain; with domain.mesh the mesh file gives "
                  "the domain (remove " + std::string(key) + " or mesh)");
  if (d.has("periodic"))
    d.fail("periodic", "is supported on box domains only, not with domain.mesh");
  const Value v = d.value("mesh");
  s.domain.mesh_file = v.string();
  if (s.domain.mesh_file.empty())
    v.fail("found an empty text, expected the path of an XDMF mesh file");
  const auto candidates = mesh_candidates(s.domain.mesh_file, s.source);
  std::string problems;
  for (const std::string& path : candidates)
  {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec) && candidates.size() > 1)
    {
      problems += (problems.empty() ? "" : "; ") + path + " does not exist";
      continue;
    }
    try
    {
      s.domain.mesh = std::make_shared<MeshDomain>(read_mesh_file(path), path);
      break;
    }
    catch (const std::runtime_error& e)
    {
      v.fail(std::string("cannot read the mesh: ") + e.what());
    }
  }
  if (!s.domain.mesh)
    v.fail("cannot read mesh file '" + s.domain.mesh_file + "': " + problems
           + " (a relative path is taken from the scene file's folder; meshes/NAME.xdmf "
             "also from the meshes built from the repository's meshes/NAME.geo)");
  const MeshDomain& m = *s.domain.mesh;
  s.domain.dim = 2;
  s.domain.lower = m.lower();
  s.domain.upper = m.upper();
  s.domain.resolution = {1, 1, 0};
  s.domain.periodic.clear();
}

/// A list of tag names of the mesh, e.g. boundary.phi_tags.
std::vector<std::string> read_tag_list(const Section& sec, const std::string& key,
                                       const MeshDomain& mesh)
{
  const Value v = sec.value(key);
  if (!v.node.IsSequence() || v.node.size() == 0)
    v.fail("found " + v.found() + ", expected a non-empty list of tag names out of "
           + join(mesh.tag_names()));
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.node.size(); ++i)
  {
    const Value e = v.element(i);
    const std::string name = e.node.IsScalar() ? e.string() : "";
    if (!mesh.data().tags.count(name))
      e.fail("unknown boundary tag " + e.found() + "; the tags of " + mesh.path() + " are "
             + (mesh.tag_names().empty() ? "none" : join(mesh.tag_names())));
    if (std::count(out.begin(), out.end(), name))
      e.fail("tag " + name + " is listed twice");
    out.push_back(name);
  }
  return out;
}
} // namespace

void read_domain(const Section& top, Scene& s)
{
  if (!top.has("domain"))
    top.fail("domain", "missing; every scene needs a domain with lower, upper and resolution "
                       "(or a mesh file)");
  const Section d = top.section("domain");
  d.allow_only({"lower", "upper", "resolution", "periodic", "mesh"});
  if (d.has("mesh"))
  {
    read_mesh(d, s);
    return;
  }

  // The first list given fixes the dimension; the others must have the same length.
  std::string first;
  for (const char* key : {"lower", "upper", "resolution"})
    if (first.empty() && d.has(key))
      first = key;
  int dim = 2;
  if (!first.empty())
  {
    const Value v = d.value(first);
    if (!v.node.IsSequence() || (v.node.size() != 2 && v.node.size() != 3))
      v.fail("found " + v.found() + ", expected a list of 2 numbers (2D) or 3 numbers (3D)");
    dim = static_cast<int>(v.node.size());
  }
  s.domain.dim = dim;
  for (const char* key : {"lower", "upper", "resolution"})
    if (d.has(key) && key != first)
    {
      const Value v = d.value(key);
      if (!v.node.IsSequence() || v.node.size() != std::size_t(dim))
        v.fail("found " + v.found() + ", expected a list of " + std::to_string(dim)
               + " values, one per axis (domain." + first + " has " + std::to_string(dim)
               + ", so the domain is " + std::to_string(dim) + "D)");
    }

  s.domain.lower = {0, 0, 0};
  s.domain.upper = {1, 1, dim == 3 ? 1.0 : 0.0};
  s.domain.resolution = {16, 16, dim == 3 ? 16 : 0};
  const std::vector<std::size_t> n{std::size_t(dim)};
  if (d.has("lower"))
  {
    const auto v = d.numbers("lower", n, any());
    std::copy(v.begin(), v.end(), s.domain.lower.begin());
  }
  if (d.has("upper"))
  {
    const auto v = d.numbers("upper", n, any());
    std::copy(v.begin(), v.end(), s.domain.upper.begin());
  }
  if (d.has("resolution"))
  {
    const auto v = d.integers("resolution", dim, closed(1, 1e6));
    std::copy(v.begin(), v.end(), s.domain.resolution.begin());
  }
  for (int i = 0; i < dim; ++i)
    if (!(s.domain.upper[i] > s.domain.lower[i]))
      d.fail("upper", "on axis " + std::to_string(i) + " upper (" + fmt(s.domain.upper[i])
                          + ") is not greater than lower (" + fmt(s.domain.lower[i])
                          + "); upper must exceed lower on every axis");
  read_periodic(d, s.domain);
}

void read_boundary(const Section& top, Scene& s)
{
  // The H^-1 flows conserve int phi exactly only without a Dirichlet row on phi, so they
  // default to natural conditions; the L2 flows default to phi = -1 (2.19).
  const Model m = s.phase_field.model;
  const bool conserving = m == Model::cahn_hilliard || m == Model::helfrich_hm1;
  const Section b = top.section("boundary");
  b.allow_only({"phi", "contact_angle", "phi_tags"});
  s.phi_boundary = b.choice<PhiBoundary>(
      "phi", conserving ? PhiBoundary::neumann : PhiBoundary::dirichlet,
      {{"dirichlet", PhiBoundary::dirichlet}, {"neumann", PhiBoundary::neumann}});
  if (b.has("contact_angle"))
  {
    // grad phi . n = cos(theta) (1 - phi^2)/(eps sqrt2) on the walls (2.8)
    if (m != Model::cahn_hilliard)
      b.fail("contact_angle", std::string("is a condition of cahn_hilliard (2.8); model ")
                                  + to_string(m) + " has none");
    if (s.phi_boundary != PhiBoundary::neumann)
      b.fail("contact_angle", "replaces the natural condition of phi; it cannot be combined "
                              "with phi: dirichlet");
    if (!s.domain.periodic.empty())
      b.fail("contact_angle", "applies on every side of the box; a periodic axis has no "
                              "walls (remove domain.periodic or the contact angle)");
    s.contact_angle_deg = b.number("contact_angle", open(0.0, 180.0));
  }
  s.phi_tags.clear();
  if (b.has("phi_tags"))
  {
    if (!s.domain.mesh)
      b.fail("phi_tags", "names facet tags of a mesh file; the box has none (use domain.mesh)");
    if (s.phi_boundary != PhiBoundary::dirichlet)
      b.fail("phi_tags", "restricts phi = -1 to these tags; it needs phi: dirichlet");
    s.phi_tags = read_tag_list(b, "phi_tags", *s.domain.mesh);
  }
}

} // namespace cellphase::scene
