// Fields as one XDMF time series (fields.xdmf): a temporal collection with one grid per
// output time, holding its mesh and every written field as point data, so that the reader
// ParaView picks colours, contours and clips by any field. Each time also gets a
// standalone file, fields/step-<n>.xdmf (the same grid; meshio.read opens it), its data in
// fields/step-<n>.h5, its mesh in fields/mesh-<m>.h5, written once and referred to while
// the mesh does not change. Every DataItem declares its precision (8-byte floats and
// integers). XDMF holds vertex values only, so P2 fields are written as P1 fields on the
// once uniformly refined mesh, whose vertices are the P2 nodes: no value is lost.
#pragma once
#include "io/FieldOutput.h"
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace pugi
{
class xml_document;
}

namespace cellphase
{
class XdmfWriter : public FieldOutput
{
public:
  /// The index `stem`.xdmf in `directory`, the data files in `stem`/.
  XdmfWriter(MPI_Comm comm, const std::string& directory,
             std::optional<double> resume_after_time = std::nullopt,
             const std::string& stem = "fields");
  ~XdmfWriter() override;
  void write(const FieldMap& fields, double time, int step) override;
  std::string index_path() const override { return directory_ + "/" + stem_ + ".xdmf"; }

private:
  /// Point the output at `mesh`: reuse the written mesh if it is the same, else refine
  /// and write it as fields/mesh-<step>.h5.
  void use_mesh(std::shared_ptr<const Mesh> mesh, int step);

  MPI_Comm comm_;
  std::string directory_;
  std::string stem_; ///< of the index and of the data folder
  std::unique_ptr<pugi::xml_document> index_; ///< rank 0 only
  std::shared_ptr<const Mesh> source_mesh_;  ///< mesh of the last written fields
  std::optional<std::uint64_t> source_fingerprint_;
  std::shared_ptr<Space> p1_;                ///< P1 on its uniform refinement
  std::shared_ptr<Space> p1_vector_;         ///< vector P1 there (velocity)
  /// source mesh -> p1_, p1_vector_: the nodes located once per mesh, not once per field
  /// (with many cells, fields.xdmf holds tens of fields on one mesh)
  std::unique_ptr<compat::MeshTransfer> to_p1_, to_p1_vector_;
  std::string mesh_file_;                    ///< fields/mesh-<m>.xdmf, written by DOLFINx
  std::optional<double> last_time_;
};
} // namespace cellphase
