// The orientation field of an active polar gel (thesis chapter 6) as a sub-problem: P and
// its chemical potential P# (vector P2, forms/polar_gel.py) in one implicit step after the
// flow (section 6.3, step 2), with phi^n and v^{n+1}; P# is eliminated from the step's
// system exactly and projected from P^{n+1} after it. With a flow it writes the force of
// P on the fluid, the P terms of (6.13) with the active stress (1/Fa) div(phi~ P (x) P)
// (6.11), that the flow adds at the next step (polar.force); the phase field adds the
// orientation terms of phi# (6.15) from polar.P.
#pragma once
#include "compat/Resample.h"
#include "core/ExtrapolationEstimate.h"
#include "core/SubProblem.h"
#include "physics/FormTable.h"
#include "scene/Scene.h"
#include "solve/L2Projection.h"
#include "solve/PeriodicSystem.h"
#include <memory>
#include <optional>
#include <vector>

namespace cellphase
{
class PolarGelSubProblem : public SubProblem
{
public:
  PolarGelSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm);

  std::vector<std::string> attach_reads() const override { return {phi_name_}; }
  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  void connect(FieldRegistry& fields) override;
  StepTimings step(double dt) override;
  /// P# and the force again from P^{n+1} and phi^{n+1} (see the .cpp).
  StepTimings finish_step() override;
  void observe(Observation& row) override;
  void save(CheckpointData& data) const override;
  void restore(const CheckpointData& data) override;
  double time_error() const override { return time_error_; }
  std::int64_t num_dofs() const override;
  int factorisations() const override { return factorisations_; }

private:
  /// P^0 = direction + delta, delta uniform in [-noise, noise] per component (6.2.5).
  void set_initial(Function& P) const;
  /// P# of the current P and phi: the L2 projection of (6.17) (the flow's first step needs
  /// P#^0; after each step it makes P# consistent with phi^{n+1}).
  void project_sharp();
  /// polar.force <- L2 projection of the P terms of (6.13) onto the flow's velocity space
  /// (on a cell's own mesh: onto vector P2 there, then resampled onto the shared mesh).
  void update_force();

  const scene::Scene& scene_;
  const scene::PolarGel& gel_;
  MPI_Comm comm_;
  std::string phi_name_;
  /// The mesh of phi and P: "" the shared mesh, else the cell's own mesh
  /// (numerics.mesh.cell_meshes: own), where P lives and is 0 beyond.
  std::string mesh_key_;
  PolarGelForms forms_;
  InterfaceForceForms mass_forms_; ///< the vector P2 mass matrix
  ConstantMap constants_;
  std::shared_ptr<Constant> dt_;

  std::shared_ptr<const Function> phi_;   ///< phi^n (the phase field's, in place)
  std::shared_ptr<Function> P_, P_sharp_; ///< standalone, in the registry
  std::shared_ptr<const Function> v_;     ///< the flow's v^{n+1}, or zero
  std::shared_ptr<Form> energy_, dissipation_;
  std::array<std::shared_ptr<Form>, 2> P_cell_;
  std::shared_ptr<Form> cell_weight_;     ///< int phi~
  std::unique_ptr<PeriodicSystem> system_; ///< built by connect on each mesh
  int factorisations_ = 0;
  double last_wall_ = 0; ///< wall time of the last step (observables column wall_polar)
  int last_iterations_ = 0;

  // numerics.adaptive_dt: the estimate of the local time error of P
  std::optional<ExtrapolationEstimate> estimate_;
  double time_error_ = -1;

  // The force on the flow (with a flow)
  std::shared_ptr<Function> force_;
  std::shared_ptr<Form> force_L_;
  std::shared_ptr<Form> sharp_L_;                 ///< (6.17) of the standalone P, phi
  std::unique_ptr<L2Projection> sharp_projection_;
  std::unique_ptr<L2Projection> force_projection_;

  // On a cell's own mesh: v^{n+1} resampled onto it before each step, the force projected
  // there and resampled onto the flow's mesh (0 beyond the patch, where P is 0)
  std::shared_ptr<Function> velocity_;
  std::unique_ptr<compat::Resampler> velocity_in_;
  std::shared_ptr<Function> force_on_patch_;
  std::unique_ptr<compat::Resampler> force_out_;
  std::vector<std::unique_ptr<compat::Resampler>> to_shared_; ///< P, P# -> their shared copies
};
} // namespace cellphase
