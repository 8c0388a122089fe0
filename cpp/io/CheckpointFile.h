// One checkpoint as a self-verifying binary file: named arrays of doubles and named texts,
// followed by the payload size and a 64-bit FNV-1a hash. It is written under a temporary
// name, flushed to disk and renamed, so a run killed during the write never leaves a
// half-written file under a checkpoint's name; a damaged file is detected when it is read.
#pragma once
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace cellphase
{
/// A checkpoint file that is missing, truncated or corrupt; the message says which and why.
struct CheckpointError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct CheckpointData
{
  std::map<std::string, std::vector<double>> arrays;
  std::map<std::string, std::string> texts;

  void set(const std::string& name, double value) { arrays[name] = {value}; }
  /// A scalar stored with set(); throws CheckpointError naming the entry if absent.
  double scalar(const std::string& name) const;
  const std::vector<double>& array(const std::string& name) const;
  const std::string& text(const std::string& name) const;
};

/// Serialise with the trailing size and hash.
std::string encode(const CheckpointData& data);
/// Parse and verify; throws CheckpointError ("truncated", "hash mismatch", ...).
CheckpointData decode(const std::string& bytes);

/// Write `bytes` to path atomically: path.tmp, fsync, rename.
void write_file_atomically(const std::string& path, const std::string& bytes);
/// Whole file as bytes; throws CheckpointError if it cannot be read.
std::string read_file(const std::string& path);
} // namespace cellphase
