// The time loop of one scene: initial mesh and fields (or those of a checkpoint), then
// step the sub-problems in the order of the split, check, remesh, observe, write,
// checkpoint. It knows the physics only through the sub-problems (core/SubProblem.h) and
// the fields they declare (core/FieldRegistry.h).
#pragma once
#include "app/CheckpointStore.h"
#include "app/SettledWatch.h"
#include "app/StepSizeControl.h"
#include "core/FieldRegistry.h"
#include "core/SubProblem.h"
#include "io/FieldOutput.h"
#include "io/ObservablesCsv.h"
#include "mesh/AdaptiveMesh.h"
#include "mesh/OwnMesh.h"
#include "scene/Scene.h"
#include <map>
#include <optional>
#include <memory>
#include <stdexcept>
#include <vector>

namespace cellphase
{
/// A run that failed numerically; the message names module, field, step and time and
/// where the last good state was written.
struct NumericalFailure : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// A run stopped by SIGINT/SIGTERM after writing a checkpoint; the message says how to
/// continue.
struct Interrupted : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// A restart that cannot start (no valid checkpoint, or one that does not fit the scene).
struct RestartError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

class Simulation
{
public:
  /// With restart == true the run continues from the newest valid checkpoint in the
  /// scene's output directory. `extra` sub-problems step after those of the scene's plan
  /// (tests add physics this way without touching the loop).
  Simulation(const scene::Scene& scene, MPI_Comm comm, bool restart = false,
             std::vector<std::unique_ptr<SubProblem>> extra = {});
  /// Run to the scene's end time; throws NumericalFailure, Interrupted or RestartError.
  void run();
  const FieldRegistry& fields() const { return fields_; }

private:
  /// Where the loop stands: the state after `step` steps.
  struct LoopState
  {
    int step = 0;
    double time = 0;
    /// The mesh and fields are already those of the remesh that begins step + 1 (the
    /// state a failed step falls back to): a restart from it does not remesh again.
    bool remeshed = false;
  };
  /// Copies of the field values at the start of the current step.
  struct GoodState
  {
    LoopState at;
    std::map<std::string, std::vector<double>> values;
    CheckpointData scalars; ///< the sub-problems' (numerics.adaptive_dt only)
  };

  void check_plan() const;
  /// Sub-problems in an order in which each attaches after those whose fields it reads.
  void order_attach();
  LoopState initialise();
  LoopState restore();
  /// Every sub-problem on the mesh of the fields now in the registry.
  void attach_all();
  void open_output(const LoopState& start);
  /// One field output per mesh: "" the shared mesh (fields.xdmf), a cell's own mesh
  /// cell.<group> (cell.<group>.xdmf).
  void make_writers(const LoopState& start);
  void write_fields(double time, int step);
  /// The fields the scene's output lists, by label.
  /// The fields of output.fields that live on mesh `key`, by their output names.
  FieldMap output_fields(const std::string& key) const;
  double remesh(double& volume_change);
  /// The new meshes at a remesh: each refined around the zero level sets of its fields.
  std::map<std::string, std::shared_ptr<Mesh>> rebuild_meshes();
  /// One step of the split from `time`; sub-problems not yet active are skipped.
  StepTimings step(double dt, double time);
  /// `last`: the row of end_time (the fields are written whatever output.every says).
  void record(const LoopState& at, const StepTimings& timings, double remesh_time,
              double volume_change, bool last = false);
  /// Throws NumericalFailure (after saving the last good state) if a field is not finite
  /// or a sub-problem's state is beyond the scene's limits.
  void check_health(const LoopState& at, const Observation& row);
  [[noreturn]] void fail(const LoopState& at, const std::string& module, const std::string& what);
  /// The description of the sub-problem that owns the field.
  std::string owner_of(const std::string& field) const;
  std::string save_checkpoint(const LoopState& at);
  void keep_good_state(const LoopState& at);
  /// The fields (and with numerics.adaptive_dt the sub-problems' scalars) of the good state.
  void restore_good_state();
  /// One step from `at` of size dt, or with numerics.adaptive_dt the first of the tried
  /// steps (from dt down) whose error estimate is accepted; returns its size.
  double take_step(const LoopState& at, double dt, StepTimings& timings);
  /// numerics.adaptive_dt: the largest speed of the flow (0 without one), for the CFL limit.
  double max_flow_speed() const;
  void log(const char* fmt, ...) const;

  const scene::Scene& scene_;
  MPI_Comm comm_;
  bool restart_;
  AdaptiveMesh adaptive_; ///< the shared mesh (key "")
  FieldRegistry fields_;
  std::map<std::string, OwnMesh> own_meshes_; ///< cells' own meshes, by key
  std::vector<std::unique_ptr<SubProblem>> split_; ///< in the order they step
  std::vector<std::string> initial_; ///< fields with initial data (the phase fields)
  std::vector<SubProblem*> attach_order_;
  CheckpointStore checkpoints_;
  std::unique_ptr<ObservablesCsv> csv_;
  std::unique_ptr<SettledWatch> settled_watch_; ///< numerics.stop_when_settled
  /// Why the watched observable has settled at the last row (rank 0 decides for all).
  std::optional<std::string> settled_now() const;
  /// The last lines of a run: factorisations and where the output is.
  void log_summary() const;
  std::map<std::string, std::unique_ptr<FieldOutput>> writers_; ///< by mesh key
  int last_step_ = 0;
  std::optional<StepSizeControl> step_control_; ///< numerics.adaptive_dt
  double last_dt_ = 0;                          ///< the step of the last row
  double last_estimate_ = -1;                   ///< its error estimate (< 0: none)
  const SubProblem* solving_ = nullptr; ///< the sub-problem being stepped
  GoodState good_;
};
} // namespace cellphase
