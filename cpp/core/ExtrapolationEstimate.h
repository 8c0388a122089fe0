// The local time error of a sub-problem's fields for numerics.adaptive_dt, by the same
// extrapolation as the phase field's (docs/scenes.md, numerics.adaptive_dt): the new value
// against (1 + w) u^n - w u^{n-1}, w = dt_n / dt_{n-1}. For the sub-problems whose fields the
// phase field's estimate does not see (the species, the orientation field): a pattern can
// form on a frozen shape, and a fast reaction can need smaller steps than the membrane.
// u^{n-1} is a registry field ("<field>_prev"), so that a rejected step, a remesh and a
// checkpoint carry it as they carry u itself.
#pragma once
#include "core/FieldRegistry.h"
#include "io/CheckpointFile.h"
#include <mpi.h>
#include <string>
#include <vector>

namespace cellphase
{
class ExtrapolationEstimate
{
public:
  /// fields: the qualified names of the estimated fields (declared by their owner).
  explicit ExtrapolationEstimate(std::vector<std::string> fields) : fields_(std::move(fields)) {}

  /// Declare "<field>_prev" for each field, moved at a remesh as the field is.
  void declare(FieldRegistry& registry) const;
  /// After the owner's attach: take the _prev functions from the registry (moved or restored)
  /// or make them (a new run: no history yet), in the space of their field.
  void attach(FieldRegistry& registry);
  /// Before the owner's step: keep u^n.
  void begin_step();
  /// After it: the estimate of the step (-1 without a history), then u^{n-1} <- u^n.
  /// Each field's error is relative to max(1, its largest |value|).
  double end_step(double dt, MPI_Comm comm);

  /// The step before and whether _prev holds a state (checkpointed scalars under prefix).
  void save(CheckpointData& data, const std::string& prefix) const;
  void restore(const CheckpointData& data, const std::string& prefix);

private:
  std::vector<std::string> fields_;
  std::vector<std::shared_ptr<Function>> now_, prev_;
  std::vector<std::vector<double>> before_; ///< u^n of the step under way
  bool have_ = false;   ///< _prev holds u^{n-1}
  double dt_prev_ = 0;  ///< t^n - t^{n-1}
};
} // namespace cellphase
