#include "io/FieldOutput.h"
#include "io/VtkWriter.h"
#include "io/XdmfWriter.h"

namespace cellphase
{
std::unique_ptr<FieldOutput> make_field_output(scene::OutputFormat format, MPI_Comm comm,
                                               const std::string& directory,
                                               std::optional<double> resume_after_time,
                                               const std::string& stem)
{
  if (format == scene::OutputFormat::vtk)
    return std::make_unique<VtkWriter>(comm, directory, resume_after_time, stem);
  return std::make_unique<XdmfWriter>(comm, directory, resume_after_time, stem);
}
} // namespace cellphase
