#include "io/XdmfWriter.h"
#include "io/MeshFingerprint.h"
#include "io/XmlIndex.h"
#include "util/Mpi.h"
#include <basix/finite-element.h>
#include <dolfinx/io/XDMFFile.h>
#include <filesystem>
#include <pugixml.hpp>
#include <stdexcept>

namespace cellphase
{
using namespace dolfinx;
namespace fs = std::filesystem;
using xml_index::numbered;

namespace
{
constexpr const char* series_name = "fields";

/// DOLFINx 0.5 declares no precision, and readers then take Float as 4 bytes: every
/// array we write is 8 bytes wide (float64 data, int64 cells).
void declare_precision(pugi::xml_node node)
{
  for (auto item : node.select_nodes(".//DataItem"))
  {
    pugi::xml_node n = item.node();
    if (!n.attribute("NumberType"))
      n.append_attribute("NumberType") = "Float";
    if (!n.attribute("Precision"))
      n.append_attribute("Precision") = "8";
  }
}

/// Data paths are relative to the file that holds them: `prefix` them for the index.
void prefix_data_items(pugi::xml_node node, const std::string& prefix)
{
  for (auto item : node.select_nodes(".//DataItem"))
  {
    pugi::xml_node text = item.node().first_child();
    text.set_value((prefix + text.value()).c_str());
  }
}

pugi::xml_node new_xdmf(pugi::xml_document& doc)
{
  doc.reset();
  auto xdmf = doc.append_child("Xdmf");
  xdmf.append_attribute("Version") = "3.0";
  return xdmf.append_child("Domain");
}

double time_of(pugi::xml_node grid)
{
  return grid.child("Time").attribute("Value").as_double();
}

/// The temporal collection of the index, created if missing.
pugi::xml_node series_of(pugi::xml_document& index)
{
  auto domain = index.child("Xdmf").child("Domain");
  auto series = domain.find_child_by_attribute("Grid", "Name", series_name);
  if (series)
    return series;
  series = domain.append_child("Grid");
  series.append_attribute("Name") = series_name;
  series.append_attribute("GridType") = "Collection";
  series.append_attribute("CollectionType") = "Temporal";
  return series;
}
} // namespace

XdmfWriter::XdmfWriter(MPI_Comm comm, const std::string& directory,
                       std::optional<double> resume_after_time, const std::string& stem)
    : comm_(comm), directory_(directory), stem_(stem)
{
  if (rank_of(comm_) != 0)
    return;
  fs::create_directories(directory_ + "/" + stem_);
  index_ = std::make_unique<pugi::xml_document>();
  // A restart continues the index of the interrupted run, cut back to the checkpoint; an
  // index of another layout (an older cellphase) is started afresh.
  if (xml_index::load_to_resume(*index_, index_path(), resume_after_time.has_value())
      && index_->child("Xdmf").child("Domain").find_child_by_attribute("Grid", "Name",
                                                                       series_name))
  {
    xml_index::remove_children(series_of(*index_), "Grid", [&](pugi::xml_node g)
                               { return time_of(g) > *resume_after_time; });
    return;
  }
  new_xdmf(*index_);
  series_of(*index_);
}

XdmfWriter::~XdmfWriter() = default;

void XdmfWriter::use_mesh(std::shared_ptr<const Mesh> mesh, int step)
{
  const std::uint64_t fingerprint = mesh_fingerprint(*mesh);
  source_mesh_ = mesh;
  to_p1_.reset();
  to_p1_vector_.reset();
  // The same nodes and cells as the written mesh (a remesh that changed nothing): keep the
  // refined mesh, its spaces and its file; the fields are evaluated on it all the same.
  if (source_fingerprint_ == fingerprint)
    return;
  source_fingerprint_ = fingerprint;
  auto fine = compat::refine_uniform(*mesh);
  const std::string name = numbered("mesh", step);
  fine->name = name;
  const int tdim = fine->topology().dim();
  auto cell = tdim == 2 ? basix::cell::type::triangle : basix::cell::type::tetrahedron;
  auto e = basix::create_element(basix::element::family::P, cell, 1,
                                 basix::element::lagrange_variant::equispaced, false);
  p1_ = std::make_shared<Space>(fem::create_functionspace(fine, e, 1));
  p1_vector_ = std::make_shared<Space>(fem::create_functionspace(fine, e, tdim));
  mesh_file_ = directory_ + "/" + stem_ + "/" + name + ".xdmf";
  {
    io::XDMFFile out(comm_, mesh_file_, "w");
    out.write_mesh(*fine);
  } // closed: the mesh is complete on disk before any index refers to it
  MPI_Barrier(comm_);
}

void XdmfWriter::write(const FieldMap& fields, double time, int step)
{
  if (fields.empty())
    return;
  auto mesh = fields.begin()->second->function_space()->mesh(); // all fields share it
  // A failed run writes its last good state, which may be the one written last.
  if (mesh == source_mesh_ && last_time_ && *last_time_ == time)
    return;
  if (mesh != source_mesh_)
    use_mesh(mesh, step);
  last_time_ = time;

  const std::string stem = numbered("step", step);
  const std::string file = directory_ + "/" + stem_ + "/" + stem + ".xdmf";
  {
    io::XDMFFile out(comm_, file, "w");
    for (auto it = fields.begin(); it != fields.end(); ++it)
    {
      // Vector fields (the velocity) as vector P1; the pressure (P1) loses nothing either.
      const bool vector = it->second->function_space()->element()->value_size() > 1;
      Function u(vector ? p1_vector_ : p1_);
      u.name = it->first;
      auto& to = vector ? to_p1_vector_ : to_p1_;
      if (!to)
        to = std::make_unique<compat::MeshTransfer>(mesh, u.function_space());
      to->apply(*it->second, u);
      // Only the data of this file is used: the grid below is composed from it. Give
      // DOLFINx an element that exists so that it does not warn about the mesh.
      out.write_function(u, time, "/Xdmf/Domain");
    }
  }
  MPI_Barrier(comm_);
  if (!index_)
    return;

  // One grid: the mesh's Topology and Geometry, the time, every field's Attribute.
  auto written = xml_index::load(file);
  auto mesh_xml = xml_index::load(mesh_file_);
  auto mesh_grid = mesh_xml.select_node("//Grid[@GridType='Uniform']").node();
  pugi::xml_document standalone;
  auto grid = new_xdmf(standalone).append_child("Grid");
  grid.append_attribute("Name") = series_name;
  grid.append_attribute("GridType") = "Uniform";
  grid.append_copy(mesh_grid.child("Topology"));
  grid.append_copy(mesh_grid.child("Geometry"));
  for (const auto& [name, f] : fields)
  {
    auto attribute = written.select_node(("//Grid[@Name='" + name + "']/Grid/Attribute").c_str());
    if (!attribute)
      throw std::runtime_error("'" + file + "' holds no field " + name);
    grid.append_copy(attribute.node());
  }
  declare_precision(grid);
  // The standalone file replaces DOLFINx's, whose grids point at a mesh it lacks. It has
  // no Time element (meshio.read refuses one in a single grid): the index holds the time.
  xml_index::save_atomically(standalone, file);

  // A failed run writes its last good state again, on the mesh the state was kept on:
  // it replaces the entry of that time.
  xml_index::remove_children(series_of(*index_), "Grid",
                             [&](pugi::xml_node g) { return time_of(g) == time; });
  auto entry = series_of(*index_).append_copy(grid);
  entry.insert_child_before("Time", entry.child("Attribute")).append_attribute("Value") =
      xml_index::time_text(time).c_str();
  prefix_data_items(entry, stem_ + "/");
  xml_index::save_atomically(*index_, index_path());
}
} // namespace cellphase
