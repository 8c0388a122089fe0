// A progress line on rank 0 every few seconds: step, time, percentage, remaining time.
#pragma once
#include <chrono>
#include <mpi.h>

namespace cellphase
{
class Progress
{
public:
  /// start_time: time of the first step of this run (0, or that of the restart checkpoint).
  Progress(MPI_Comm comm, double start_time, double end_time, bool enabled);
  void update(int step, double time);
  void finish(int step, double time);

private:
  bool enabled_;
  double start_time_, end_time_;
  std::chrono::steady_clock::time_point start_, last_;
};
} // namespace cellphase
