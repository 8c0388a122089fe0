#include "io/FieldWriter.h"
#include <basix/finite-element.h>

namespace cellphase
{
using namespace dolfinx;

FieldWriter::FieldWriter(MPI_Comm comm, const std::string& path, std::vector<std::string> fields)
    : file_(comm, path, "w"), names_(std::move(fields))
{
}

void FieldWriter::write(const FieldMap& fields, double time)
{
  // A failed run writes its last good state, which may be the one written last.
  if (meshes_written_ > 0 && time == last_time_ && fields.at("phi")->function_space()->mesh() == source_mesh_)
    return;
  last_time_ = time;
  auto mesh = fields.at("phi")->function_space()->mesh();
  if (mesh != source_mesh_)
  {
    source_mesh_ = mesh;
    auto fine = compat::refine_uniform(*mesh);
    fine->name = "mesh" + std::to_string(meshes_written_++);
    const int tdim = fine->topology().dim();
    auto cell = tdim == 2 ? basix::cell::type::triangle : basix::cell::type::tetrahedron;
    auto e = basix::create_element(basix::element::family::P, cell, 1,
                                   basix::element::lagrange_variant::equispaced, false);
    p1_ = std::make_shared<Space>(fem::create_functionspace(fine, e, 1));
    file_.write_mesh(*fine);
    mesh_xpath_ = "/Xdmf/Domain/Grid[@Name='" + fine->name + "']";
  }
  for (const auto& name : names_)
  {
    auto it = fields.find(name);
    if (it == fields.end())
      continue;
    Function out(p1_);
    out.name = name;
    compat::transfer(it->second, out);
    file_.write_function(out, time, mesh_xpath_);
  }
}
} // namespace cellphase
