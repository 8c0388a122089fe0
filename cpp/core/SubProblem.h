// One sub-problem of the operator split (section 5.3): it owns fields (declared in the
// registry), builds its spaces, forms and solver on the mesh its fields live on, steps,
// reports observables and checkpoints its scalars. The time loop (app/Simulation) knows
// sub-problems only through this interface and the plan (scene/Plan.h) that orders them.
#pragma once
#include "core/FieldRegistry.h"
#include "core/StepTimings.h"
#include "io/CheckpointFile.h"
#include "physics/Observables.h"
#include "scene/Plan.h"
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace cellphase
{
/// One row of observables.csv as the sub-problems fill it: the standard columns, then any
/// columns of their own (appended in the order of the sub-problems).
struct Observation
{
  ObservableValues values;
  double lam_v = 0, lam_a = 0; ///< multipliers of the (first) phase field's constraints
  int phase_fields = 0;        ///< phase fields that observed so far
  std::vector<std::pair<std::string, double>> extra;
};

class SubProblem
{
public:
  explicit SubProblem(scene::PlanStep step) : step_(std::move(step)) {}
  virtual ~SubProblem() = default;

  const std::string& name() const { return step_.name; }
  const std::string& description() const { return step_.description; }
  /// Fields it reads while stepping and those it writes (the plan's lists).
  const std::vector<std::string>& reads() const { return step_.reads; }
  const std::vector<std::string>& writes() const { return step_.writes; }
  /// Steps that begin before this time are skipped (scene/Plan.h, PlanStep::active_from).
  double active_from() const { return step_.active_from; }
  /// Fields that must be attached before this one can attach (it builds forms on them).
  virtual std::vector<std::string> attach_reads() const { return {}; }

  /// Declare the fields it writes (once, before any mesh).
  virtual void declare(FieldRegistry& fields) = 0;
  /// Build on the mesh its fields live on. The registry holds the values they start from
  /// (initial data, a remesh transfer or a checkpoint; absent: the owner's default); the
  /// sub-problem puts the functions it steps back into the registry.
  virtual void attach(FieldRegistry& fields) = 0;
  /// After every sub-problem is attached: bind fields of those attached later.
  virtual void connect(FieldRegistry&) {}
  /// Once, after the first attach of a new run (not a restart): targets of constraints.
  virtual void start() {}
  virtual StepTimings step(double dt) = 0;
  /// After every sub-problem of the split has stepped: refresh what the next step reads and
  /// depends on the state of several (a force of the new fields), so that it is consistent.
  virtual StepTimings finish_step() { return {}; }
  /// Its part of one row of observables.csv (in attach order).
  virtual void observe(Observation&) {}
  /// "" or why the state it owns is beyond the scene's limits (numerics.limits).
  virtual std::string health(const Observation&) const { return ""; }
  /// Its checkpointed scalars (keys begin with its name).
  virtual void save(CheckpointData&) const {}
  virtual void restore(const CheckpointData&) {}
  /// After a rejected step (numerics.adaptive_dt): the registry's fields are back at t^n and
  /// restore() has run; make what it keeps beside the registry (copies of fields, amounts)
  /// match them again.
  virtual void rewind() {}
  /// Estimate of the local time error of its last step (numerics.adaptive_dt), < 0 if it
  /// makes none (or cannot yet: the first step).
  virtual double time_error() const { return -1; }
  virtual std::int64_t num_dofs() const { return 0; }
  virtual int factorisations() const { return 0; }
  /// Krylov iterations of its solves since the start (numerics.solver: reuse).
  virtual int krylov_iterations() const { return 0; }

private:
  scene::PlanStep step_;
};
} // namespace cellphase
