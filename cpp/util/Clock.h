// Wall-clock helpers for the timings in observables.csv and the progress line.
#pragma once
#include <chrono>

namespace cellphase
{
using Clock = std::chrono::steady_clock;

/// Seconds elapsed since t0.
inline double seconds_since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
} // namespace cellphase
