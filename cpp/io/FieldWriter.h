// Fields to one XDMF/HDF5 time series that ParaView opens (fields.xdmf). The mesh changes
// at every remesh, so each mesh is written under its own name and every time step points
// at its mesh. XDMF holds vertex values only, so P2 fields are written as P1 fields on the
// once uniformly refined mesh, whose vertices are the P2 nodes: no value is lost.
#pragma once
#include "compat/Dolfinx.h"
#include "physics/PhaseFieldModule.h"
#include <dolfinx/io/XDMFFile.h>
#include <string>
#include <vector>

namespace cellphase
{
class FieldWriter
{
public:
  FieldWriter(MPI_Comm comm, const std::string& path, std::vector<std::string> fields);
  /// Append the fields at `time`; a second write of the same time on the same mesh is skipped.
  void write(const FieldMap& fields, double time);

private:
  dolfinx::io::XDMFFile file_;
  std::vector<std::string> names_;
  std::shared_ptr<const Mesh> source_mesh_;  ///< mesh of the last written fields
  std::shared_ptr<Space> p1_;                ///< P1 on its uniform refinement
  std::string mesh_xpath_;
  int meshes_written_ = 0;
  double last_time_ = 0;
};
} // namespace cellphase
