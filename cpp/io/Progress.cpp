#include "io/Progress.h"
#include "util/Clock.h"
#include <cstdio>

namespace cellphase
{
namespace
{
void format_duration(double s, char* buf, std::size_t n)
{
  if (s < 120)
    std::snprintf(buf, n, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buf, n, "%.1f min", s / 60);
  else
    std::snprintf(buf, n, "%.1f h", s / 3600);
}
} // namespace

Progress::Progress(MPI_Comm comm, double start_time, double end_time, bool enabled)
    : start_time_(start_time), end_time_(end_time), start_(Clock::now()), last_(start_)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  enabled_ = enabled && rank == 0;
}

void Progress::update(int step, double time)
{
  if (!enabled_ || seconds_since(last_) < 5.0)
    return;
  last_ = Clock::now();
  const double elapsed = seconds_since(start_);
  // The rate is that of this run, which may have started from a checkpoint.
  const double done = (time - start_time_) / (end_time_ - start_time_);
  char el[32], rem[32];
  format_duration(elapsed, el, sizeof el);
  format_duration(done > 0 ? elapsed * (1 - done) / done : 0, rem, sizeof rem);
  std::printf("  step %6d  t = %-10.5g %5.1f%%  elapsed %s, about %s left\n", step, time,
              100 * time / end_time_, el, rem);
  std::fflush(stdout);
}

void Progress::finish(int step, double time)
{
  if (!enabled_)
    return;
  char el[32];
  format_duration(seconds_since(start_), el, sizeof el);
  std::printf("  finished: %d steps to t = %g in %s\n", step, time, el);
  std::fflush(stdout);
}
} // namespace cellphase
