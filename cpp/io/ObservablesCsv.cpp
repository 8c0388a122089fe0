#include "io/ObservablesCsv.h"
#include "util/Split.h"
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace cellphase
{
namespace
{
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
  check_header_ = resume;
  path_ = path;
}

namespace
{
/// The file's rows under the header `names`, by column name ("nan" where a row has none).
/// Returns the columns added and dropped, or "" if the header is `names` already.
std::string rewrite_under(const std::string& path, const std::vector<std::string>& names)
{
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const auto old_names = split(line);
  if (old_names == names)
    return "";
  std::string text, added, dropped;
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    text += (i ? "," : "") + names[i];
    if (std::find(old_names.begin(), old_names.end(), names[i]) == old_names.end())
      added += " " + names[i];
  }
  for (const auto& n : old_names)
    if (std::find(names.begin(), names.end(), n) == names.end())
      dropped += " " + n;
  text += "\n";
  while (std::getline(in, line))
  {
    const auto cells = split(line);
    for (std::size_t i = 0; i < names.size(); ++i)
    {
      auto it = std::find(old_names.begin(), old_names.end(), names[i]);
      const std::size_t k = it - old_names.begin();
      text += (i ? "," : "") + (k < cells.size() ? cells[k] : std::string("nan"));
    }
    text += "\n";
  }
  in.close();
  const std::string tmp = path + ".tmp";
  std::ofstream(tmp) << text;
  std::filesystem::rename(tmp, path);
  return (added.empty() ? "" : "added" + added) + (!added.empty() && !dropped.empty() ? "; " : "")
         + (dropped.empty() ? "" : "dropped" + dropped);
}
} // namespace

ObservablesCsv::~ObservablesCsv()
{
  if (file_)
    std::fclose(file_);
}

std::vector<ObservableColumn> observable_columns(const StepRecord& r, int dim)
{
  const auto& v = r.values;
  const double z = dim == 3 ? v.center[2] : 0.0, vz = dim == 3 ? v.cell_velocity[2] : 0.0;
  const char *g15 = "%.15g", *g10 = "%.10g", *g4 = "%.4g", *integer = nullptr;
  std::vector<ObservableColumn> c{
      {"time", r.time, g10}, {"step", double(r.step), integer},
      {"volume", v.volume, g15}, {"surface", v.surface, g15},
      {"helfrich_energy", v.helfrich, g15}, {"total_energy", v.total_energy, g15},
      {"energy_ch", v.energy_ch, g15}, {"center_x", v.center[0], g15},
      {"center_y", v.center[1], g15}, {"center_z", z, g15},
      {"circularity", v.circularity, g15}, {"phi_min", v.phi_min, g10},
      {"phi_max", v.phi_max, g10}, {"lambda_volume", r.lam_v, g10},
      {"lambda_area", r.lam_a, g10}, {"dofs", double(r.dofs), integer},
      {"remesh_volume_change", r.remesh_volume_change, "%.3e"},
      {"wall_assembly", r.timings.assemble, g4}, {"wall_factorise", r.timings.factorise, g4},
      {"wall_solve", r.timings.solve, g4}, {"wall_remesh", r.remesh_time, g4},
      {"wall_output", r.output_time, g4},
      // appended with the flow coupling; readers find columns by name
      {"kinetic_energy", v.kinetic_energy, g15},
      {"total_energy_kinetic", v.total_with_kinetic, g15},
      {"cell_velocity_x", v.cell_velocity[0], g15}, {"cell_velocity_y", v.cell_velocity[1], g15},
      {"cell_velocity_z", vz, g15}, {"rise_velocity", v.cell_velocity[1], g15},
      {"inclination_deg", v.inclination_deg, g10}, {"wall_flow", r.timings.flow, g4},
      // the membrane's local stretching; the mean multiplier of (3.67)
      {"stretch_min", v.stretch_min, g10}, {"stretch_max", v.stretch_max, g10},
      {"tension_mean", v.tension_mean, g10}};
  for (const auto& [name, value] : r.extra)
    c.push_back({name, value, g15});
  return c;
}

void ObservablesCsv::write(const StepRecord& r)
{
  if (!file_)
    return;
  const auto columns = observable_columns(r, dim_);
  if (check_header_)
  {
    check_header_ = false;
    std::vector<std::string> names;
    for (const auto& c : columns)
      names.push_back(c.name);
    std::fclose(file_);
    const std::string change = rewrite_under(path_, names);
    if (!change.empty())
      std::fprintf(stderr, "cellphase: note: the observables' columns differ from those of %s "
                           "(%s); its rows before the restart are written again under the new "
                           "header, nan where they have no value\n", path_.c_str(), change.c_str());
    file_ = std::fopen(path_.c_str(), "a");
    if (!file_)
      throw std::runtime_error("cannot write '" + path_ + "'");
  }
  if (header_due_)
  {
    for (std::size_t i = 0; i < columns.size(); ++i)
      std::fprintf(file_, i ? ",%s" : "%s", columns[i].name.c_str());
    std::fputs("\n", file_);
    header_due_ = false;
  }
  for (std::size_t i = 0; i < columns.size(); ++i)
  {
    if (i)
      std::fputc(',', file_);
    if (columns[i].format)
      std::fprintf(file_, columns[i].format, columns[i].value);
    else
      std::fprintf(file_, "%lld", (long long)columns[i].value);
  }
  std::fputs("\n", file_);
  std::fflush(file_);
}

std::vector<std::pair<double, double>> read_observable(const std::string& path,
                                                      const std::string& column)
{
  std::ifstream in(path);
  std::string line;
  std::vector<std::pair<double, double>> rows;
  if (!std::getline(in, line))
    return rows;
  const auto names = split(line);
  const std::size_t index = std::find(names.begin(), names.end(), column) - names.begin();
  if (index == names.size())
    return rows;
  while (std::getline(in, line))
  {
    const auto cells = split(line);
    if (cells.size() > index)
      rows.emplace_back(std::atof(cells[0].c_str()), std::atof(cells[index].c_str()));
  }
  return rows;
}
} // namespace cellphase
