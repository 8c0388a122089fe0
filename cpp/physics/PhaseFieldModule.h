// One subproblem of the operator split: the phase-field / Helfrich gradient flow of the
// scene's model (section 2.5 and 3.4.1), solved as one monolithic P2 system per step.
#pragma once
#include "compat/Dolfinx.h"
#include "core/Bdf2.h"
#include "core/StepTimings.h"
#include "physics/FormTable.h"
#include "scene/Scene.h"
#include "compat/Periodic.h"
#include "solve/L2Projection.h"
#include "solve/LinearSolver.h"
#include <future>
#include <map>
#include <memory>
#include <string>
#include <span>
#include <vector>

namespace cellphase
{
/// Standalone P2 fields by name ("phi", "mu", "w"), all on one space.
using FieldMap = std::map<std::string, std::shared_ptr<Function>>;


/// Targets of the constraints, fixed at the start: V0 = int phi (3.10), A0 = E_CH (3.11).
struct ConstraintTargets
{
  double volume = 0, area = 0;
};

class PhaseFieldModule
{
public:
  PhaseFieldModule(const scene::Scene& scene, MPI_Comm comm);

  /// Build spaces, forms and solver on a (new) mesh. `fields` holds phi and, if known,
  /// the other fields of the model on the P2 space V; missing ones are computed from phi.
  void attach(std::shared_ptr<Space> V, FieldMap fields);
  /// Advect phi with this velocity (vector P2 on the current mesh, updated in place by the
  /// flow step before each phase-field step, section 5.3); call after every attach. Without
  /// it the advection velocity is zero. The matrix then changes every step.
  void set_velocity(std::shared_ptr<const Function> v);
  /// A cell's own mesh: whether it has cut edges (a patch: phi + 1 advected, with the
  /// outflow term at the edges, forms/cellphase_ufl.py) or is the whole domain (phi advected,
  /// as on the shared mesh). Call after every attach.
  void set_patch_edges(bool cut);
  /// dE/dphi of the model's energy, the potential of the interface force (dE/dphi) grad phi
  /// of the flow: mu (Cahn-Hilliard, to be scaled by 1/Ca), w (helfrich_hm1, (3.62)), or for
  /// the L2 Helfrich flows the L2 projection of (3.84), kept up to date after every step.
  std::shared_ptr<const Function> interface_potential();
  /// Multipliers of the last step (the projection of (3.84) uses them); for restarts.
  void set_multipliers(const std::array<double, 2>& m)
  {
    lam_v_->value[0] = m[0];
    lam_a_->value[0] = m[1];
  }
  /// The model's forms have the advection term (all but the Allen-Cahn models).
  bool advected() const { return forms_.advected; }
  /// Interaction with other cells (7.11), helfrich_hm1: the explicit source load_int of
  /// forms/helfrich_hm1.py from the other cells' sums w_sum, B_sum (P2 on this mesh,
  /// updated in place before each step) and the constants In_inv, r1, r2, a1, a2, a3.
  /// Call after every attach, once for each potential (the sources add up).
  /// in_flow_force false (interaction.flow_force): the source's L2 projection w_int enters
  /// the mobility term, gamma Lap(w + w_int), instead of w, so that w and the flow's force
  /// (7.12) hold the cell's own energy only (load_int_mobility).
  void set_interaction(std::shared_ptr<const Function> w_sum, std::shared_ptr<const Function> B_sum,
                       const ConstantMap& parameters, bool refresh = false,
                       bool in_flow_force = true);
  /// interaction.refresh: after the step (phi^{n+1} in place, the sums made again from the
  /// other cells' phi^{n+1}), w += P(source now) - P(source of the step), P the L2
  /// projection onto P2. The flow's next force then sees the interaction of the cells'
  /// present positions. No-op without it.
  void refresh_interaction();
  /// The orientation field's part of phi# (6.15), forms/helfrich_hm1.py's load_polar with
  /// P (vector P2 on this mesh, updated in place) and the constants Pa_inv, polar_c1,
  /// polar_beta. Call after every attach.
  void set_orientation(std::shared_ptr<const Function> P, const ConstantMap& parameters);
  /// Advance one time step of size dt.
  StepTimings step(double dt);

