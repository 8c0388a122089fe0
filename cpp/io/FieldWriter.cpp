#include "io/FieldWriter.h"
#include "util/Mpi.h"
#include <basix/finite-element.h>
#include <cstdio>
#include <dolfinx/io/XDMFFile.h>
#include <filesystem>
#include <pugixml.hpp>
#include <stdexcept>

namespace cellphase
{
using namespace dolfinx;
namespace fs = std::filesystem;

namespace
{
std::string numbered(const char* stem, int step)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s-%08d", stem, step);
  return buf;
}

/// The data files live in fields/, the index one directory up: prefix their paths.
void prefix_data_items(pugi::xml_node node)
{
  for (auto item : node.select_nodes(".//DataItem"))
  {
    pugi::xml_node text = item.node().first_child();
    text.set_value(("fields/" + std::string(text.value())).c_str());
  }
}

pugi::xml_document load_xml(const std::string& path)
{
  pugi::xml_document doc;
  if (!doc.load_file(path.c_str()))
    throw std::runtime_error("cannot read '" + path + "' just written by DOLFINx");
  return doc;
}

/// Drop the time steps after `time` and the meshes no step refers to any more.
void prune(pugi::xml_node domain, double time)
{
  for (auto series : domain.children("Grid"))
  {
    if (std::string(series.attribute("CollectionType").value()) != "Temporal")
      continue;
    std::vector<pugi::xml_node> late;
    for (auto g : series.children("Grid"))
      if (g.child("Time").attribute("Value").as_double() > time)
        late.push_back(g);
    for (auto g : late)
      series.remove_child(g);
  }
  std::vector<pugi::xml_node> unused;
  for (auto grid : domain.children("Grid"))
  {
    if (std::string(grid.attribute("GridType").value()) != "Uniform")
      continue;
    const std::string ref = "[@Name='" + std::string(grid.attribute("Name").value()) + "']";
    bool used = false;
    for (auto inc : domain.select_nodes(".//*[local-name()='include']"))
      used |= std::string(inc.node().attribute("xpointer").value()).find(ref) != std::string::npos;
    if (!used)
      unused.push_back(grid);
  }
  for (auto g : unused)
    domain.remove_child(g);
}
} // namespace

FieldWriter::FieldWriter(MPI_Comm comm, const std::string& directory,
                         std::optional<double> resume_after_time)
    : comm_(comm), directory_(directory)
{
  if (rank_of(comm_) != 0)
    return;
  fs::create_directories(directory_ + "/fields");
  index_ = std::make_unique<pugi::xml_document>();
  if (resume_after_time && fs::exists(index_path()) && index_->load_file(index_path().c_str()))
  {
    prune(index_->child("Xdmf").child("Domain"), *resume_after_time);
    return;
  }
  index_->reset();
  auto xdmf = index_->append_child("Xdmf");
  xdmf.append_attribute("Version") = "3.0";
  xdmf.append_attribute("xmlns:xi") = "http://www.w3.org/2001/XInclude";
  xdmf.append_child("Domain");
}

FieldWriter::~FieldWriter() = default;

void FieldWriter::save_index() const
{
  const std::string tmp = index_path() + ".tmp";
  if (!index_->save_file(tmp.c_str(), "  "))
    throw std::runtime_error("cannot write '" + tmp + "'");
  fs::rename(tmp, index_path());
}

void FieldWriter::write_mesh(std::shared_ptr<const Mesh> mesh, int step)
{
  source_mesh_ = mesh;
  auto fine = compat::refine_uniform(*mesh);
  mesh_name_ = numbered("mesh", step);
  fine->name = mesh_name_;
  const int tdim = fine->topology().dim();
  auto cell = tdim == 2 ? basix::cell::type::triangle : basix::cell::type::tetrahedron;
  auto e = basix::create_element(basix::element::family::P, cell, 1,
                                 basix::element::lagrange_variant::equispaced, false);
  p1_ = std::make_shared<Space>(fem::create_functionspace(fine, e, 1));
  p1_vector_ = std::make_shared<Space>(fem::create_functionspace(fine, e, tdim));

  const std::string file = directory_ + "/fields/" + mesh_name_ + ".xdmf";
  {
    io::XDMFFile out(comm_, file, "w");
    out.write_mesh(*fine);
  } // closed: the mesh is complete on disk before the index refers to it
  MPI_Barrier(comm_);
  if (!index_)
    return;
  auto written = load_xml(file);
  auto grid = written.select_node(("//Grid[@Name='" + mesh_name_ + "']").c_str()).node();
  auto domain = index_->child("Xdmf").child("Domain");
  // Meshes first, as DOLFINx writes them (insert_copy_before needs an existing child).
  auto copy = domain.first_child() ? domain.insert_copy_before(grid, domain.first_child())
                                   : domain.append_copy(grid);
  prefix_data_items(copy);
}

void FieldWriter::write(const FieldMap& fields, double time, int step)
{
  if (fields.empty())
    return;
  auto mesh = fields.begin()->second->function_space()->mesh(); // all fields share it
  // A failed run writes its last good state, which may be the one written last.
  if (mesh == source_mesh_ && last_time_ && *last_time_ == time)
    return;
  if (mesh != source_mesh_)
    write_mesh(mesh, step);
  last_time_ = time;

  const std::string mesh_xpath = "/Xdmf/Domain/Grid[@Name='" + mesh_name_ + "']";
  const std::string file = directory_ + "/fields/" + numbered("step", step) + ".xdmf";
  std::vector<std::string> written_names;
  {
    io::XDMFFile out(comm_, file, "w");
    // The caller chose the fields (output.fields, with phi_<group> for every cell's phi).
    for (auto it = fields.begin(); it != fields.end(); ++it)
    {
      const std::string& name = it->first;
      // Vector fields (the velocity) as vector P1; the pressure (P1) loses nothing either.
      const bool vector = it->second->function_space()->element()->value_size() > 1;
      Function u(vector ? p1_vector_ : p1_);
      u.name = name;
      compat::transfer(it->second, u);
      // The data file's own XML is not used (the index points at its datasets); give it an
      // element that exists so that DOLFINx does not warn about the mesh living elsewhere.
      out.write_function(u, time, "/Xdmf/Domain");
      written_names.push_back(name);
    }
  }
  MPI_Barrier(comm_);
  if (!index_)
    return;

  auto written = load_xml(file);
  auto domain = index_->child("Xdmf").child("Domain");
  char time_text[64];
  std::snprintf(time_text, sizeof time_text, "%.17g", time);
  for (const auto& name : written_names)
  {
    const std::string series_path = "Grid[@Name='" + name + "'][@CollectionType='Temporal']";
    auto attribute = written.select_node(("//" + series_path + "/Grid/Attribute").c_str()).node();
    if (!attribute)
      throw std::runtime_error("'" + file + "' holds no field " + name);
    auto series = domain.select_node(series_path.c_str()).node();
    if (!series)
    {
      series = domain.append_child("Grid");
      series.append_attribute("Name") = name.c_str();
      series.append_attribute("GridType") = "Collection";
      series.append_attribute("CollectionType") = "Temporal";
    }
    auto grid = series.append_child("Grid");
    grid.append_attribute("Name") = name.c_str();
    grid.append_attribute("GridType") = "Uniform";
    grid.append_child("xi:include").append_attribute("xpointer") =
        ("xpointer(" + mesh_xpath + "/*[self::Topology or self::Geometry])").c_str();
    grid.append_child("Time").append_attribute("Value") = time_text;
    prefix_data_items(grid.append_copy(attribute));
  }
  save_index();
}
} // namespace cellphase
