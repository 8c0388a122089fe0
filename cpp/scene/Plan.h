// The operator split of a scene as data: which sub-problems it builds, in which order they
// step, and the fields each reads and writes (qualified names, see core/FieldRegistry.h).
// Plain C++ (no DOLFINx), so that `cellphase check` prints and verifies it; the time loop
// builds exactly these sub-problems.
#pragma once
#include "scene/Scene.h"
#include <string>
#include <vector>

namespace cellphase::scene
{
struct PlanStep
{
  std::string name;        ///< as in numerics.split: "flow", "phase_field", ...
  std::string description; ///< for messages and the plan: "flow (Navier-Stokes, 2.47-2.57)"
  std::vector<std::string> reads, writes;
  /// Steps that begin before this time are skipped (reaction_diffusion.frozen_until
  /// freezes the shape and the flow while the pattern forms, section 5.4.1).
  double active_from = 0;
};

struct Plan
{
  std::vector<PlanStep> steps;      ///< in the order of the split
  std::vector<std::string> initial; ///< fields the scene gives initial values for
};

/// The cells that share one phase field (by Cell::group). With one group its fields are
/// cell.phi, cell.mu, ... (output labels phi, mu); with several, cell.<group>.phi, ...
/// (labels phi_<group>, ...) and the step phase_field.<group>.
struct CellGroup
{
  std::string name;
  std::string prefix;       ///< of its fields: "cell" or "cell.<group>"
  std::string label_suffix; ///< of its output labels: "" or "_<group>"
  std::string step;         ///< "phase_field" or "phase_field.<group>"
  std::vector<std::size_t> cells;
};
std::vector<CellGroup> cell_groups(const Scene& s);
/// The scene as one group's phase field sees it: only its cells, its own parameters.
Scene group_scene(const Scene& s, const CellGroup& g);

/// numerics.mesh.cell_meshes: own. Each phase field then lives on its own mesh (key: the
/// group's prefix) as <prefix>.own.<field>, and <prefix>.<field> are its copies on the
/// shared mesh, which the flow, the membrane union and the output read.
bool own_meshes(const Scene& s);
/// The field of the group's own state: <prefix>.<field>, or <prefix>.own.<field>.
std::string state_field(const Scene& s, const CellGroup& g, const std::string& field);
/// The flow's state one step back for its second-order step (numerics.time_scheme: bdf2
/// with one cell group): v^{n-1} and (numerics.coupling: extrapolated) the phase field and
/// potential that drove that step (flow.v_prev, flow.phi_prev, flow.potential_prev); none
/// otherwise, where the flow takes backward Euler steps driven by phi^n.
std::vector<std::string> flow_history_fields(const Scene& s);
/// Whether the second-order flow extrapolates the potential mu that drives it as it does
/// phi: for the H^-1 flows (cahn_hilliard, helfrich_hm1), whose mu is a solved field. The
/// L2 Helfrich flows' dE/dphi (3.84) is the rate -(d_t phi + v.grad phi)/gamma itself, an
/// algebraic response to v with a gain of order 1/gamma: extrapolating it,
/// (1 + w) dE^n - w dE^{n-1}, makes the explicit coupling unstable at every dt (seen:
/// phi blows up after 13-25 steps at dt 1e-3 .. 2.5e-4), so the flow reads dE^n there.
bool flow_extrapolates_potential(const Scene& s);

/// Sub-problems the scene needs, in the thesis' order (section 5.3: the membrane union,
/// then the flow with phi^n, the phase field with v^{n+1}, the reaction-diffusion with
/// phi^{n+1} and v^{n+1}, the membrane concentration), or
/// in the order of numerics.split. Does not verify it (see plan_problem).
Plan make_plan(const Scene& s);
/// The names make_plan would use without numerics.split.
std::vector<std::string> default_split(const Scene& s);
/// The species fields of reaction_diffusion: rd.<species>.
std::vector<std::string> species_fields(const Scene& s);
/// rd.force, the protrusion force -(1/Fa) c1 grad phi (5.7) the flow adds: with a flow
/// and numbers.Fa.
bool has_protrusion(const Scene& s);
/// "" if every field a step reads is written by a step of the plan or is initial data;
/// else the problem, naming the step and the field.
std::string plan_problem(const Plan& plan);
/// The plan as indented lines for `cellphase check`.
std::string plan_text(const Plan& plan);
} // namespace cellphase::scene
