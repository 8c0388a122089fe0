// numerics.adaptive_dt: the size of the next time step from the estimate of the local time
// error of the last one (the phase fields' time_error()), and whether that step is kept.
// A step whose estimate exceeds the tolerance is rejected and repeated from the saved
// state with a smaller step (section "Adaptive time step" of docs/scenes.md).
#pragma once
#include "io/CheckpointFile.h"
#include "scene/Scene.h"

namespace cellphase
{
class StepSizeControl
{
public:
  /// `first`: the first step (numerics.dt).
  StepSizeControl(const scene::AdaptiveDt& settings, double first);

  /// The step to try next, also limited by the interface CFL condition max |v| dt <=
  /// cfl * h_min (max_speed 0: no flow) and by the time left.
  double next(double max_speed, double finest_cell, double time_left) const;
  struct Verdict
  {
    bool accept;
    double next; ///< the step after it (accepted) or the step to try again (rejected)
  };
  /// The step of size dt had this estimate (< 0: none, e.g. the first step: accepted,
  /// the next step as large). A step at dt_min is accepted whatever its estimate.
  Verdict judge(double dt, double estimate);
  /// A step of size dt that failed otherwise (its solver): rejected, the next try is
  /// dt * factor (at least dt_min).
  double reject(double dt, double factor);
  int rejected() const { return rejected_; }
  int rejected_at_dt_min() const { return forced_; }

  /// The proposed step and the counts: a restart continues the sequence exactly.
  void save(CheckpointData& data) const;
  void restore(const CheckpointData& data);

private:
  scene::AdaptiveDt settings_;
  double proposed_;
  int rejected_ = 0; ///< steps rejected and repeated so far
  int forced_ = 0;   ///< steps accepted at dt_min although their estimate was too large
};
} // namespace cellphase
