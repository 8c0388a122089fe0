#include "app/CheckpointStore.h"
#include "util/Mpi.h"
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace cellphase
{
namespace fs = std::filesystem;
namespace
{
/// Checkpoint files of dir, newest (highest step) first. Temporary files are not listed.
std::vector<fs::path> list_checkpoints(const std::string& dir)
{
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
  {
    const std::string name = e.path().filename().string();
    if (name.rfind("checkpoint-", 0) == 0 && e.path().extension() == ".cpk")
      files.push_back(e.path());
  }
  // Zero-padded step numbers sort by name.
  std::sort(files.rbegin(), files.rend());
  return files;
}

void broadcast(MPI_Comm comm, std::string& bytes)
{
  unsigned long long n = bytes.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  bytes.resize(n);
  // MPI counts are int: send in pieces below 1 GiB.
  for (unsigned long long off = 0; off < n; off += (1ull << 30))
    MPI_Bcast(bytes.data() + off, int(std::min<unsigned long long>(n - off, 1ull << 30)),
              MPI_CHAR, 0, comm);
}
} // namespace

CheckpointStore::CheckpointStore(MPI_Comm comm, const std::string& run_directory, int keep)
    : comm_(comm), dir_(run_directory + "/checkpoints"), keep_(keep)
{
}

std::string CheckpointStore::save(const CheckpointData& data, int step) const
{
  char name[64];
  std::snprintf(name, sizeof name, "/checkpoint-%08d.cpk", step);
  const std::string path = dir_ + name;
  if (rank_of(comm_) == 0)
  {
    fs::create_directories(dir_);
    write_file_atomically(path, encode(data));
    auto files = list_checkpoints(dir_);
    for (std::size_t i = std::size_t(keep_); i < files.size(); ++i)
      fs::remove(files[i]);
  }
  MPI_Barrier(comm_);
  return path;
}

CheckpointData CheckpointStore::load_newest(std::string& path) const
{
  std::string bytes;
  path.clear();
  if (rank_of(comm_) == 0)
  {
    for (const auto& file : list_checkpoints(dir_))
    {
      try
      {
        std::string b = read_file(file.string());
        decode(b); // verify before choosing it
        bytes = std::move(b);
        path = file.string();
        break;
      }
      catch (const CheckpointError& e)
      {
        std::printf("cellphase: skipping checkpoint %s: %s\n", file.string().c_str(), e.what());
        std::fflush(stdout);
      }
    }
  }
  broadcast(comm_, bytes);
  if (bytes.empty())
    throw CheckpointError("no valid checkpoint in " + dir_);
  broadcast(comm_, path);
  return decode(bytes);
}
} // namespace cellphase
