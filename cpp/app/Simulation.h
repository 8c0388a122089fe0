// The time loop of one scene: initial mesh and fields (or those of a checkpoint), then
// step, check, remesh, observe, write, checkpoint.
#pragma once
#include "app/CheckpointStore.h"
#include "io/FieldWriter.h"
#include "io/ObservablesCsv.h"
#include "mesh/AdaptiveMesh.h"
#include "physics/ConcentrationModule.h"
#include "physics/FlowModule.h"
#include "physics/Observables.h"
#include "physics/PhaseFieldModule.h"
#include "scene/Scene.h"
#include <map>
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
  /// scene's output directory.
  Simulation(const scene::Scene& scene, MPI_Comm comm, bool restart = false);
  /// Run to the scene's end time; throws NumericalFailure, Interrupted or RestartError.
  void run();

private:
  /// Where the loop stands: the state after `step` steps.
  struct LoopState
  {
    int step = 0;
    double time = 0;
  };
  /// Copies of the field values at the start of the current step.
  struct GoodState
  {
    LoopState at;
    std::map<std::string, std::vector<double>> values;
  };

  LoopState initialise();
  LoopState restore();
  void open_output(const LoopState& start);
  std::unique_ptr<FieldWriter> make_writer(const LoopState& start) const;
  double remesh(double& volume_change);
  /// Flow on the phase field's current mesh, reading its phi and dE/dphi, starting from
  /// `velocity` (null: at rest); the phase field is then advected by the flow's velocity.
  /// With the concentration variant of the inextensibility, c starts from `concentration`
  /// (null: c = 1).
  void attach_flow(std::shared_ptr<const Function> velocity,
                   std::shared_ptr<const Function> concentration = nullptr);
  /// The phase-field fields plus, with flow, the velocity v and pressure p.
  FieldMap all_fields() const;
  /// One step of the split (section 5.3): flow with phi^n, mu^n, then phi with v^{n+1}.
  StepTimings step(double dt);
  void record(const LoopState& at, const StepTimings& timings, double remesh_time,
              double volume_change);
  /// Throws NumericalFailure (after saving the last good state) if a field is not finite,
  /// phi leaves its bound or the volume drifts beyond the scene's limit.
  void check_health(const LoopState& at, const ObservableValues& v);
  [[noreturn]] void fail(const LoopState& at, const std::string& module, const std::string& what);
  /// "flow module" for v and p, "phase-field module (<model>)" for the others.
  std::string module_name(const std::string& field) const;
  std::string save_checkpoint(const LoopState& at);
  void keep_good_state(const LoopState& at);
  void log(const char* fmt, ...) const;

  const scene::Scene& scene_;
  MPI_Comm comm_;
  bool restart_;
  AdaptiveMesh adaptive_;
  PhaseFieldModule module_;
  std::unique_ptr<FlowModule> flow_; ///< only if the scene has a flow section
  /// Membrane concentration (3.70), only with flow.inextensibility.concentration
  std::unique_ptr<ConcentrationModule> concentration_;
  CheckpointStore checkpoints_;
  std::unique_ptr<Observables> observables_;
  std::unique_ptr<ObservablesCsv> csv_;
  std::unique_ptr<FieldWriter> writer_;
  double initial_volume_ = 0;
  int last_step_ = 0;
  std::string solving_ = "phi"; ///< a field of the subproblem being solved
  /// Along periodic axes the centre of mass is continued across the periodic faces: the
  /// whole periods added so far, and the centre of the last row.
  std::array<double, 3> centre_shift_{0, 0, 0}, last_centre_{0, 0, 0};
  bool have_last_centre_ = false;
  void unwrap_centre(std::array<double, 3>& centre);
  GoodState good_;
};
} // namespace cellphase