  const FieldMap& fields() const { return fields_; }
  std::shared_ptr<Space> space() const { return V_; }
  std::int64_t num_dofs() const;
  void set_targets(const ConstraintTargets& t) { targets_ = t; }
  const ConstraintTargets& targets() const { return targets_; }
  /// Explicit multipliers of the last step (lam_v, lam_a), for the log.
  std::array<double, 2> multipliers() const { return {lam_v_->value[0], lam_a_->value[0]}; }
  /// Energy whose gradient flow the model is: E_CH, E_H or E_H plus penalties (3.30)/(3.33).
  double total_energy(double phi_integral, double energy_ch, double helfrich) const;
  /// Threads of this rank: 2 when a CPU is spare for the assembly that runs beside the
  /// main thread's (the unit loads, the area linearisation during the solve), else 1.
  int threads() const { return spare_cpu_ && forms_.load_a ? 2 : 1; }
  /// Matrix factorisations since the start (all meshes).
  int factorisations() const { return factorisations_; }
  /// GMRES iterations since the start (numerics.solver: reuse; 0 with direct solves).
  int krylov_iterations() const { return krylov_iterations_; }
  /// numerics.time_scheme: bdf2. The previous state is in fields() as phi_prev (and
  /// mu_prev); with `have` false the next step is a backward Euler step (the first one).
  using History = StepHistory;
  History history() const { return history_; }
  /// The local time error of the last step as backward Euler's, estimated from the
  /// extrapolation phi* of phi^n and phi^{n-1}: max over the nodes of
  /// |phi^{n+1} - phi*| dt / (dt + dt_prev) (= |phi''| dt^2 / 2 to leading order);
  /// < 0 when there was no phi^{n-1} (the first step) or none is kept.
  double time_error() const { return time_error_; }
  void set_history(const History& h) { history_ = h; }

private:
  void bind_forms();
  void update_interface_potential(); ///< L2 Helfrich flows: dE_ <- projection of (3.84)
  void bind_system_forms(); ///< a_, L_ (they depend on the velocity)
  void compute_mu_from_phi();
  void update_multipliers(double dt);
  /// Assemble the step's right-hand side and the unit loads whose solutions are not
  /// current: they are solved together. Their vectors and solutions in the solver's order.
  void assemble_right_hand_sides(std::vector<const dolfinx::la::Vector<T>*>& rhs,
                                 std::vector<dolfinx::la::Vector<T>*>& solutions);
  /// Helfrich models: add the unit-load solutions with the multipliers that hold the
  /// constraints at t^{n+1} (helfrich_lagrange) or with the penalties evaluated at t^{n+1}
  /// (helfrich_penalty, helfrich_hm1), E_CH linearised about phi^n.
  void apply_constraint_loads();
  /// The area weights dA[.] and E_CH about phi^n do not depend on the step's solution: their
  /// local assembly (no MPI) starts before the solve, on a second thread when the process
  /// has a CPU to spare; apply_constraint_loads() waits for it.
  void start_area_linearisation();
  void gather_state();   ///< standalone fields -> mixed vector u0
  void gather_history(); ///< phi_prev, mu_prev -> mixed vector u1 (BDF2)
  void keep_history();   ///< u0 (the state before the step) -> phi_prev, mu_prev
  /// BDF2's coefficients for this step (variable step ratio w = dt / dt_prev).
  void set_bdf2_coefficients(double dt);
  void scatter_state();  ///< mixed solution -> standalone fields
  /// The standalone fields `names` (the i-th in the i-th slot of the mixed space) into a
  /// mixed vector, and back.
  void to_mixed(const std::vector<std::string>& names, std::span<T> mixed) const;
  void from_mixed(std::span<const T> mixed, const std::vector<std::string>& names);
  double integral(const std::shared_ptr<Form>& f) const;

  const scene::Scene& scene_;
  MPI_Comm comm_;
  ModelForms forms_;
  std::vector<std::string> names_;
  bool stabilised_;
  /// Stabilised L2 Helfrich flow: its phi rows are scaled (row_psi in helfrich_l2.py) so
  /// that the matrix is symmetric as long as no flow adds advection.
  bool symmetrisable_;

