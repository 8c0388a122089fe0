// Bulk-surface reaction-diffusion on the diffuse cell (thesis 2.6, chapter 5) as a
// sub-problem: the species of forms/<model>.py (gtpase: c1, c2 on the membrane and C in the
// cytoplasm, (5.16)-(5.18)), one coupled implicit step after the phase field (section 5.3,
// step 4), with phi^{n+1} and v^{n+1}. With a flow and numbers.Fa it also writes the
// protrusion force -(1/Fa) c grad phi (5.7) of the model's protrusion species that the
// flow adds at the next step (rd.force).
#pragma once
#include "core/ExtrapolationEstimate.h"
#include "core/SubProblem.h"
#include "physics/FormTable.h"
#include "scene/Scene.h"
#include "solve/L2Projection.h"
#include "solve/PeriodicSystem.h"
#include <array>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace cellphase
{
class ReactionDiffusionSubProblem : public SubProblem
{
public:
  ReactionDiffusionSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm);

  std::vector<std::string> attach_reads() const override { return {phi_name_}; }
  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  void connect(FieldRegistry& fields) override;
  StepTimings step(double dt) override;
  void observe(Observation& row) override;
  void save(CheckpointData& data) const override;
  void restore(const CheckpointData& data) override;
  void rewind() override;
  double time_error() const override { return time_error_; }
  std::int64_t num_dofs() const override;
  int factorisations() const override { return factorisations_; }

  /// Per species, the amount in the transport weights: what the scheme conserves.
  std::vector<double> amounts() const;

private:
  /// The species' initial values (scene, section 5.4.1): constants, a region, or random.
  void set_initial(std::size_t i, Function& c) const;
  /// grad c~ of (5.21) at time t for the uniform modes 1-3 (0 for the point source).
  std::array<double, 3> signal_gradient(double t) const;
  /// Sets the chemotaxis constants of the form to grad c~ at time t.
  void update_signal(double t);
  /// The direction of grad c~ at `centre` (degrees): where the signal draws the cell.
  double signal_angle(const std::array<double, 3>& centre) const;
  /// The largest (sign 1) or smallest (sign -1) protrusion species on the membrane and its angle (degrees)
  /// about `centre`.
  std::pair<double, double> membrane_extremum(double sign, const std::array<double, 3>& centre) const;
  /// rd.force <- L2 projection of -(1/Fa) c1 grad phi (5.7) onto the flow's velocity space.
  void update_force();

  const scene::Scene& scene_;
  const scene::ReactionDiffusion& rd_;
  MPI_Comm comm_;
  std::string phi_name_;
  ReactionForms forms_;
  std::size_t protrusion_ = 0; ///< index of the species of the protrusion force
  InterfaceForceForms force_forms_;
  ConstantMap constants_;
  std::shared_ptr<Constant> dt_, chem_dir_, chem_point_, chem_xi_, chem_x0_;

  std::shared_ptr<const Function> phi_;    ///< phi^{n+1} (the phase field's, in place)
  std::shared_ptr<Function> phi_old_;      ///< phi^n: the weights of the old amounts
  std::shared_ptr<Space> W_;               ///< (c1, c2, C)
  std::vector<std::vector<std::int32_t>> to_mixed_; ///< per species: V dof -> W dof
  std::vector<std::shared_ptr<Function>> species_; ///< standalone, in the registry
  std::shared_ptr<Function> u_, u0_;       ///< the mixed solution and (c^n)
  std::shared_ptr<const Function> v_;      ///< the flow's v^{n+1}, or zero
  std::vector<std::shared_ptr<Form>> amount_, amount_cell_; ///< per species
  std::unique_ptr<PeriodicSystem> system_; ///< built by connect on each mesh
  int factorisations_ = 0;
  double last_wall_ = 0; ///< wall time of the last step (observables column wall_rd)
  int last_iterations_ = 0; ///< GMRES iterations of the last step (numerics.solver: reuse)

  std::vector<double> node_x_; ///< coordinates of the species' nodes on this mesh (3 per node)

  // Amounts after the last step: a remesh scales the moved species back to them.
  std::vector<double> kept_;
  double time_ = 0; ///< time of the species (checkpointed: the chemotactic signal's clock)

  // numerics.adaptive_dt: the species' own estimate of the local time error
  std::optional<ExtrapolationEstimate> estimate_;
  double time_error_ = -1;

  // Protrusion force (with a flow and numbers.Fa)
  std::shared_ptr<Function> force_;
  std::shared_ptr<Form> force_L_;
  std::unique_ptr<L2Projection> force_projection_;
};
} // namespace cellphase
