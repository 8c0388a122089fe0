// The flow subproblem of the operator split (section 5.3, step 1): one semi-implicit step
// of the two-phase Navier-Stokes / Stokes equations (2.47)-(2.57), section 2.8, on a
// P2/P1 Taylor-Hood space, for a given phase field phi and chemical potential mu.
#pragma once
#include "compat/Dolfinx.h"
#include "core/Bdf2.h"
#include "physics/FormTable.h"
#include "compat/Periodic.h"
#include "solve/LinearSolver.h"
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cellphase
{
/// Sides of the (axis-aligned) box: left/right x = min/max, bottom/top y, front/back z.
enum class Side { left, right, bottom, top, front, back };

enum class WallKind
{
  no_slip,    ///< v = 0
  moving,     ///< v = tangential part of `velocity` (its normal component is dropped)
  free_slip,  ///< v.n = 0, no tangential stress
  prescribed, ///< v = profile(x) (in/outflow profiles)
};

/// Velocity condition on one side. Sides without a wall are traction-free (natural
/// condition (2 eta D(v) - p I) n = 0). Where sides meet, moving/prescribed walls win over
/// no-slip, which wins over free-slip.
struct Wall
{
  Side side = Side::bottom;
  WallKind kind = WallKind::no_slip;
  std::array<double, 3> velocity{0, 0, 0};
  VectorPointFunction profile;
  /// A wall given by facet tags (mesh-file domains) instead of a side: its boundary
  /// facets on a mesh, and the axis it is perpendicular to (-1: none; free slip needs one,
  /// a moving wall then keeps its velocity as given).
  std::function<std::vector<std::int32_t>(const Mesh&)> facets;
  int normal_axis = -1;
};

/// Local inextensibility of the membrane, section 3.4.3 (Aland et al.): a multiplier
/// lambda solved with v and p, (3.67)-(3.68); optionally the global area (3.69) and the
/// concentration penalty (3.71).
struct Inextensibility
{
  bool enabled = false;
  double xi = 1;             ///< xi of (3.68)
  double epsilon = 0;        ///< interface width eps of (3.68)
  bool global_area = false;  ///< (3.69): every flow step restores the area A0
  double xi2 = 0;            ///< xi_2 of (3.71) (0: no concentration penalty)
};

/// Dimensionless parameters of the flow. Index 0 of the two-phase pairs is the surrounding
/// fluid (phi = -1), index 1 the cell (phi = +1).
struct FlowParameters
{
  double Re = 0;           ///< 0: Stokes (no time derivative, no convection)
  bool convection = true;  ///< false: time-dependent Stokes (no transport terms)
  std::array<double, 2> density{1, 1};
  std::array<double, 2> viscosity{1, 1}; ///< interpolated as (2.56)
  double mobility = 0;     ///< gamma of the variable-density flux J (2.8)
  bool degenerate_mobility = false; ///< gamma(phi) = mobility W(phi) (2.8)
  double capillary = 0;    ///< prefactor of the capillary force mu grad phi (2.8)
  std::array<double, 3> gravity{0, 0, 0}; ///< times rho(phi)
  std::array<double, 3> force{0, 0, 0};   ///< constant body force density
  std::vector<Wall> walls;
  /// Periodic axes (0, 1, 2 = x, y, z) of the mesh's bounding box; no walls on their sides.
  std::vector<int> periodic;
  /// Walls by facet tags (Wall::facets) rather than box sides: the pressure is pinned at
  /// this mesh vertex when the walls close the whole boundary (none: a part is open).
  bool tagged_walls = false;
  std::optional<std::array<double, 3>> pressure_pin;
  std::map<std::string, std::string> petsc; ///< options under the prefix flow_
  bool reuse_factorisations = false;        ///< numerics.solver: reuse
  /// numerics.time_scheme: bdf2. Each step is driven by the extrapolations phi*, mu* of the
  /// phase field and its potential to t^{n+1} (Stokes and Navier-Stokes), and d_t v is
  /// BDF2's with the transport velocity v* (Re > 0); the first step is backward Euler.
  bool second_order = false;
  /// Second order: the step is driven by phi* (numerics.coupling: extrapolated), else by
  /// phi^n (lagged: the split's first-order error stays); mu* too with
  /// extrapolate_potential (scene::flow_extrapolates_potential), else mu^n.
  bool extrapolate_phase = true;
  bool extrapolate_potential = true;
  Inextensibility inextensibility;
};

/// The flow's state one step back (FlowParameters::second_order), moved from the last
/// mesh or read from a checkpoint: v^{n-1}, and the phi and mu that drove the last step.
struct PreviousFlowState
{
  std::shared_ptr<const Function> velocity, phi, mu;
};

struct FlowTimings
{
  double assemble = 0, factorise = 0, solve = 0;
  bool factorised = false; ///< a new factorisation was needed this step
};

struct FlowObservables
{
  double kinetic_energy = 0;                ///< 1/2 int rho(phi) |v|^2, (2.54)
  std::array<double, 3> cell_velocity{0, 0, 0}; ///< int phi~ v / int phi~, phi~ = (1+phi)/2
  double divergence_l2 = 0;                 ///< || div v ||_L2
  // With inextensibility (zero without):
  double tension_mean = 0;       ///< int lambda delta_phi / int delta_phi
  double lambda_dissipation = 0; ///< xi eps^2 int phi^2 |grad lambda|^2, (3.76)
};

/// Fields of the membrane read by the inextensibility constraint (null: defaults).
struct MembraneFields
{
  /// phi_cells = max_i phi_i, (7.14) (null: the flow's phi)
  std::shared_ptr<const Function> phi_cells;
  /// concentration c of (3.70) (null: c = 1, no penalty)
  std::shared_ptr<const Function> concentration;
  /// eta(phi_1, ..., phi_N) of (7.12) at the P2 nodes, updated in place before each step
  /// (null: eta(phi) of (2.56))
  std::shared_ptr<const Function> viscosity;
};

class FlowModule
{
public:
  /// `forms` defaults to forms/flow.py of the mesh's dimension (tests pass extended forms).
  FlowModule(const FlowParameters& parameters, MPI_Comm comm, FlowForms forms = {});

  /// Build the Taylor-Hood space, BCs, forms and solver on a (new) mesh. phi and mu are
  /// P2 functions on this mesh read at every step (null: phi = -1, mu = 0); `velocity`
  /// (vector P2 on this mesh, any dof numbering) is the initial v^n (null: v = 0).
  void attach(std::shared_ptr<const Mesh> mesh, std::shared_ptr<const Function> phi = nullptr,
              std::shared_ptr<const Function> mu = nullptr,
              std::shared_ptr<const Function> velocity = nullptr,
              MembraneFields membrane = {}, PreviousFlowState previous = {});
  /// Area target A0 of the global constraint (3.69), as the E_CH of (3.11) at the start.
  void set_area_target(double energy_ch) { area_target_ = energy_ch; }
  /// v^n -> v^{n+1}, p^{n+1}. The matrix is rebuilt and refactorised only if something it
  /// depends on changed since the last factorisation (dt, phi, mu, v^n, the mesh).
  FlowTimings step(double dt);

  /// v (vector P2, holds v^n before and v^{n+1} after a step), p (P1).
  std::shared_ptr<Function> velocity() const { return velocity_; }
  std::shared_ptr<Function> pressure() const { return pressure_; }
  /// Multiplier lambda of (3.67) (P1), null without inextensibility.
  std::shared_ptr<Function> multiplier() const { return multiplier_; }
  /// Extra force density f_membrane (vector P2), zero unless a coupling writes into it.
  std::shared_ptr<Function> membrane_force() const { return membrane_force_; }
  FlowObservables observables() const;
  /// Second order: whether the previous step's state is held (else the next step is
  /// backward Euler driven by phi^n, as the first one), and that step's size.
  using History = StepHistory;
  History history() const { return history_; }
  void set_history(const History& h) { history_ = h; }
  /// Second order: v^{n-1}, phi and mu of the last step (null without; phi and mu also
  /// when not extrapolated, FlowParameters::extrapolate_phase, extrapolate_potential).
  PreviousFlowState previous() const { return {velocity_prev_, phi_prev_, mu_prev_}; }
  std::shared_ptr<Function> velocity_prev() const { return velocity_prev_; }
  std::shared_ptr<Function> phi_prev() const { return phi_prev_; }
  std::shared_ptr<Function> mu_prev() const { return mu_prev_; }
  /// Matrix factorisations since construction (all meshes).
  int factorisations() const { return factorisations_; }
  /// GMRES iterations since construction (numerics.solver: reuse; 0 with direct solves).
  int krylov_iterations() const { return krylov_iterations_; }
  /// The pressure is fixed at one dof and shifted to zero mean (closed box).
  bool pressure_pinned() const { return pinned_; }
  std::int64_t num_dofs() const;

private:
  void build_bcs();
  void bind_forms();
  bool matrix_outdated(double dt) const;
  bool local_matrix_outdated(double dt) const;
  void remember_matrix_inputs(double dt);
  void store_solution();
  /// Second order: phi*, mu* into the functions the forms read and the BDF2 constants;
  /// returns whether this step is a BDF2 step.
  bool prepare_second_order(double dt);
  /// Second order: the state before this step becomes the next step's previous state.
  void keep_previous(double dt);
  /// area_source of forms/flow_inextensible.py: the membrane-area rate that brings the
  /// area back to A0 in one step, per unit of int delta_phi (0 without global_area).
  double area_source(double dt) const;

  FlowParameters params_;
  MPI_Comm comm_;
  FlowForms forms_;
  ConstantMap constants_;
  std::shared_ptr<Constant> dt_, area_source_;

  std::shared_ptr<const Mesh> mesh_;
  std::shared_ptr<Space> W_;
  compat::CollapsedSpace Vv_, Q_, Lambda_;
  std::shared_ptr<const Function> phi_, mu_, phi_cells_, concentration_;
  /// What the system's forms read for phi, mu and phi_cells: the fields themselves, or
  /// (second order) their extrapolations phi*, mu* to t^{n+1}.
  std::shared_ptr<Function> phi_star_, mu_star_;
  std::shared_ptr<const Function> phi_in_, mu_in_, phi_cells_in_;
  std::shared_ptr<Function> velocity_prev_, phi_prev_, mu_prev_;
  Bdf2Constants bdf_;
  History history_;
  bool second_order_step_ = false; ///< the current step is a BDF2 step
  std::shared_ptr<const Function> viscosity_; ///< eta_cells of (7.12), or null
  std::shared_ptr<Function> velocity_, pressure_, membrane_force_, multiplier_;
  std::vector<std::shared_ptr<Function>> bc_values_;
  BCs bcs_;
  bool pinned_ = false;

  std::shared_ptr<Form> a_, L_, a_bdf2_, L_bdf2_;
  std::shared_ptr<Form> kinetic_, divergence_, phase_weight_, pressure_integral_;
  std::vector<std::shared_ptr<Form>> phase_velocity_;
  std::shared_ptr<Form> membrane_delta_, energy_ch_, lambda_dissipation_, lambda_membrane_;
  double domain_volume_ = 0;
  double area_target_ = 0;

  /// Periodic directions (plain assembly without): rebuilt with the BCs on every mesh.
  std::unique_ptr<PeriodicConstraint> periodic_;
  std::unique_ptr<dolfinx::la::petsc::Matrix> A_;
  std::unique_ptr<dolfinx::la::Vector<T>> b_, x_;
  /// -A g of the Dirichlet values, from the last matrix assembly (reused with the factorisation)
  std::unique_ptr<dolfinx::la::Vector<T>> lifting_;
  std::unique_ptr<LinearSolver> solver_;
  /// Inputs of the factorised matrix; a step compares them with the current ones.
  bool factorised_ = false;
  double factorised_dt_ = 0, factorised_w_ = 0;
  bool factorised_second_order_ = false;
  std::vector<T> factorised_phi_, factorised_mu_, factorised_v_, factorised_phi_cells_;
  std::vector<T> factorised_eta_, factorised_v_prev_;
  int factorisations_ = 0, krylov_iterations_ = 0;
};
} // namespace cellphase
