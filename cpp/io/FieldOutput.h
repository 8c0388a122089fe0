// The field output of a run: every output time as one dataset holding all written fields
// on the shared mesh, indexed by one file that ParaView opens (docs/scenes.md, "Field
// output"). Two formats share this interface: XdmfWriter (fields.xdmf, the default) and
// VtkWriter (fields.pvd). Both are safe against a kill at any moment: the data of a time
// is complete on disk before the index, replaced atomically, refers to it.
#pragma once
#include "physics/PhaseFieldModule.h"
#include "scene/Scene.h"
#include <memory>
#include <optional>
#include <string>

namespace cellphase
{
class FieldOutput
{
public:
  virtual ~FieldOutput() = default;
  /// Append the fields (keyed by their output names, all on one mesh) at `time`, step
  /// `step`; a second write of the same time on the same mesh is skipped.
  virtual void write(const FieldMap& fields, double time, int step) = 0;
  /// The file users open (fields.xdmf or fields.pvd).
  virtual std::string index_path() const = 0;
};

/// The writer of `format` into `directory`: the index `stem`.xdmf (or .pvd) with its data
/// in `stem`/. With resume_after_time (a restart) the existing index is kept up to that
/// time and continued.
std::unique_ptr<FieldOutput> make_field_output(scene::OutputFormat format, MPI_Comm comm,
                                               const std::string& directory,
                                               std::optional<double> resume_after_time,
                                               const std::string& stem = "fields");
} // namespace cellphase
