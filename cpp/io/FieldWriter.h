// Fields as one XDMF time series that ParaView opens (fields.xdmf), safe against a kill at
// any moment. Each output time goes to a file of its own, fields/step-<n>.h5 (and each mesh
// to fields/mesh-<n>.h5), closed before the next one starts; only then does fields.xdmf,
// rewritten under a temporary name and renamed, point at it. A killed run so leaves an
// index that refers to complete files only.
// The mesh changes at every remesh; each mesh is a grid of its own and every time step
// points at its mesh. XDMF holds vertex values only, so P2 fields are written as P1 fields
// on the once uniformly refined mesh, whose vertices are the P2 nodes: no value is lost.
#pragma once
#include "compat/Dolfinx.h"
#include "physics/PhaseFieldModule.h"
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pugi
{
class xml_document;
}

namespace cellphase
{
class FieldWriter
{
public:
  /// Index `directory`/`index_name` with the data files in `directory`/fields/. With
  /// resume_after_time (a restart), the existing index is kept up to that time and continued.
  FieldWriter(MPI_Comm comm, const std::string& directory,
              std::optional<double> resume_after_time = std::nullopt);
  ~FieldWriter();
  /// Append the fields (keyed by their output names) at `time` (step `step`); a second write of the same time on the same
  /// mesh is skipped.
  void write(const FieldMap& fields, double time, int step);
  std::string index_path() const { return directory_ + "/fields.xdmf"; }

private:
  void write_mesh(std::shared_ptr<const Mesh> mesh, int step);
  void save_index() const;

  MPI_Comm comm_;
  std::string directory_;
  std::unique_ptr<pugi::xml_document> index_; ///< rank 0 only
  std::shared_ptr<const Mesh> source_mesh_;  ///< mesh of the last written fields
  std::shared_ptr<Space> p1_;                ///< P1 on its uniform refinement
  std::shared_ptr<Space> p1_vector_;         ///< vector P1 there (velocity)
  std::string mesh_name_;
  std::optional<double> last_time_;
};
} // namespace cellphase
