// How many CPUs one MPI rank may use, to decide whether independent work can run on a
// second thread without taking a core from another rank.
#pragma once
#include <cstdlib>
#include <mpi.h>
#include <sched.h>
#include <string>
#include <thread>

namespace cellphase
{
/// CPUs of this rank: its affinity mask when mpirun bound it to some of the node's CPUs,
/// else the node's CPUs shared among the ranks on it; capped by OMP_NUM_THREADS when that
/// is a positive number.
inline int cpus_per_rank(MPI_Comm comm)
{
  cpu_set_t set;
  CPU_ZERO(&set);
  int n = sched_getaffinity(0, sizeof(set), &set) == 0 ? CPU_COUNT(&set) : 1;
  if (n >= static_cast<int>(std::thread::hardware_concurrency()))
  {
    MPI_Comm node;
    MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    int ranks;
    MPI_Comm_size(node, &ranks);
    MPI_Comm_free(&node);
    n = std::max(1, n / ranks);
  }
  if (const char* limit = std::getenv("OMP_NUM_THREADS"))
  {
    try
    {
      const int m = std::stoi(limit);
      if (m > 0 && m < n)
        n = m;
    }
    catch (const std::exception&)
    {
      // not a number: no limit (as for OpenMP)
    }
  }
  return n;
}
} // namespace cellphase
