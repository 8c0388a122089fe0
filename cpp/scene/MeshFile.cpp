#include "scene/MeshFile.h"
#include <cerrno>
#include <cstring>
#include <fstream>
#include <pugixml.hpp>
#include <sstream>
#include <stdexcept>

namespace cellphase::scene
{
namespace
{
[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw std::runtime_error("mesh file '" + path + "': " + problem);
}

/// Values of an inline DataItem (Format="XML") with `columns` values per row.
template <typename V>
std::vector<V> read_item(const std::string& path, const pugi::xml_node& parent,
                         std::size_t columns, const char* what)
{
  const pugi::xml_node item = parent.child("DataItem");
  if (!item)
    fail(path, std::string("the ") + what + " has no DataItem");
  const std::string format = item.attribute("Format").as_string("XML");
  if (format != "XML")
    fail(path, std::string("the ") + what + " is stored as " + format
                   + "; cellphase reads XDMF with inline data (Format=\"XML\", as written by "
                     "python/msh_to_xdmf.py)");
  std::istringstream in(item.child_value());
  std::vector<V> out;
  V v;
  while (in >> v)
    out.push_back(v);
  if (!in.eof())
    fail(path, std::string("the ") + what + " holds text that is not a number");
  std::istringstream dims(item.attribute("Dimensions").as_string());
  std::size_t rows = 0, cols = 0;
  dims >> rows >> cols;
  if (cols == 0)
    cols = 1;
  if (cols != columns || out.size() != rows * cols)
    fail(path, std::string("the ") + what + " has " + std::to_string(out.size())
                   + " values for Dimensions \"" + item.attribute("Dimensions").as_string()
                   + "\"; expected " + std::to_string(columns) + " per row");
  return out;
}

pugi::xml_node grid(const pugi::xml_node& domain, const char* name)
{
  for (pugi::xml_node g : domain.children("Grid"))
    if (std::string(g.attribute("Name").as_string()) == name)
      return g;
  return {};
}
} // namespace

MeshData read_mesh_file(const std::string& path)
{
  std::ifstream probe(path);
  if (!probe)
    fail(path, std::strerror(errno));
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_file(path.c_str());
  if (!parsed)
    fail(path, std::string("not an XML file (") + parsed.description() + " at byte "
                   + std::to_string(parsed.offset) + ")");
  const pugi::xml_node domain = doc.child("Xdmf").child("Domain");
  if (!domain)
    fail(path, "not an XDMF file (no <Xdmf><Domain>)");
  const pugi::xml_node mesh = grid(domain, "mesh");
  if (!mesh)
    fail(path, "no <Grid Name=\"mesh\">");
  const pugi::xml_node topology = mesh.child("Topology");
  if (std::string(topology.attribute("TopologyType").as_string()) != "Triangle")
    fail(path, std::string("the mesh has cells of type \"")
                   + topology.attribute("TopologyType").as_string()
                   + "\"; cellphase reads 2D meshes of first-order triangles");
  const pugi::xml_node geometry = mesh.child("Geometry");
  if (std::string(geometry.attribute("GeometryType").as_string()) != "XY")
    fail(path, std::string("the geometry is of type \"")
                   + geometry.attribute("GeometryType").as_string() + "\"; expected XY (2D)");

  MeshData m;
  m.cells = read_item<std::int64_t>(path, topology, 3, "mesh topology");
  const auto xy = read_item<double>(path, geometry, 2, "mesh geometry");
  for (std::size_t i = 0; i < xy.size(); i += 2)
    m.points.insert(m.points.end(), {xy[i], xy[i + 1], 0.0});
  if (m.cells.empty())
    fail(path, "the mesh has no triangles");
  const auto n = std::int64_t(m.num_nodes());
  auto check_nodes = [&](const std::vector<std::int64_t>& v, const char* what)
  {
    for (auto i : v)
      if (i < 0 || i >= n)
        fail(path, std::string("a ") + what + " refers to node " + std::to_string(i) + " of "
                       + std::to_string(n));
  };
  check_nodes(m.cells, "triangle");

  const pugi::xml_node tags = grid(domain, "facet_tags");
  if (!tags)
    return m; // no named boundaries: usable without tags
  if (std::string(tags.child("Topology").attribute("TopologyType").as_string()) != "PolyLine")
    fail(path, "the facet tags are not lines (TopologyType \"PolyLine\")");
  m.facets = read_item<std::int64_t>(path, tags.child("Topology"), 2, "facet topology");
  check_nodes(m.facets, "facet");
  const auto values = read_item<std::int64_t>(path, tags.child("Attribute"), 1, "facet tag values");
  if (values.size() != m.facets.size() / 2)
    fail(path, "the number of facet tag values differs from the number of facets");
  m.facet_tags.assign(values.begin(), values.end());
  for (pugi::xml_node info : tags.children("Information"))
  {
    const std::string name = info.attribute("Name").as_string();
    if (name.empty() || !info.attribute("Value"))
      fail(path, "an <Information> of the facet tags lacks Name or Value");
    if (!m.tags.emplace(name, info.attribute("Value").as_int()).second)
      fail(path, "the tag name \"" + name + "\" is given twice");
  }
  return m;
}
} // namespace cellphase::scene