  std::shared_ptr<Space> V_, W_;
  FieldMap fields_;
  std::vector<std::vector<std::int32_t>> to_mixed_; ///< per field: V dof -> W dof
  std::shared_ptr<Function> u0_;                    ///< state at t^n on W
  // numerics.time_scheme: bdf2
  bool bdf2_;
  std::vector<std::string> history_names_;          ///< "phi_prev"(, "mu_prev"): names_[i] + "_prev"
  std::shared_ptr<Function> u1_;                    ///< state at t^{n-1} on W
  std::shared_ptr<Form> a_bdf2_, L_bdf2_;
  Bdf2Constants bdf_;
  History history_;
  bool second_order_step_ = false;                  ///< this step is a BDF2 step
  double time_error_ = -1;                          ///< of the last step, see time_error()
  void estimate_time_error(double dt);              ///< before keep_history()
  std::shared_ptr<const Function> velocity_;        ///< advection velocity ("v")
  bool flowing_ = false;                            ///< velocity_ is the flow's
  std::shared_ptr<Function> dE_;                    ///< dE/dphi (L2 Helfrich with flow)
  std::shared_ptr<Form> dE_rhs_;
  std::unique_ptr<L2Projection> dE_projection_;     ///< mass matrix, factorised per mesh
  std::shared_ptr<Function> boundary_value_;
  BCs bcs_;
  std::shared_ptr<Form> a_, L_;
  std::shared_ptr<Form> dW_integral_, phi_integral_, energy_ch_;
  /// The solution is linear in each multiplier/penalty: its load and the solution for a
  /// unit value of it.
  struct UnitLoad
  {
    enum Kind { volume, area } kind;
    std::shared_ptr<Form> form;
    std::shared_ptr<Form> form_bdf2; ///< for BDF2 steps (null: `form` serves both)
    std::unique_ptr<dolfinx::la::Vector<T>> x, b;
    std::shared_ptr<Constant> value;
    double penalty;       ///< p1 or p2 (penalty models)
    bool current = false; ///< x solves the current matrix (the volume load is constant)
  };
  std::vector<UnitLoad> loads_;
  /// Volume and linearised area of the phi part of a mixed vector are dot products with
  /// these weights on V (volume: once per mesh; area: once per step, about phi^n).
  std::shared_ptr<Form> volume_weights_form_, area_weights_form_;
  std::unique_ptr<dolfinx::la::Vector<T>> volume_weights_, area_weights_;
  std::future<double> local_energy_ch_; ///< of start_area_linearisation()
  bool spare_cpu_; ///< a second thread may run beside the main one (cpus_per_rank)
  double phi_dot(const dolfinx::la::Vector<T>& weights, const dolfinx::la::Vector<T>& x,
                 bool minus_phi_n) const;
  /// Periodic directions of the scene (plain assembly without); rebuilt on every mesh.
  std::unique_ptr<PeriodicConstraint> periodic_;
  std::unique_ptr<dolfinx::la::petsc::Matrix> A_;
  std::unique_ptr<dolfinx::la::Vector<T>> b_, x_;
  /// -A g of the Dirichlet values through the matrix last assembled (reused with it)
  std::unique_ptr<dolfinx::la::Vector<T>> lifting_;
  std::unique_ptr<LinearSolver> solver_; ///< created at the first factorisation on a mesh
  /// An explicit source of the step's right-hand side (form null: the model lacks `term`).
  void add_source(const ufcx_form* form, const std::string& term, CoefficientMap coefficients,
                  const ConstantMap& parameters);
  /// Explicit sources of the step's right-hand side: (7.11), (6.15); none by default.
  std::vector<std::shared_ptr<Form>> sources_;
  std::unique_ptr<dolfinx::la::Vector<T>> source_b_; ///< their vector
  // interaction.refresh or flow_force false: the source (7.11) as P2 fields, of the step
  // and after it
  std::vector<std::shared_ptr<Form>> interaction_rhs_; ///< one per potential
  std::vector<const Form*> interaction_sources() const;
  std::unique_ptr<L2Projection> interaction_projection_;
  std::shared_ptr<Function> interaction_of_step_, interaction_now_;
  bool matrix_current_ = false; ///< stabilised scheme: matrix assembled and factorised
  ConstantMap constants_;
  std::shared_ptr<Constant> dt_, lam_v_, lam_a_;
  std::shared_ptr<Constant> own_mesh_; ///< 1 on a patch with cut edges, else 0 (set_patch_edges)
  ConstraintTargets targets_;
  double domain_volume_;
  int factorisations_ = 0, krylov_iterations_ = 0;
  bool reuse_ = false; ///< numerics.solver: reuse: the solver counts its factorisations
};
} // namespace cellphase
