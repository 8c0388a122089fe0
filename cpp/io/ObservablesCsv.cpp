#include "io/ObservablesCsv.h"
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace cellphase
{
namespace
{
const char* header = "time,step,volume,surface,helfrich_energy,total_energy,energy_ch,"
                     "center_x,center_y,center_z,circularity,phi_min,phi_max,lambda_volume,"
                     "lambda_area,dofs,remesh_volume_change,wall_assembly,wall_factorise,"
                     "wall_solve,wall_remesh,wall_output,"
                     // appended with the flow coupling; readers find columns by name
                     "kinetic_energy,total_energy_kinetic,cell_velocity_x,cell_velocity_y,"
                     "cell_velocity_z,rise_velocity,inclination_deg,wall_flow,"
                     // the membrane's local stretching; the mean multiplier of (3.67)
                     "stretch_min,stretch_max,tension_mean";

/// Rows of an existing file up to `step` (complete lines only: a killed run may have left
/// half a row), written back atomically. Returns false if there is no such file.
bool cut_back(const std::string& path, int step)
{
  std::ifstream in(path);
  if (!in)
    return false;
  std::string line, kept;
  std::getline(in, line);
  kept = line + "\n";
  while (std::getline(in, line) && !in.eof())
  {
    const auto comma = line.find(',');
    if (comma == std::string::npos || std::atoi(line.c_str() + comma + 1) > step)
      break;
    kept += line + "\n";
  }
  const std::string tmp = path + ".tmp";
  std::ofstream(tmp) << kept;
  std::filesystem::rename(tmp, path);
  return true;
}
} // namespace

ObservablesCsv::ObservablesCsv(const std::string& path, int dim, MPI_Comm comm,
                               int resume_after_step)
    : dim_(dim)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0)
    return;
  const bool resume = resume_after_step >= 0 && cut_back(path, resume_after_step);
  file_ = std::fopen(path.c_str(), resume ? "a" : "w");
  if (!file_)
    throw std::runtime_error("cannot write '" + path + "'");
  header_due_ = !resume;
}

ObservablesCsv::~ObservablesCsv()
{
  if (file_)
    std::fclose(file_);
}

void ObservablesCsv::write(const StepRecord& r)
{
  if (!file_)
    return;
  if (header_due_)
  {
    std::fputs(header, file_);
    for (const auto& [name, value] : r.extra)
      std::fprintf(file_, ",%s", name.c_str());
    std::fputs("\n", file_);
    header_due_ = false;
  }
  const auto& v = r.values;
  std::fprintf(file_,
               "%.10g,%d,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.10g,%.10g,"
               "%.10g,%.10g,%lld,%.3e,%.4g,%.4g,%.4g,%.4g,%.4g,"
               "%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.10g,%.4g,%.10g,%.10g,%.10g",
               r.time, r.step, v.volume, v.surface, v.helfrich, v.total_energy, v.energy_ch,
               v.center[0], v.center[1], dim_ == 3 ? v.center[2] : 0.0, v.circularity,
               v.phi_min, v.phi_max, r.lam_v, r.lam_a, (long long)r.dofs,
               r.remesh_volume_change, r.timings.assemble, r.timings.factorise, r.timings.solve,
               r.remesh_time, r.output_time, v.kinetic_energy, v.total_with_kinetic,
               v.cell_velocity[0], v.cell_velocity[1], dim_ == 3 ? v.cell_velocity[2] : 0.0,
               v.cell_velocity[1], v.inclination_deg, r.timings.flow, v.stretch_min, v.stretch_max,
               v.tension_mean);
  for (const auto& [name, value] : r.extra)
    std::fprintf(file_, ",%.15g", value);
  std::fputs("\n", file_);
  std::fflush(file_);
}
} // namespace cellphase
