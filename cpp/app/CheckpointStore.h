// The checkpoints of one run directory: <dir>/checkpoints/checkpoint-<step>.cpk. Rank 0
// writes and reads the files; every rank gets the decoded content.
#pragma once
#include "io/CheckpointFile.h"
#include <mpi.h>
#include <string>

namespace cellphase
{
class CheckpointStore
{
public:
  CheckpointStore(MPI_Comm comm, const std::string& run_directory, int keep);
  /// Write the checkpoint of `step` (data gathered on rank 0) and delete all but the
  /// newest `keep`. Returns its path.
  std::string save(const CheckpointData& data, int step) const;
  /// The newest checkpoint that verifies, on every rank; damaged ones are skipped with a
  /// message on stdout. Throws CheckpointError if none is valid.
  CheckpointData load_newest(std::string& path) const;
  const std::string& directory() const { return dir_; }

private:
  MPI_Comm comm_;
  std::string dir_;
  int keep_;
};
} // namespace cellphase
