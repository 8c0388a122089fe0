// The phase field of the scene's cells as a sub-problem of the split: PhaseFieldModule
// (the solver) plus what the time loop needs around it: its fields in the registry,
// its observables (section 5.3), the constraint targets fixed at t = 0 and the centre of
// mass continued across periodic faces, both checkpointed.
#pragma once
#include "compat/Resample.h"
#include "core/SolverColumns.h"
#include "core/SubProblem.h"
#include "physics/Observables.h"
#include "physics/PhaseFieldModule.h"
#include <array>
#include <memory>

namespace cellphase
{
class PhaseFieldSubProblem : public SubProblem
{
public:
  /// One phase field per group of cells (scene/Plan.h): its fields are
  /// <group.prefix>.phi, ..., its parameters those of its cells.
  PhaseFieldSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm,
                       scene::CellGroup group, int groups);

  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  void connect(FieldRegistry& fields) override;
  void start() override;
  StepTimings step(double dt) override;
  StepTimings finish_step() override;
  void observe(Observation& row) override;
  std::string health(const Observation& row) const override;
  void save(CheckpointData& data) const override;
  void restore(const CheckpointData& data) override;
  std::int64_t num_dofs() const override { return module_.num_dofs(); }
  int factorisations() const override { return module_.factorisations(); }
  int krylov_iterations() const override { return module_.krylov_iterations(); }
  double time_error() const override { return module_.time_error(); }
  int threads() const { return module_.threads(); }

private:
  /// The field others read (on the shared mesh) and the one holding its state (the same
  /// field, or with own meshes the one on this cell's mesh).
  std::string field(const std::string& f) const { return group_.prefix + "." + f; }
  std::string state(const std::string& f) const { return scene::state_field(scene_, group_, f); }
  /// Own meshes: the copies on the shared mesh from the state (after every step).
  void update_copies();
  /// Own meshes: "" or how close the cell came to the edge of its mesh.
  std::string patch_problem() const;
  std::string key(const std::string& k) const { return name() + "." + k; }
  void publish_targets();
  void unwrap_centre(std::array<double, 3>& centre);

  scene::CellGroup group_;
  SolverColumns solver_columns_; ///< numerics.solver: reuse
  int groups_;              ///< phase fields of the scene
  const scene::Scene scene_; ///< as this group sees it (its cells, its parameters)
  PhaseFieldModule module_;
  std::unique_ptr<Observables> observables_;
  FieldRegistry* fields_ = nullptr;
  double initial_volume_ = 0;
  ObservableValues last_; ///< of the last observe()
  /// Along periodic axes: the whole periods added so far, and the centre of the last row.
  std::array<double, 3> centre_shift_{0, 0, 0}, last_centre_{0, 0, 0};
  bool have_last_centre_ = false;

  // numerics.mesh.cell_meshes: own (section 7.2)
  bool own_;
  std::vector<std::unique_ptr<compat::Resampler>> to_shared_; ///< state -> copies
  std::unique_ptr<compat::Resampler> velocity_in_;            ///< flow.v -> own mesh
  std::shared_ptr<Function> velocity_;                         ///< flow.v on the own mesh
  /// What the flow carries across the edge of the own mesh per unit time (forms/observables.py)
  /// and its sum over the steps, int (1 + phi) (put back into the interface: see step()).
  std::shared_ptr<Form> edge_outflow_form_;
  double edge_outflow_ = 0;
  /// int phi~ and int phi~ v_d of this cell (its velocity column), with a flow
  std::shared_ptr<Form> weight_form_;
  std::vector<std::shared_ptr<Form>> velocity_forms_;
  double patch_volume_ = 0, shared_volume_ = 0;               ///< |own mesh|, |shared mesh|
  compat::Box cut_box_{}; ///< the box its own mesh was cut around
  bool whole_domain_ = false; ///< that box covers the domain (a cell next to a periodic side)
  /// int (1 + phi), the volume target that does not depend on the patch; < 0 until start().
  double cell_volume_target_ = -1;
};
} // namespace cellphase
