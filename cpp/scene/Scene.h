// The validated description of one experiment, read from a YAML scene file.
// Everything here is plain data (no DOLFINx), so the parser and `cellphase check`
// stay cheap to build and to test.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cellphase::scene
{
class MeshDomain;

/// Rectangle (2D) or box (3D) domain meshed with triangles / tetrahedra, or a 2D mesh
/// read from a file (domain.mesh; lower/upper are then its bounding box).
struct Domain
{
  int dim = 2;
  std::array<double, 3> lower{0, 0, 0};
  std::array<double, 3> upper{1, 1, 0};
  std::array<int, 3> resolution{16, 16, 0}; ///< base cells per axis
  /// Periodic axes (0, 1, 2 = x, y, z), sorted: the max face is identified with the min face.
  std::vector<int> periodic;
  /// domain.mesh as written in the scene (empty: the box) and the mesh read from it.
  std::string mesh_file;
  std::shared_ptr<const MeshDomain> mesh;
  bool is_periodic(int axis) const;
  /// The point moved by whole periods into [lower, upper] along the periodic axes where it
  /// lies beyond a side by more than round-off (a node of a cell's patch wrapped across a
  /// periodic side lies a period up); points within the period are returned unchanged.
  std::array<double, 3> into_period(double x, double y, double z) const;
  double volume() const;
  /// The longest side of the box (of the bounding box for a mesh file): the length that
  /// geometric tolerances scale with.
  double largest_extent() const;
};

/// Boundary condition of the phase field: phi = -1 (2.19) or homogeneous Neumann.
enum class PhiBoundary { dirichlet, neumann };

enum class ShapeKind { circle, ellipse, cassini, expression, field };

/// One cell's initial shape; its phase field is tanh(-r/(sqrt2 eps)) with r the signed
/// distance (negative inside), eq. (2.12).
struct Cell
{
  std::string name;               ///< "cells[i]" unless the scene names it
  ShapeKind shape = ShapeKind::circle;
  std::array<double, 3> center{0, 0, 0};
  double radius = 0;              ///< circle / sphere
  std::array<double, 3> semi_axes{0, 0, 0}; ///< ellipse / ellipsoid
  double rotation = 0;            ///< radians, about the z axis
  double cassini_a = 0, cassini_b = 0; ///< Cassini oval |x-f1||x-f2| = b^2, foci at +-a
  std::string expression;         ///< signed distance in x, y, z (muparser syntax); for
                                  ///< shape field phi_0 itself
  double field_epsilon = 0;       ///< shape field: epsilon of r = -sqrt2 eps atanh(phi_0) (2.12)
  /// Phase field the cell belongs to: cells of one group share a phase field (case (a) of
  /// Fig. 7.3); by default every cell has its own (7.3).
  std::string group;
  /// Parameters of this cell's phase field (7.4)-(7.10); absent: those of phase_field and
  /// numbers. Cells of one group must agree.
  std::optional<double> Be, spontaneous_curvature, mobility, penalty_area;
  /// eta_i / eta_0 of this cell in eta(phi_1, ..., phi_N) (7.12); absent: flow.viscosity.inside.
  std::optional<double> viscosity;
};

/// The interaction function w-bar of Fig. 7.7: repulsion strength r1 and range r2 (in
/// eps^2), adhesion strength a1, position a2 (in eps) and range a3 (in eps^2); the Gaussian
/// w of (7.2) is r1 = r2 = 1, a1 = 0.
struct InteractionPotential
{
  double r1 = 1, r2 = 1, a1 = 0, a2 = 0, a3 = 1;
  bool operator==(const InteractionPotential&) const = default;
};

/// The interaction of one pair of phase fields (named by their groups), In_ij = In_ji of
/// (7.5) and (7.11) and the potential that both cells' w take for the other.
struct InteractionPair
{
  std::string first, second;
  double In = 0.01;
  InteractionPotential potential;
};

/// Interaction between the cells' phase fields, (7.5) and (7.11): the interaction number
/// In and the potential of every pair, except the pairs listed with their own.
struct Interaction
{
  double In = 0.01;
  InteractionPotential potential;
  std::vector<InteractionPair> pairs;
  /// The interaction part of each cell's w (phi#, the flow's force 7.12) made again from
  /// phi^{n+1} after every step; false: from phi^n, as the step's source (7.11) uses it.
  bool refresh = false;
  /// The interaction's part of phi# in the flow's force (7.12), as the thesis writes it.
  /// false: left out; summed over the cells it is the gradient (1/In) grad sum B(phi_i) w_j,
  /// which the pressure absorbs, so only its discretisation error goes with it.
  bool flow_force = true;
  /// w'_i of (7.11) only where the distance |d_i| < derivative_reach eps (forms/cellphase_ufl.py);
  /// absent: wherever |phi_i| < 1, as the thesis writes it.
  std::optional<double> derivative_reach;
};

/// The phase-field / membrane model of section 2.5 and 3.4.1.
enum class Model
{
  allen_cahn,          ///< (2.24)
  allen_cahn_volume,   ///< (2.26)-(2.27)
  cahn_hilliard,       ///< (2.25)
  helfrich_lagrange,   ///< (3.25)-(3.29)
  helfrich_penalty,    ///< (3.30)-(3.32)
  helfrich_hm1         ///< (3.33)-(3.35)
};

/// How the nonlinear terms W'(phi), W''(phi) mu are treated in time.
enum class Linearisation
{
  taylor,     ///< first-order Taylor expansion about phi^n (section 5.3): matrix changes every step
  stabilised  ///< explicit nonlinearity + S (phi^{n+1} - phi^n): matrix constant between remeshes
};

struct PhaseField
{
  Model model = Model::helfrich_penalty;
  double mobility = 1.0;             ///< gamma
  double spontaneous_curvature = 0;  ///< H0 (dimensionless)
  double penalty_volume = 0;         ///< p1 of (3.30)
  double penalty_area = 0;           ///< p2 of (3.30), (3.33)
  double constraint_relaxation = 0.5; ///< drift correction of the multipliers, (1/2tau) in 5.3
  /// Helfrich models: add the surface tension energy (1/Ca) E_CH of (3.77)-(3.78)
  bool surface_tension = false;
  /// cahn_hilliard: gamma(phi) = mobility W(phi) (section 2.8) instead of the constant
  bool degenerate_mobility = false;
};

/// Physical parameters (SI) from which the dimensionless numbers follow, (3.12)-(3.17).
struct PhysicalUnits
{
  std::optional<double> length, velocity, density, viscosity, bending_rigidity, surface_tension;
  std::optional<double> protrusion_coefficient; ///< alpha of (5.8), N/m^2
  std::optional<double> frank_constant;         ///< k of (6.2), N: Pa = eta V L / k
  std::optional<double> activity_parameter;     ///< zeta of (6.11), N/m^2 (sign: contractile > 0)
  std::optional<double> rotational_viscosity;   ///< eta_rot of (6.16), Pa s
};

/// Dimensionless numbers used by the equations.
struct Numbers
{
  double Re = 0, Ca = 1, Be = 1;
  /// Active surface force number (5.8) of the protrusion force -(1/Fa) c1 grad phi (5.7);
  /// absent: no protrusion force.
  std::optional<double> Fa;
  /// Polarisation elasticity number Pa = eta V L / k of (6.4) (polar_gel)
  double Pa = 1;
  std::optional<double> time_scale_s; ///< L/V when units are given
};

struct Mesh
{
  /// false: the base mesh itself, uniform and never rebuilt (no refinement levels).
  bool adaptive = true;
  int remesh_every = 10;             ///< steps between rebuilds from the base mesh; 0 = only at start
  double points_across_interface = 6;
  double refine_threshold = 0.95;    ///< cells with |phi| below this are refined
  int max_levels = 8;                ///< safety cap on refinement levels
  /// Refine the cells' interiors (phi > -threshold) as finely as the interface; absent:
  /// true with polar_gel (P lives inside the cell, section 6.3), else false.
  std::optional<bool> refine_inside;
  /// With refine_inside: refinement levels the interior stays coarser than the interface
  /// (its cells 2^k times the interface's). P varies on the cell's scale inside, on
  /// epsilon's only across the interface, whose band keeps the finest level.
  int inside_coarser_by = 0;
  /// Where each phase field is solved: on the one mesh refined around all cells (shared),
  /// or on its own patch of the base mesh refined around its cell only (own), which makes
  /// the cells' cost linear in their number (section 7.2).
  enum class CellMeshes { shared, own } cell_meshes = CellMeshes::shared;
  /// Own meshes: distance kept between the cell's band (phi > -0.9) and the edge of its
  /// patch, so that the cell may move that far between two remeshes.
  std::optional<double> own_margin;
  /// Absent: 16 epsilon. With 8, a flow through the patch's edge carried phi + 1 there
  /// up to 6e-3 and slowed the vessel flow of demos/rbc-bifurcation by 0.6 % per step.
  double own_margin_or_default(double epsilon) const { return own_margin.value_or(16 * epsilon); }
  /// How the base mesh (and every mesh refined from it) is split among MPI ranks: by
  /// DOLFINx's graph partitioner, or in stripes across the domain's longest axis, dealt
  /// to the ranks in turn, so that each cell's patch is shared by all ranks. Absent:
  /// stripes with own meshes, else graph.
  enum class Partition { graph, stripes };
  std::optional<Partition> partition;
  std::optional<double> stripe_width; ///< absent: 2 base cell sizes
  Partition partition_or_default() const
  {
    return partition.value_or(cell_meshes == CellMeshes::own ? Partition::stripes : Partition::graph);
  }
};

/// Bounds beyond which a run counts as failed numerically and stops (section "limits").
struct Limits
{
  double phi_bound = 2.0;              ///< stop when |phi| exceeds this anywhere
  std::optional<double> volume_drift;  ///< stop when |V - V0| / V0 exceeds this
};

/// Stop before end_time once an observable has settled: over the last `over` time units
/// it varied (max - min) by at most max(relative |value now|, absolute).
struct SettledStop
{
  std::string observable; ///< a column of observables.csv
  double over = 1;
  double relative = 1e-3, absolute = 0;
  double after = 0; ///< not before this time
};

/// numerics.adaptive_dt: the step follows an estimate of the local time error of the phase
/// fields (docs/scenes.md, "Adaptive time step"); numerics.dt is the first step.
struct AdaptiveDt
{
  double tolerance = 1e-3; ///< largest accepted estimate (max over the nodes, units of phi)
  double dt_min = 0;       ///< smallest step; a step this small is accepted whatever its estimate
  double dt_max = 0;       ///< largest step
  double growth = 2;       ///< largest ratio of a step to the one before (BDF2 needs <= 1 + sqrt2)
  double safety = 0.9;     ///< the next step aims at safety^2 of the tolerance
  double cfl = 0.5;        ///< with a flow: max |v| dt <= cfl * the finest cell size
};

struct Numerics
{
  double epsilon = 0.03;
  double dt = 1e-3;
  double end_time = 1.0;
  Linearisation linearisation = Linearisation::taylor;
  double stabilisation = 2.0;        ///< S of the stabilised scheme
  Mesh mesh;
  Limits limits;
  std::map<std::string, std::string> petsc; ///< options without the leading '-' and prefix
  /// Order of the operator split by sub-problem name (scene/Plan.h); absent: the thesis'.
  std::optional<std::vector<std::string>> split;
  /// Linear solves: a direct factorisation of every new matrix, or factors reused as the
  /// preconditioner of GMRES while they serve (solve/LinearSolver, reuse_factorisations).
  enum class Solver { direct, reuse } solver = Solver::direct;
  /// Time discretisation of the phase field: backward Euler (the thesis', first order) or
  /// the variable-step BDF2 (second order, forms/cellphase_ufl.py bdf2_constants).
  enum class TimeScheme { euler, bdf2 } time_scheme = TimeScheme::euler;
  /// What drives a BDF2 flow step: phi*, mu* extrapolated to t^{n+1} (second-order split)
  /// or phi^n, mu^n (lagged: the split's first-order error; backward Euler's coupling).
  enum class Coupling { extrapolated, lagged } coupling = Coupling::extrapolated;
  std::optional<SettledStop> stop_when_settled;
  /// Adaptive time step (numerics.adaptive_dt, app/StepSizeControl): absent, every step is dt.
  std::optional<AdaptiveDt> adaptive_dt;
};

struct Checkpoints
{
  int every = 100;                   ///< steps between checkpoints (also at the start and the end); 0 = none
  int keep = 2;                      ///< newest checkpoints kept
};

/// How the fields are written (docs/scenes.md, "Field output").
enum class OutputFormat
{
  xdmf, ///< fields.xdmf: one grid per time, P2 fields as P1 on the once refined mesh
  vtk   ///< fields.pvd: one .vtu per time with second-order Lagrange cells (P2 exact)
};

struct Output
{
  std::string directory = "output";
  OutputFormat format = OutputFormat::xdmf;
  int every = 10;                    ///< steps between field writes; 0 = the final state only
  std::vector<std::string> fields{"phi"};
  bool progress = true;
  Checkpoints checkpoints;
};

/// Which momentum equation the flow solves (section 2.8, (3.17)).
enum class FlowEquations
{
  stokes,        ///< Re = 0: quasi-steady Stokes, no inertia
  navier_stokes  ///< semi-implicit Navier-Stokes (section 5.3, step 1)
};

/// Velocity condition on one side of the box.
enum class WallType
{
  no_slip,   ///< v = 0
  moving,    ///< v = the wall's tangential velocity
  free_slip, ///< v.n = 0, no tangential stress
  open,      ///< traction-free ((2 eta D - p I) n = 0)
  prescribed ///< v = a profile given by formulas of x, y, z (an inflow)
};

struct WallSpec
{
  WallType type = WallType::no_slip;
  std::array<double, 3> velocity{0, 0, 0}; ///< moving walls
  std::array<std::string, 3> profile;      ///< prescribed: one formula per component
};

/// Sides of the box in the order of the flow module: left/right (x), bottom/top (y),
/// front/back (z).
const std::array<const char*, 6> side_names{"left", "right", "bottom", "top", "front", "back"};

/// The two-phase flow coupled to the phase field (section 2.8, 3.4.2, 3.5), in the thesis'
/// dimensionless scaling (3.17): Re rho (d_t v + v.grad v) + grad p = div(2 eta D) +
/// rho gravity + force + (dE/dphi) grad phi, with rho, eta interpolated in phi (2.56).
/// Local inextensibility of the membrane (section 3.4.3).
struct Inextensibility
{
  double xi = 1;               ///< xi of (3.68); Aland et al. recommend 1
  bool global_area = false;    ///< global area constraint (3.69)
  /// Concentration variant (3.70)-(3.72): xi_2 of (3.71) and d_c of (3.70); absent: off.
  struct Concentration
  {
    double penalty = 1;
    double diffusion = 1e-3;
  };
  std::optional<Concentration> concentration;
};

struct Flow
{
  FlowEquations equations = FlowEquations::navier_stokes;
  std::array<double, 2> density{1, 1};   ///< relative to the reference: {outside, inside}
  std::array<double, 2> viscosity{1, 1}; ///< relative to the reference: {outside, inside}
  std::array<double, 3> gravity{0, 0, 0}; ///< body force per unit relative density
  std::array<double, 3> force{0, 0, 0};   ///< constant body force density
  /// Body force on the cells only: F(x) (1 + phi_cells)/2 with F given by one formula per
  /// component in x, y, z (section 7.3.1: 0.5 (phi + 1) f1 / Fr).
  std::optional<std::array<std::string, 3>> cell_force;
  std::optional<double> surface_tension;  ///< sigma (dimensionless); default from Ca
  std::array<WallSpec, 6> walls;          ///< by side, see side_names (box domains)
  /// Mesh-file domains: by tag name; every tag not listed is no_slip, and so is the
  /// boundary that carries no tag.
  std::map<std::string, WallSpec> tag_walls;
  std::map<std::string, std::string> petsc; ///< options of the flow solver (prefix flow_)
  /// How the flow's matrices are solved; absent: numerics.solver (see flow_solver).
  std::optional<Numerics::Solver> solver;
  std::optional<Inextensibility> inextensibility; ///< absent: the membrane may stretch
  /// beta of forms/helfrich_hm1.py: a mobility on the step's change of the interface
  /// potential, -div(beta grad(w^{n+1} - w^n)); 0: the thesis' explicit split.
  double coupling_stabilisation = 0;
};

/// Initial value of one species: a constant, a constant where a formula is true (else
/// another), or uniformly random in [low, high] (seeded, reaction_diffusion.seed).
struct SpeciesInitial
{
  double value = 0;
  std::string where;      ///< muparser condition in x, y, z; empty: everywhere
  double otherwise = 0;   ///< where the condition is false
  std::optional<std::array<double, 2>> random; ///< [low, high]
};

/// One species of a reaction-diffusion model: its region is fixed by the model's form file
/// (the literal `species` of forms/<model>.py).
struct Species
{
  std::string name;        ///< as in the form file: c1, c2, C
  bool membrane = true;    ///< on the membrane (weight |grad phi~|, 2.39) or in the bulk (phi~, 2.36)
  double diffusion = 1;
  SpeciesInitial initial;
};

/// Chemotactic signal of (5.21), the four modes of section 5.4.3.
struct Chemotaxis
{
  enum class Mode { rotating, sinusoidal, random_turns, point_source } mode = Mode::rotating;
  double xi = 5;                 ///< signal strength
  double omega = 0;              ///< angular velocity (modes 1, 2) or turning angle (mode 3), radians
  int theta = 1;                 ///< mode 3: steps between turns
  double direction_deg = 0;      ///< mode 3: initial direction
  std::array<double, 3> x0{0, 0, 0}; ///< mode 4: the source point (outside the domain)
};

/// Bulk-surface reaction-diffusion on the diffuse cell (2.45)-(2.46); model gtpase is
/// (5.1)-(5.6) in the diffuse form (5.16)-(5.18), forms/gtpase.py.
struct ReactionDiffusion
{
  std::string model = "gtpase";
  std::vector<Species> species;            ///< in the order of the form's mixed space
  /// The form's other constants by name (gtpase: a1..a5, b1, b2, gamma of Table 5.1).
  std::map<std::string, double> kinetics;
  std::string protrusion;                  ///< species of the protrusion force (5.7)
  double regularisation = 1e-6;            ///< rho of the weights (forms/gtpase.py)
  std::uint64_t seed = 1;                  ///< random initial values and turns
  /// The shape and the flow stay frozen until this time (the pre-polarisation of 5.4.1).
  double frozen_until = 0;
  std::optional<Chemotaxis> chemotaxis;
  /// Options of the species' solver (prefix rd_); absent: those of numerics.petsc.
  std::optional<std::map<std::string, std::string>> petsc;
  /// How the species' matrices are solved; absent: numerics.solver.
  std::optional<Numerics::Solver> solver;
};

/// Orientation field of an active polar gel in the cell (chapter 6, (6.16)-(6.17)),
/// forms/polar_gel.py; defaults of Table 6.1.
struct PolarGel
{
  double activity = 1;   ///< 1/Fa of the active stress (6.11): > 0 contractile, < 0 extensile
  double xi = 1.1;       ///< flow alignment (shape factor) of (6.16)
  double kappa = 1.65;   ///< rotational viscosity ratio eta_rot / eta of (6.16)
  double c1 = 5;         ///< double-well parameter of P, (6.4)
  double beta = 0;       ///< anchoring of P along grad phi, (6.4)
  /// S of the stabilised orientation step (forms/polar_gel.py); default (1 + |xi|)^2 /
  /// (2 eta_min) with a flow (twice the alignment feedback), 0 without.
  double stabilisation = 0;
  /// P^0 = direction + delta, delta uniform in [-noise, noise] per component (6.2.5)
  std::array<double, 3> direction{1, 0, 0};
  double noise = 0.05;
  /// Spacing of a lattice whose nodes draw delta (bilinear between them); 0: delta drawn
  /// at every mesh node (the thesis).
  double noise_length = 0;
  /// P^0 phi~(phi^0) instead of P^0 everywhere (the thesis): without the transient in
  /// which the double well empties the outside (see docs/scenes.md).
  bool inside_only = false;
  /// A splay added to P^0: splay ((x - x_c) . n) n, n the direction turned by +90 degrees,
  /// x_c the domain's centre: a fan of divergence `splay` (a seed of the splay mode).
  double splay = 0;
  /// R P^0(R x) with R the reflection about the domain's centre line in x: the mirror image
  /// of the same perturbation (Fig. 6.7).
  bool mirror = false;
  std::uint64_t seed = 1;
  /// How the orientation field's matrices are solved; absent: numerics.solver.
  std::optional<Numerics::Solver> solver;
};

struct Scene
{
  std::string source;                ///< file the scene came from
  std::vector<std::string> overrides; ///< the --set KEY=VALUE options, as given
  std::string resolved_yaml;         ///< the scene's YAML after --set overrides (for checkpoints)
  Domain domain;
  PhiBoundary phi_boundary = PhiBoundary::dirichlet;
  /// Mesh-file domains: the tags where phi = -1 holds (empty: the whole boundary).
  std::vector<std::string> phi_tags;
  /// cahn_hilliard: contact angle (degrees, through phi = +1) on every wall (2.8)
  std::optional<double> contact_angle_deg;
  std::vector<Cell> cells;
  PhaseField phase_field;
  PhysicalUnits units;
  Numbers numbers;
  Numerics numerics;
  Output output;
  std::optional<Flow> flow;           ///< absent: no flow module at all
  std::optional<Interaction> interaction; ///< absent: the cells do not interact
  std::optional<ReactionDiffusion> reaction_diffusion; ///< absent: no signalling species
  std::optional<PolarGel> polar_gel;  ///< absent: no orientation field
};

const char* to_string(Model m);
const char* to_string(Linearisation l);
/// Fields a model solves for, in the order of its mixed space (phi first).
std::vector<std::string> model_fields(Model m);
/// The fields of the phase field's previous step that a two-step scheme or the error
/// estimate of numerics.adaptive_dt keeps (phi_prev; mu_prev with numerics.time_scheme:
/// bdf2); none for backward Euler at a fixed step.
std::vector<std::string> history_fields(const Scene& s);
bool is_helfrich(Model m);
const char* to_string(WallType w);
const char* to_string(OutputFormat f);
/// Models the flow can be coupled to (they have the advection term and a chemical
/// potential for the interface force): cahn_hilliard (2.8), the Helfrich models
/// (Navier-Stokes-Helfrich: H^-1 (3.59)-(3.64), L2 with multipliers/penalties (3.81)-(3.85)).
bool couples_to_flow(Model m);
/// Re of the momentum equation: 0 for Stokes (explicitly or because numbers.Re = 0).
double flow_reynolds(const Scene& s);
/// flow.solver, else numerics.solver.
Numerics::Solver flow_solver(const Scene& s);
/// reaction_diffusion.solver, else numerics.solver.
Numerics::Solver reaction_diffusion_solver(const Scene& s);
/// polar_gel.solver, else numerics.solver.
Numerics::Solver polar_gel_solver(const Scene& s);
/// Prefactor of the interface force (dE/dphi) grad phi: 3 sigma / (2 sqrt2) = 1/Ca (3.13)
/// for Cahn-Hilliard (mu unscaled there), 1 for the Helfrich models (dE/dphi itself).
double flow_capillary(const Scene& s);

} // namespace cellphase::scene
