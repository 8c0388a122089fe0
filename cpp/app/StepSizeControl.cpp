#include "app/StepSizeControl.h"
#include <algorithm>
#include <cmath>

namespace cellphase
{
StepSizeControl::StepSizeControl(const scene::AdaptiveDt& settings, double first)
    : settings_(settings), proposed_(first)
{
}

double StepSizeControl::next(double max_speed, double finest_cell, double time_left) const
{
  double dt = proposed_;
  // The interface may not cross a mesh cell in one step (section 6.3).
  if (max_speed > 0)
    dt = std::min(dt, settings_.cfl * finest_cell / max_speed);
  dt = std::clamp(dt, settings_.dt_min, settings_.dt_max);
  // A last step shorter than dt_min / 2 would be round-off: stretch the one before it.
  return time_left < dt + 0.5 * settings_.dt_min ? time_left : dt;
}

StepSizeControl::Verdict StepSizeControl::judge(double dt, double estimate)
{
  if (estimate < 0)
  {
    proposed_ = std::min(dt, settings_.dt_max);
    return {true, proposed_};
  }
  // The estimate is of a local error ~ dt^2 (backward Euler's): the step that meets
  // safety^2 * tolerance, growing at most by `growth`, shrinking at most to a fifth.
  const double ratio = estimate > 0 ? settings_.tolerance / estimate : INFINITY;
  const double factor = std::clamp(settings_.safety * std::sqrt(ratio), 0.2, settings_.growth);
  const double resized = std::clamp(dt * factor, settings_.dt_min, settings_.dt_max);
  if (estimate <= settings_.tolerance || dt <= settings_.dt_min * (1 + 1e-12))
  {
    forced_ += estimate > settings_.tolerance;
    proposed_ = resized;
    return {true, resized};
  }
  ++rejected_;
  proposed_ = resized;
  return {false, resized};
}

double StepSizeControl::reject(double dt, double factor)
{
  ++rejected_;
  proposed_ = std::max(dt * factor, settings_.dt_min);
  return proposed_;
}

void StepSizeControl::save(CheckpointData& data) const
{
  data.set("adaptive_dt.proposed", proposed_);
  data.set("adaptive_dt.rejected", rejected_);
  data.set("adaptive_dt.forced", forced_);
}

void StepSizeControl::restore(const CheckpointData& data)
{
  if (!data.arrays.count("adaptive_dt.proposed"))
    return; // written at a fixed step: start from numerics.dt
  proposed_ = data.scalar("adaptive_dt.proposed");
  rejected_ = int(data.scalar("adaptive_dt.rejected"));
  forced_ = int(data.scalar("adaptive_dt.forced"));
}
} // namespace cellphase
