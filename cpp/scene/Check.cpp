#include "scene/Check.h"
#include "scene/Geometry.h"
#include "scene/MeshDomain.h"
#include "scene/Plan.h"
#include "scene/Resolution.h"
#include "scene/Sections.h"
#include "scene/Units.h"
#include "scene/YamlRead.h"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace cellphase::scene
{
using yaml::fmt;
using yaml::join;

namespace
{

std::string point(const std::array<double, 3>& p, int dim) { return point_text(p, dim); }

std::string shape_text(const Cell& c, int dim)
{
  std::string s;
  switch (c.shape)
  {
  case ShapeKind::circle:
    s = std::string(dim == 2 ? "circle" : "sphere") + ", radius " + fmt(c.radius);
    break;
  case ShapeKind::ellipse:
    s = std::string(dim == 2 ? "ellipse" : "ellipsoid") + ", semi-axes " + fmt(c.semi_axes[0])
        + " x " + fmt(c.semi_axes[1]) + (dim == 3 ? " x " + fmt(c.semi_axes[2]) : "");
    break;
  case ShapeKind::cassini:
    s = "Cassini oval, a " + fmt(c.cassini_a) + ", b " + fmt(c.cassini_b);
    break;
  case ShapeKind::expression:
    s = "expression \"" + c.expression + "\"";
    break;
  case ShapeKind::field:
    s = "phase field phi0 = \"" + c.expression + "\"";
    break;
  }
  s += ", centre " + point(c.center, dim);
  if (c.rotation != 0)
    s += ", rotated " + fmt(c.rotation * 180 / M_PI) + " deg";
  return s;
}

/// Two significant digits: the estimate is not more precise than that.
std::string rough(double v)
{
  if (v < 100)
    return std::to_string(std::lround(v));
  if (v >= 1e6)
  {
    std::ostringstream s;
    s.precision(2);
    s << v; // 1.8e+08
    return s.str();
  }
  const double scale = std::pow(10.0, std::floor(std::log10(v)) - 1);
  std::ostringstream s;
  s.precision(0);
  s << std::fixed << std::round(v / scale) * scale;
  return s.str();
}

class Report
{
public:
  void line(const std::string& label, const std::string& text)
  {
    out_ << "  " << label << std::string(label.size() < 22 ? 22 - label.size() : 1, ' ')
         << text << '\n';
  }
  std::ostringstream out_;
};

std::string vector_text(const std::array<double, 3>& v, int dim)
{
  std::string t = "(";
  for (int i = 0; i < dim; ++i)
    t += (i ? ", " : "") + fmt(v[i]);
  return t + ")";
}

/// The flow section: equations with the numbers that enter them.
std::string initial_text(const SpeciesInitial& i)
{
  if (i.random)
    return "random in [" + fmt((*i.random)[0]) + ", " + fmt((*i.random)[1]) + "]";
  if (i.where.empty())
    return fmt(i.value);
  return fmt(i.value) + " where " + i.where + ", else " + fmt(i.otherwise);
}

void polar_gel_report(const Scene& s, Report& r)
{
  const PolarGel& g = *s.polar_gel;
  const std::string kind = g.activity > 0 ? "contractile" : g.activity < 0 ? "extensile" : "passive";
  r.line("polar gel", "orientation field P (forms/polar_gel.py, 6.16-6.17), Pa " + fmt(s.numbers.Pa)
                          + ", c1 " + fmt(g.c1) + ", beta " + fmt(g.beta));
  r.line("  flow coupling", "xi " + fmt(g.xi) + ", kappa " + fmt(g.kappa) + ", active stress 1/Fa = "
                                + fmt(g.activity) + " (" + kind + ", 6.11)");
  r.line("  stabilisation", "S = " + fmt(g.stabilisation) + " (S (P#^{n+1} - P#^n) in (6.16))");
  r.line("  initial P", "(" + fmt(g.direction[0]) + ", " + fmt(g.direction[1]) + ") + delta, |delta_i| <= "
                            + fmt(g.noise)
                            + (g.noise_length > 0 ? " on a lattice of spacing " + fmt(g.noise_length)
                                                  : " at every node")
                            + ", seed " + std::to_string(g.seed)
                            + (g.splay != 0 ? ", plus a splay of divergence " + fmt(g.splay) : "")
                            + (g.inside_only ? ", times phi~ (inside the cell only)" : "")
                            + (g.mirror ? ", mirrored about the centre line in x" : ""));
}

void reaction_diffusion_report(const Scene& s, Report& r)
{
  const ReactionDiffusion& rd = *s.reaction_diffusion;
  r.line("reaction-diffusion", "model " + rd.model + " (forms/" + rd.model
                                   + ".py), regularisation " + fmt(rd.regularisation)
                                   + ", seed " + std::to_string(rd.seed));
  for (const auto& sp : rd.species)
    r.line("  species " + sp.name, std::string(sp.membrane ? "membrane" : "bulk") + ", diffusion "
                                       + fmt(sp.diffusion) + ", initial "
                                       + initial_text(sp.initial));
  std::string k;
  for (const auto& [name, value] : rd.kinetics)
    k += (k.empty() ? "" : ", ") + name + " " + fmt(value);
  r.line("  kinetics", k);
  if (rd.frozen_until > 0)
    r.line("  frozen", "shape and flow frozen until t = " + fmt(rd.frozen_until)
                           + " (the pattern forms on the initial shape)");
  if (s.flow)
    r.line("  protrusion", s.numbers.Fa ? "-(1/Fa) c1 grad phi with Fa = " + fmt(*s.numbers.Fa)
                                         + " (5.7)"
                                        : "none (numbers.Fa absent)");
  if (rd.chemotaxis)
  {
    const Chemotaxis& c = *rd.chemotaxis;
    const char* modes[] = {"rotating (mode 1)", "sinusoidal (mode 2)", "random turns (mode 3)",
                           "point source (mode 4)"};
    std::string text = std::string(modes[int(c.mode)]) + ", xi " + fmt(c.xi);
    if (c.mode == Chemotaxis::Mode::random_turns)
      text += ", turns of " + fmt(c.omega * 180 / std::numbers::pi) + " deg every "
              + std::to_string(c.theta) + " steps";
    else if (c.mode == Chemotaxis::Mode::point_source)
      text += ", x0 " + point(c.x0, s.domain.dim);
    else
      text += ", omega " + fmt(c.omega);
    r.line("  chemotaxis", text);
  }
}

void flow_report(const Scene& s, Report& r)
{
  const Flow& f = *s.flow;
  const int dim = s.domain.dim;
  const double Re = flow_reynolds(s);
  std::string eq = Re == 0 ? "Stokes (Re = 0" : "Navier-Stokes (Re = " + fmt(Re);
  if (Re == 0 && f.equations == FlowEquations::navier_stokes)
    eq += ", as numbers.Re is 0";
  r.line("flow", eq + "), P2/P1 Taylor-Hood, split: flow first, then phi advected (5.3)");
  r.line("  density", "inside " + fmt(f.density[1]) + ", outside " + fmt(f.density[0])
                          + " (relative; Re rho(phi) in the inertia)");
  r.line("  viscosity", "inside " + fmt(f.viscosity[1]) + ", outside " + fmt(f.viscosity[0])
                            + " (relative, (2.56))");
  r.line("  body force", "rho(phi) " + vector_text(f.gravity, dim) + " + "
                             + vector_text(f.force, dim));
  if (f.cell_force)
  {
    std::string F = "(";
    for (int c = 0; c < dim; ++c)
      F += (c ? ", " : "") + (*f.cell_force)[c];
    r.line("  force on the cells", F + ") (1 + phi_cells)/2");
  }
  const double cap = flow_capillary(s);
  if (s.phase_field.model == Model::helfrich_hm1)
  {
    r.line("  interface force", "w grad phi (3.59), w = dE/dphi (3.62)");
    if (f.coupling_stabilisation > 0)
      r.line("  stabilised split", "-div(" + fmt(f.coupling_stabilisation)
                                         + " grad(w^{n+1} - w^n)) in the phase field's step");
  }
  else if (is_helfrich(s.phase_field.model))
  {
    r.line("  interface force", "(dE/dphi) grad phi (3.81), dE/dphi of (3.84) projected on P2");
    if (f.coupling_stabilisation > 0)
      r.line("  stabilised split", "-" + fmt(f.coupling_stabilisation)
                                         + " (B^{n+1} - B^n) in the phase field's step, B the "
                                           "bending part of dE/dphi");
  }
  else
    r.line("  interface force", fmt(cap) + " mu grad phi (2.8; 3 sigma/(2 sqrt2) = 1/Ca"
                                    + (f.surface_tension ? ", sigma " + fmt(*f.surface_tension)
                                                         : std::string(" from numbers.Ca"))
                                    + ")");
  std::string walls;
  auto wall_text = [&](const std::string& where, const WallSpec& w)
  {
    walls += std::string(walls.empty() ? "" : ", ") + where + " " + to_string(w.type);
    if (w.type == WallType::moving)
      walls += " " + vector_text(w.velocity, dim);
    if (w.type == WallType::prescribed)
    {
      walls += " (";
      for (int c = 0; c < dim; ++c)
        walls += (c ? ", " : "") + w.profile[c];
      walls += ")";
    }
  };
  if (s.domain.mesh)
    for (const std::string& name : s.domain.mesh->tag_names())
    {
      const auto it = f.tag_walls.find(name);
      wall_text(name, it != f.tag_walls.end() ? it->second : WallSpec{});
    }
  else
    for (int i = 0; i < 2 * dim; ++i)
      wall_text(side_names[i], f.walls[i]);
  r.line("  walls", walls);
  if (!f.petsc.empty())
  {
    std::string opts;
    for (const auto& [k, v] : f.petsc)
      opts += (opts.empty() ? "" : " ") + ("-flow_" + k) + (v.empty() ? "" : " " + v);
    r.line("  solver", opts);
  }
}

} // namespace

long number_of_steps(const Scene& s) { return steps_between(s, 0.0); }

long steps_between(const Scene& s, double from)
{
  // A remainder below 1e-6 dt is round-off of the scene's numbers (end_time = 1, dt = 1e-3
  // is 1000 steps; end_time = 0.2, dt = 0.00114285714 is 175): the last step ends at
  // end_time instead of adding a step of 1e-10, whose system is singular to working precision.
  const double steps = (s.numerics.end_time - from) / s.numerics.dt;
  return std::max(0L, static_cast<long>(std::ceil(steps - 1e-6)));
}

std::string stabilised_accuracy_warning(const Scene& s)
{
  if (s.numerics.linearisation != Linearisation::stabilised)
    return "";
  const auto& pf = s.phase_field;
  const double eps = s.numerics.epsilon, dt = s.numerics.dt;
  // Measured guides (docs/scenes.md, "Linearisation"): beyond them the explicit terms make
  // the error many times Taylor's at the same dt.
  if (pf.model == Model::cahn_hilliard)
  {
    const double q = s.numerics.stabilisation * pf.mobility * dt / (eps * eps * eps);
    if (q > 0.1)
      return "S gamma dt / eps^3 = " + fmt(q) + " > 0.1: the stabilised Cahn-Hilliard error "
             "is about 15 times Taylor's at this dt (it matches Taylor's at about dt/16); use "
             "linearisation: taylor or dt <= " + fmt(dt * 0.1 / q);
  }
  if (pf.model == Model::helfrich_lagrange || pf.model == Model::helfrich_penalty)
  {
    const double q = pf.mobility * dt / (s.numbers.Be * eps * eps);
    if (q > 0.1)
      return "gamma dt / (Be eps^2) = " + fmt(q) + " > 0.1: the stabilised Helfrich error is "
             "up to 20 times Taylor's at this dt (it matches Taylor's at about dt/128 for "
             "gamma dt / (Be eps^2) = 11); use linearisation: taylor or dt <= "
             + fmt(dt * 0.1 / q);
  }
  return "";
}

long number_of_outputs(const Scene& s)
{
  if (s.output.every <= 0)
    return 1; // the final state only
  // The initial state, every `every` steps, and the end when it falls between.
  const long steps = number_of_steps(s);
  return 1 + steps / s.output.every + (steps % s.output.every != 0 ? 1 : 0);
}

SizeEstimate estimate_size(const Scene& s)
{
  const Domain& d = s.domain;
  SizeEstimate e;
  // 2D base meshes have crossed diagonals: four triangles per rectangle
  e.base_cells = d.mesh ? double(d.mesh->data().num_cells())
                 : d.dim == 2 ? 4.0 * d.resolution[0] * d.resolution[1]
                              : 6.0 * d.resolution[0] * d.resolution[1] * d.resolution[2];
  for (const Cell& c : s.cells)
    e.interface_measure += interface_measure(d, SignedDistance(c, d.dim));
  if (required_levels(s) > 0)
  {
    // Refined band: |phi| < threshold, plus one coarse cell on each side.
    const double band = 2 * std::atanh(s.numerics.mesh.refine_threshold) * std::sqrt(2.0)
                            * s.numerics.epsilon
                        + 2 * base_cell_size(d);
    const double h = finest_cell_size(s);
    const double fine_volume = d.dim == 2 ? h * h / 2 : h * h * h / 6;
    e.refined_cells = e.interface_measure * band / fine_volume;
    if (s.numerics.mesh.refine_inside.value_or(false))
    {
      const double coarser = std::pow(d.dim == 2 ? 4.0 : 8.0, s.numerics.mesh.inside_coarser_by);
      for (const Cell& c : s.cells)
        e.refined_cells += enclosed_measure(d, SignedDistance(c, d.dim)) / (fine_volume * coarser);
    }
    // Never more than the base mesh refined everywhere (a band wider than the domain).
    const double uniform = e.base_cells * std::pow(d.dim == 2 ? 4.0 : 8.0, required_levels(s));
    e.refined_cells = std::min(e.refined_cells, uniform - e.base_cells);
  }
  const double per_cell = d.dim == 2 ? 2.0 : 1.4; // P2 dofs per simplex, asymptotically
  e.dofs = per_cell * (e.base_cells + e.refined_cells)
           * static_cast<double>(model_fields(s.phase_field.model).size());
  return e;
}

std::string check_report(const Scene& s)
{
  const Domain& d = s.domain;
  const int dim = d.dim;
  Report r;
  r.out_ << "scene " << s.source << " is valid\n";

  std::string domain, cells_per_axis;
  for (int a = 0; a < dim; ++a)
  {
    domain += (a ? " x [" : "[") + fmt(d.lower[a]) + ", " + fmt(d.upper[a]) + "]";
    cells_per_axis += (a ? " x " : "") + std::to_string(d.resolution[a]);
  }
  r.line("dimension", std::to_string(dim) + "D (" + (dim == 2 ? "triangles" : "tetrahedra")
                          + ")");
  if (d.mesh)
  {
    const MeshDomain& m = *d.mesh;
    r.line("domain", "mesh " + m.path() + ", " + std::to_string(m.data().num_cells())
                         + " triangles, area " + fmt(m.area()) + ", bounding box " + domain);
    std::string tags;
    for (const std::string& name : m.tag_names())
      tags += (tags.empty() ? "" : ", ") + name + " (length " + fmt(m.tag_length(m.tag(name)))
              + ")";
    const double untagged = m.tag_length(MeshDomain::untagged);
    if (untagged > 0)
      tags += (tags.empty() ? "" : ", ") + std::string("untagged (length ") + fmt(untagged) + ")";
    r.line("boundary tags", tags.empty() ? "none" : tags);
  }
  else
    r.line("domain", domain + ", " + cells_per_axis + " base cells");
  if (!d.periodic.empty())
  {
    std::string axes;
    for (int a : d.periodic)
      axes += std::string(axes.empty() ? "" : ", ") + "xyz"[a];
    r.line("periodic", axes + " (dolfinx_mpc; all fields, flow sides on these axes open)");
  }
  r.line("boundary", std::string("phi ")
                         + (s.phi_boundary == PhiBoundary::dirichlet ? "dirichlet (phi = -1)"
                                                                     : "neumann")
                         + (d.periodic.empty() ? "" : " on the non-periodic sides")
                         + (s.phi_tags.empty() ? "" : " on " + join(s.phi_tags))
                         + (s.contact_angle_deg ? ", contact angle " + fmt(*s.contact_angle_deg)
                                                      + " degrees on the walls"
                                                : ""));
  r.line("cells", std::to_string(s.cells.size()));
  for (std::size_t i = 0; i < s.cells.size(); ++i)
    r.line("  " + s.cells[i].name, shape_text(s.cells[i], dim));

  const PhaseField& pf = s.phase_field;
  r.line("model", std::string(to_string(pf.model)) + " (fields "
                      + join(model_fields(pf.model)) + "), linearisation "
                      + to_string(s.numerics.linearisation)
                      + (s.numerics.linearisation == Linearisation::stabilised
                             ? " (S = " + fmt(s.numerics.stabilisation) + ")"
                             : "")
                      + (s.numerics.time_scheme == Numerics::TimeScheme::bdf2
                             ? ", time scheme bdf2 (second order; the first step and the "
                               "explicit sources backward Euler"
                                   + std::string(flow_history_fields(s).empty() ? ""
                                                 : s.numerics.coupling == Numerics::Coupling::lagged
                                                     ? "; the flow driven by phi^n, mu^n (lagged)"
                                                 : flow_extrapolates_potential(s)
                                                     ? "; the flow driven by phi*, mu*"
                                                     : "; the flow driven by phi*, dE/dphi^n")
                                   + ")"
                             : ", time scheme euler (first order)"));
  r.line("phase field", "mobility " + fmt(pf.mobility) + ", H0 " + fmt(pf.spontaneous_curvature)
                            + ", penalties p1 " + fmt(pf.penalty_volume) + " p2 "
                            + fmt(pf.penalty_area) + ", constraint relaxation "
                            + fmt(pf.constraint_relaxation));

  const Numbers& n = s.numbers;
  const DerivedFlags from_units = derivable_numbers(s.units);
  auto origin = [&](bool derived) { return derived ? "" : " (default)"; };
  const bool units = s.units.length || s.units.velocity || s.units.density || s.units.viscosity
                     || s.units.bending_rigidity || s.units.surface_tension
                     || s.units.protrusion_coefficient || s.units.frank_constant;
  if (units)
    r.line("numbers (from units)", "Re = " + fmt(n.Re) + origin(from_units.Re) + ", Ca = "
                                       + fmt(n.Ca) + origin(from_units.Ca) + ", Be = "
                                       + fmt(n.Be) + origin(from_units.Be)
                                       + (n.Fa ? ", Fa = " + fmt(*n.Fa) : "")
                                       + (s.polar_gel ? ", Pa = " + fmt(n.Pa) + origin(from_units.Pa) : ""));
  else
    r.line("numbers", "Re = " + fmt(n.Re) + ", Ca = " + fmt(n.Ca) + ", Be = " + fmt(n.Be)
                          + (n.Fa ? ", Fa = " + fmt(*n.Fa) : "")
                          + (s.polar_gel ? ", Pa = " + fmt(n.Pa) : ""));
  if (n.time_scale_s)
    r.line("time scale", "L/V = " + fmt(*n.time_scale_s) + " s; end time "
                             + fmt(s.numerics.end_time * *n.time_scale_s) + " s");

  if (s.flow)
    flow_report(s, r);
  else
    r.line("flow", "none (phase field only)");

  if (s.reaction_diffusion)
    reaction_diffusion_report(s, r);
  if (s.polar_gel)
    polar_gel_report(s, r);

  r.out_ << "  operator split" << (s.numerics.split ? " (numerics.split)" : " (the thesis' order)")
         << ", one step:\n" << plan_text(make_plan(s));

  const double eps = s.numerics.epsilon;
  const int levels = required_levels(s);
  const double h = finest_cell_size(s);
  r.line("epsilon", fmt(eps));
  r.line("interface width", fmt(interface_width(eps)) + " (|phi| < 0.9, 4.16 epsilon)");
  r.line("base cell size", fmt(base_cell_size(d)));
  if (s.numerics.mesh.adaptive)
  {
    r.line("refinement levels", std::to_string(levels) + " (max "
                                    + std::to_string(s.numerics.mesh.max_levels) + ")");
    r.line("finest cell size", fmt(h));
    r.line("points across", fmt(interface_width(eps) / h) + " mesh points across the interface "
                                "(requested " + fmt(s.numerics.mesh.points_across_interface)
                                + ")");
    const int coarser = s.numerics.mesh.inside_coarser_by;
    r.line("refined", !s.numerics.mesh.refine_inside.value_or(false)
                          ? "the interfaces"
                      : coarser == 0
                          ? "the interfaces and the cells' interiors (refine_inside)"
                          : "the interfaces, and the cells' interiors to cell size "
                                + fmt(std::ldexp(h, coarser)) + " (refine_inside, "
                                + std::to_string(coarser) + " level" + (coarser > 1 ? "s" : "")
                                + " coarser: inside_coarser_by)");
  }
  else
  {
    r.line("refinement levels", "0 (numerics.mesh.adaptive: false, the uniform base mesh)");
    r.line("points across", fmt(interface_width(eps) / h) + " mesh points across the interface");
  }
  r.line("remeshing", s.numerics.mesh.remesh_every > 0
                          ? "every " + std::to_string(s.numerics.mesh.remesh_every) + " steps"
                          : std::string("never (mesh built once)"));

  const long steps = number_of_steps(s);
  if (const auto& a = s.numerics.adaptive_dt)
  {
    r.line("time step", "adaptive from " + fmt(s.numerics.dt) + ", in [" + fmt(a->dt_min) + ", "
                            + fmt(a->dt_max) + "], end time " + fmt(s.numerics.end_time));
    r.line("step control", "local error estimate <= " + fmt(a->tolerance) + " (max |phi - phi*| "
                               "over the nodes), growth <= " + fmt(a->growth) + ", safety "
                               + fmt(a->safety) + (s.flow ? ", cfl " + fmt(a->cfl) : ""));
    r.line("steps", "as the estimate says (" + std::to_string(steps) + " at the first step)");
  }
  else
  {
    r.line("time step", fmt(s.numerics.dt) + ", end time " + fmt(s.numerics.end_time));
    r.line("steps", std::to_string(steps));
  }
  if (const auto& w = s.numerics.stop_when_settled)
    r.line("stop when settled", w->observable + " varies by at most max(" + fmt(w->relative)
                                    + " |value|, " + fmt(w->absolute) + ") over "
                                    + fmt(w->over) + " time units (from t = "
                                    + fmt(w->after + w->over) + ")");
  const std::string guide = stabilised_accuracy_warning(s);
  if (!guide.empty())
    r.out_ << "  warning: " << guide << "\n";
  r.line("outputs", s.output.every > 0
                        ? std::to_string(number_of_outputs(s)) + " (initial state, every "
                              + std::to_string(s.output.every) + " steps and the end) of "
                              + join(s.output.fields) + " to " + s.output.directory
                        : "1 (the final state, output.every = 0) of " + join(s.output.fields)
                              + " to " + s.output.directory);
  r.line("field format", s.output.format == OutputFormat::vtk
                             ? "vtk (fields.pvd, one .vtu per time, P2 kept exact)"
                             : "xdmf (fields.xdmf, one grid per time, P2 as P1 on the refined mesh)");
  const int cp = s.output.checkpoints.every;
  r.line("checkpoints", cp > 0 ? "at the start, every " + std::to_string(cp)
                                     + " steps and at the end (keep "
                                     + std::to_string(s.output.checkpoints.keep) + ")"
                               : std::string("none (output.checkpoints.every = 0; a numerical "
                                             "failure or a stop signal still writes one)"));

  const SizeEstimate e = estimate_size(s);
  std::ostringstream measure;
  measure.precision(3);
  measure << e.interface_measure;
  r.line(dim == 2 ? "interface length" : "interface area", std::string("~") + measure.str());
  // The reduced area 4 pi A / L^2 (2D) or volume 6 sqrt(pi) V / A^(3/2) (3D) of each cell's
  // sharp initial shape: 1 for a circle (sphere), the shape parameter of the vesicle papers.
  std::ostringstream reduced;
  reduced.precision(3);
  for (std::size_t i = 0; i < s.cells.size(); ++i)
  {
    if (s.cells[i].shape == ShapeKind::field)
      continue; // a given phase field, not a distance: no sharp shape to measure
    const SignedDistance shape(s.cells[i], dim);
    const double inside = enclosed_measure(s.domain, shape), size = interface_measure(s.domain, shape);
    const double nu = dim == 2 ? 4 * std::numbers::pi * inside / (size * size)
                               : 6 * std::sqrt(std::numbers::pi) * inside / std::pow(size, 1.5);
    reduced << (reduced.tellp() > 0 ? ", " : "") << nu << " (" << s.cells[i].name << ")";
  }
  if (reduced.tellp() > 0)
    r.line(dim == 2 ? "reduced area" : "reduced volume", reduced.str());
  r.line("mesh cells", std::string("~") + rough(e.base_cells + e.refined_cells) + " (" + rough(e.base_cells)
                           + " base + ~" + rough(e.refined_cells) + " in the refined band)");
  r.line("degrees of freedom",
         std::string("~") + rough(e.dofs) + " (P2, " + std::to_string(model_fields(pf.model).size())
             + " field" + (model_fields(pf.model).size() > 1 ? "s" : "") + ")");
  r.out_ << "  (mesh cells and degrees of freedom are rough estimates from the interface size)\n";
  return r.out_.str();
}

} // namespace cellphase::scene
