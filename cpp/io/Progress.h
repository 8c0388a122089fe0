// A progress line on rank 0 every few seconds: step, time, percentage, remaining time.
#pragma once
#include <chrono>
#include <mpi.h>

namespace cellphase
{
class Progress
{
public:
  Progress(MPI_Comm comm, double end_time, bool enabled);
  void update(int step, double time);
  void finish(int step, double time);

private:
  bool enabled_;
  double end_time_;
  std::chrono::steady_clock::time_point start_, last_;
};
} // namespace cellphase
