#include "io/VtkWriter.h"
#include "io/XmlIndex.h"
#include "util/Mpi.h"
#include <basix/finite-element.h>
#include <dolfinx/io/VTKFile.h>
#include <algorithm>
#include <filesystem>
#include <functional>
#include <pugixml.hpp>
#include <stdexcept>

namespace cellphase
{
using namespace dolfinx;
namespace fs = std::filesystem;

namespace
{
pugi::xml_node collection_of(pugi::xml_document& index)
{
  return index.child("VTKFile").child("Collection");
}

/// DOLFINx 0.5.2 lists every rank's piece once per field in the .pvtu (readers then draw
/// each cell several times) and declares scalars with 0 components: list each piece once,
/// scalars with 1 component.
void repair_pvtu(const std::string& path)
{
  auto doc = xml_index::load(path);
  auto grid = doc.child("VTKFile").child("PUnstructuredGrid");
  std::vector<std::string> seen;
  std::vector<pugi::xml_node> repeated;
  for (auto piece : grid.children("Piece"))
  {
    const std::string source = piece.attribute("Source").value();
    if (std::find(seen.begin(), seen.end(), source) != seen.end())
      repeated.push_back(piece);
    else
      seen.push_back(source);
  }
  for (auto piece : repeated)
    grid.remove_child(piece);
  for (auto array : grid.child("PPointData").children("PDataArray"))
    if (auto n = array.attribute("NumberOfComponents"); n && n.as_int() == 0)
      n = "1";
  xml_index::save_atomically(doc, path);
}

double time_of(pugi::xml_node dataset)
{
  return dataset.attribute("timestep").as_double();
}

void new_index(pugi::xml_document& doc)
{
  doc.reset();
  auto vtk = doc.append_child("VTKFile");
  vtk.append_attribute("type") = "Collection";
  vtk.append_attribute("version") = "0.1";
  vtk.append_child("Collection");
}
} // namespace

VtkWriter::VtkWriter(MPI_Comm comm, const std::string& directory,
                       std::optional<double> resume_after_time, const std::string& stem)
    : comm_(comm), directory_(directory), stem_(stem)
{
  if (rank_of(comm_) != 0)
    return;
  fs::create_directories(directory_ + "/" + stem_);
  index_ = std::make_unique<pugi::xml_document>();
  // A restart continues the index, cut back to the checkpoint's time.
  if (xml_index::load_to_resume(*index_, index_path(), resume_after_time.has_value())
      && collection_of(*index_))
  {
    xml_index::remove_children(collection_of(*index_), "DataSet", [&](pugi::xml_node d)
                               { return time_of(d) > *resume_after_time; });
    return;
  }
  new_index(*index_);
}

VtkWriter::~VtkWriter() = default;

void VtkWriter::write(const FieldMap& fields, double time, int step)
{
  if (fields.empty())
    return;
  auto mesh = fields.begin()->second->function_space()->mesh(); // all fields share it
  if (mesh == mesh_ && last_time_ && *last_time_ == time)
    return; // a failed run writes its last good state, which may be the one written last
  if (mesh != mesh_)
  {
    mesh_ = mesh;
    const int tdim = mesh->topology().dim();
    auto cell = tdim == 2 ? basix::cell::type::triangle : basix::cell::type::tetrahedron;
    auto e = basix::create_element(basix::element::family::P, cell, 2,
                                   basix::element::lagrange_variant::equispaced, false);
    auto m = std::const_pointer_cast<Mesh>(mesh);
    p2_ = std::make_shared<Space>(fem::create_functionspace(m, e, 1));
    p2_vector_ = std::make_shared<Space>(fem::create_functionspace(m, e, tdim));
  }
  last_time_ = time;

  // DOLFINx's writer wants one element for all fields (up to the block size): P2.
  std::vector<Function> values;
  values.reserve(fields.size());
  for (const auto& [name, f] : fields)
  {
    const bool vector = f->function_space()->element()->value_size() > 1;
    values.emplace_back(vector ? p2_vector_ : p2_);
    values.back().name = name;
    compat::transfer(f, values.back());
  }
  std::vector<std::reference_wrapper<const Function>> refs(values.begin(), values.end());
  const std::string stem = xml_index::numbered("step", step);
  const std::string own_pvd = directory_ + "/" + stem_ + "/" + stem + ".pvd";
  {
    io::VTKFile out(comm_, own_pvd, "w");
    out.write(refs, time);
  } // closed: the .vtu files are complete before the index refers to them
  MPI_Barrier(comm_);
  if (!index_)
    return;

  auto written = xml_index::load(own_pvd);
  auto dataset = written.select_node("//DataSet").node();
  if (!dataset)
    throw std::runtime_error("'" + own_pvd + "' holds no DataSet");
  const std::string dataset_file = dataset.attribute("file").value();
  if (dataset_file.ends_with(".pvtu"))
    repair_pvtu(directory_ + "/" + stem_ + "/" + dataset_file);
  // A failed run writes its last good state again: it replaces the entry of that time.
  xml_index::remove_children(collection_of(*index_), "DataSet",
                             [&](pugi::xml_node d) { return time_of(d) == time; });
  auto entry = collection_of(*index_).append_child("DataSet");
  entry.append_attribute("timestep") = xml_index::time_text(time).c_str();
  entry.append_attribute("part") = "0";
  entry.append_attribute("file") = (stem_ + "/" + dataset_file).c_str();
  xml_index::save_atomically(*index_, index_path());
}
} // namespace cellphase
