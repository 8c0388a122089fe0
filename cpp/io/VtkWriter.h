// Fields as a VTK time series (fields.pvd): one dataset per output time,
// fields/step-<n>.vtu (.pvtu with one piece per rank under mpirun), written by DOLFINx's
// VTK writer with second-order Lagrange cells, so P2 fields are kept exactly and
// ParaView draws them on curved cells. Every field goes through P2 on the shared mesh
// (the P1 pressure exactly). fields.pvd is ours, replaced atomically once a time's files
// are complete; DOLFINx's own step-<n>.pvd beside them opens on its own as well.
#pragma once
#include "io/FieldOutput.h"
#include <memory>
#include <optional>
#include <string>

namespace pugi
{
class xml_document;
}

namespace cellphase
{
class VtkWriter : public FieldOutput
{
public:
  /// The index `stem`.pvd in `directory`, the data files in `stem`/.
  VtkWriter(MPI_Comm comm, const std::string& directory,
            std::optional<double> resume_after_time = std::nullopt,
            const std::string& stem = "fields");
  ~VtkWriter() override;
  void write(const FieldMap& fields, double time, int step) override;
  std::string index_path() const override { return directory_ + "/" + stem_ + ".pvd"; }

private:
  MPI_Comm comm_;
  std::string directory_;
  std::string stem_; ///< of the index and of the data folder
  std::unique_ptr<pugi::xml_document> index_; ///< rank 0 only
  std::shared_ptr<const Mesh> mesh_;         ///< mesh of the spaces below
  std::shared_ptr<Space> p2_, p2_vector_;
  std::optional<double> last_time_;
};
} // namespace cellphase
