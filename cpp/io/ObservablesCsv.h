// observables.csv: one row per step, written by rank 0 and flushed every row so that a
// killed run keeps what it computed.
#pragma once
#include "physics/Observables.h"
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace cellphase
{
struct StepRecord
{
  double time = 0;
  int step = 0;
  ObservableValues values;
  std::int64_t dofs = 0;
  double lam_v = 0, lam_a = 0;
  StepTimings timings;
  double remesh_time = 0, output_time = 0;
  double remesh_volume_change = 0; ///< relative, after correction (0 if no remesh this step)
  /// Columns of the sub-problems beyond the standard ones, appended in this order (the
  /// same names in every row).
  std::vector<std::pair<std::string, double>> extra;
};

/// One column of a row: its name, value and printf format (nullptr: an integer).
struct ObservableColumn
{
  std::string name;
  double value;
  const char* format;
};
/// The columns of observables.csv for a row, in file order: the standard ones, then the
/// sub-problems' (r.extra).
std::vector<ObservableColumn> observable_columns(const StepRecord& r, int dim);
/// (time, value) of each row of an observables.csv for one column; empty if there is no
/// such file or column.
std::vector<std::pair<double, double>> read_observable(const std::string& path,
                                                      const std::string& column);

class ObservablesCsv
{
public:
  /// A new file; or, with resume_after_step >= 0 (a restart), the existing file cut back
  /// to the rows up to that step and continued. If the run's columns differ from the
  /// file's (a checkpoint of an older version, another scene), the kept rows are written
  /// again under the new header, nan where they have no value, and a note names the change.
  ObservablesCsv(const std::string& path, int dim, MPI_Comm comm, int resume_after_step = -1);
  ~ObservablesCsv();
  void write(const StepRecord& r);

private:
  std::FILE* file_ = nullptr;
  int dim_;
  bool header_due_ = false; ///< the header (with the extra columns) precedes the first row
  bool check_header_ = false; ///< resumed: compare the file's header with the first row's
  std::string path_;
};
} // namespace cellphase
