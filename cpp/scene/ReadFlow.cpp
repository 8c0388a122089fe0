// flow: the two-phase flow coupled to the phase field (section 2.8, 3.4.2). Absent: no flow.
#include "scene/MeshDomain.h"
#include "scene/Plan.h"
#include "scene/Sections.h"
#include "scene/Shapes.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{
using namespace yaml;

namespace
{
/// inside/outside pair of positive numbers; returned as {outside, inside}.
std::array<double, 2> read_pair(const Section& f, const std::string& key)
{
  std::array<double, 2> out{1, 1};
  if (!f.has(key))
    return out;
  const Section p = f.section(key);
  p.allow_only({"inside", "outside"});
  out[0] = p.number("outside", out[0], positive());
  out[1] = p.number("inside", out[1], positive());
  return out;
}

std::array<double, 3> read_vector(const Section& f, const std::string& key, int dim)
{
  std::array<double, 3> out{0, 0, 0};
  if (!f.has(key))
    return out;
  const auto v = f.numbers(key, {std::size_t(dim)}, any());
  std::copy(v.begin(), v.end(), out.begin());
  return out;
}

const std::vector<std::pair<std::string, WallType>> wall_types{
    {"no_slip", WallType::no_slip},
    {"free_slip", WallType::free_slip},
    {"moving", WallType::moving},
    {"open", WallType::open},
    {"prescribed", WallType::prescribed}};

/// A vector of formulas (or numbers), one per component, in x, y, z.
std::array<std::string, 3> read_formulas(const Section& s, const std::string& key, int dim)
{
  const Value v = s.value(key);
  if (!v.node.IsSequence() || v.node.size() != std::size_t(dim))
    v.fail("found " + v.found() + ", expected a list of " + std::to_string(dim)
           + " formulas in x, y, z (numbers or text), one per component");
  std::array<std::string, 3> out{"0", "0", "0"};
  for (int c = 0; c < dim; ++c)
  {
    const Value e = v.element(std::size_t(c));
    if (!e.node.IsScalar())
      e.fail("found " + e.found() + ", expected a formula in x, y, z or a number");
    out[c] = e.string();
    const std::string error = check_expression(out[c]);
    if (!error.empty())
      e.fail("cannot parse the formula \"" + out[c] + "\": " + error);
  }
  return out;
}

/// velocity of a prescribed wall: one formula (or number) per component in x, y, z.
std::array<std::string, 3> read_profile(const Section& s, int dim)
{
  if (!s.has("velocity"))
    s.fail("velocity", "missing; a prescribed wall needs its velocity profile (a list of "
                           + std::to_string(dim) + " formulas in x, y, z, e.g. [\"4*y*(1-y)\", 0])");
  return read_formulas(s, "velocity", dim);
}

WallSpec read_wall(const Section& walls, const std::string& side, int dim)
{
  WallSpec w;
  const Value v = walls.value(side);
  if (v.node.IsScalar())
  {
    w.type = walls.choice<WallType>(side, w.type, wall_types);
    if (w.type == WallType::moving)
      v.fail("a moving wall needs its velocity: write " + side
             + ": {type: moving, velocity: [..]}");
    if (w.type == WallType::prescribed)
      v.fail("a prescribed wall needs its velocity profile: write " + side
             + ": {type: prescribed, velocity: [formula, ...]}");
    return w;
  }
  const Section s = walls.section(side);
  s.allow_only({"type", "velocity"});
  if (!s.has("type"))
    s.fail("type", "missing; choose one of no_slip, free_slip, moving, open, prescribed");
  w.type = s.choice<WallType>("type", w.type, wall_types);
  if (w.type == WallType::moving)
  {
    if (!s.has("velocity"))
      s.fail("velocity", "missing; a moving wall needs its velocity (a list of "
                             + std::to_string(dim) + " numbers)");
    const auto u = s.numbers("velocity", {std::size_t(dim)}, any());
    std::copy(u.begin(), u.end(), w.velocity.begin());
  }
  else if (w.type == WallType::prescribed)
    w.profile = read_profile(s, dim);
  else if (s.has("velocity"))
    s.fail("velocity", "only a moving wall has a velocity (type is " + std::string(to_string(w.type))
                           + ")");
  return w;
}

/// flow.inextensibility (3.67)-(3.72); `enabled: false` keeps the section but switches it
/// off (e.g. --set flow.inextensibility.enabled=false to compare).
/// flow.walls of a mesh-file domain: one key per facet tag. free_slip fixes one velocity
/// component, so its facets must all be perpendicular to one axis; a moving wall's
/// velocity must lie in the wall.
void read_tag_walls(const Section& walls, const MeshDomain& mesh, Flow& flow)
{
  const auto names = mesh.tag_names();
  if (names.empty() && !walls.keys().empty())
    walls.fail(walls.keys()[0], "the mesh file " + mesh.path()
                                    + " has no facet tags; its whole boundary is no_slip");
  for (const std::string& key : walls.keys())
    if (!std::count(names.begin(), names.end(), key))
      walls.fail(key, "unknown boundary tag; the tags of " + mesh.path() + " are "
                          + join(names) + " (walls of a mesh domain are named by tag)");
  for (const std::string& name : names)
  {
    if (!walls.has(name))
      continue;
    WallSpec w = read_wall(walls, name, 2);
    const int tag = mesh.tag(name);
    if (w.type == WallType::free_slip && mesh.normal_axis({tag}) < 0)
      walls.fail(name, "free_slip fixes the velocity component normal to the wall, so every "
                       "facet of tag " + name + " must be perpendicular to the x or the y "
                       "axis (one of them for the whole tag); use no_slip here");
    if (w.type == WallType::moving && mesh.normal_axis({tag}) < 0)
      for (const auto& e : mesh.boundary())
        if (std::count(e.tags.begin(), e.tags.end(), tag)
            && std::abs(e.n[0] * w.velocity[0] + e.n[1] * w.velocity[1])
                   > 1e-9 * std::hypot(w.velocity[0], w.velocity[1]))
          walls.fail(name, "the velocity of a moving wall must lie in the wall, but tag "
                               + name + " has a facet with normal (" + fmt(e.n[0]) + ", "
                               + fmt(e.n[1]) + ")");
    flow.tag_walls[name] = w;
  }
}

std::optional<Inextensibility> read_inextensibility(const Section& f, Model m)
{
  if (!f.has("inextensibility"))
    return std::nullopt;
  const Section s = f.section("inextensibility");
  s.allow_only({"enabled", "xi", "global_area", "concentration"});
  if (!s.boolean("enabled", true))
    return std::nullopt;
  if (!is_helfrich(m))
    f.fail("inextensibility", std::string("phase_field.model ") + to_string(m)
                                  + " has no membrane; the inextensibility constraint (3.67) "
                                    "needs a Helfrich model");
  Inextensibility in;
  in.xi = s.number("xi", in.xi, positive());
  in.global_area = s.boolean("global_area", in.global_area);
  if (s.has("concentration"))
  {
    const Section c = s.section("concentration");
    c.allow_only({"penalty", "diffusion"});
    Inextensibility::Concentration conc;
    conc.penalty = c.number("penalty", conc.penalty, non_negative());
    conc.diffusion = c.number("diffusion", conc.diffusion, non_negative());
    in.concentration = conc;
  }
  return in;
}
} // namespace

namespace
{
/// cells[i].viscosity enters eta(phi_1, ..., phi_N) of (7.12): a flow and several phase
/// fields are needed.
void check_cell_viscosities(const Section& top, const Scene& s)
{
  for (std::size_t i = 0; i < s.cells.size(); ++i)
    if (s.cells[i].viscosity)
    {
      const std::string key = cell_label(i, s.cells[i]) + ".viscosity";
      if (!s.flow)
        top.fail("cells", key + " is given, but the scene has no flow section");
      if (cell_groups(s).size() < 2)
        top.fail("cells", key + " is given with one phase field; use flow.viscosity.inside");
    }
}
} // namespace

void read_flow(const Section& top, Scene& s)
{
  if (!top.has("flow"))
  {
    check_cell_viscosities(top, s);
    return;
  }
  const Section f = top.section("flow");
  f.allow_only({"equations", "density", "viscosity", "gravity", "force", "cell_force",
                "surface_tension", "walls", "petsc", "solver", "inextensibility",
                "coupling_stabilisation"});
  const Model m = s.phase_field.model;
  if (!couples_to_flow(m))
    top.fail("flow", std::string("phase_field.model ") + to_string(m)
                         + " cannot be coupled to the flow; use cahn_hilliard (surface "
                           "tension, 2.8) or a Helfrich model (3.59)-(3.64), (3.81)-(3.85)");
  const int dim = s.domain.dim;
  Flow flow;
  flow.equations = f.choice<FlowEquations>(
      "equations", flow.equations,
      {{"stokes", FlowEquations::stokes}, {"navier_stokes", FlowEquations::navier_stokes}});
  flow.density = read_pair(f, "density");
  flow.viscosity = read_pair(f, "viscosity");
  flow.gravity = read_vector(f, "gravity", dim);
  flow.force = read_vector(f, "force", dim);
  if (f.has("cell_force")) // F(x) (1 + phi_cells)/2, the force on the cells of section 7.3
    flow.cell_force = read_formulas(f, "cell_force", dim);
  if (f.has("surface_tension"))
  {
    if (is_helfrich(m))
      f.fail("surface_tension", std::string("model ") + to_string(m)
                                    + " takes its interface force from its energy "
                                      "(3.62)/(3.84); surface tension is only for cahn_hilliard");
    flow.surface_tension = f.number("surface_tension", non_negative());
  }
  const Section walls = f.section("walls");
  if (s.domain.mesh)
    read_tag_walls(walls, *s.domain.mesh, flow);
  std::vector<std::string> sides(side_names.begin(), side_names.begin() + 2 * dim);
  if (!s.domain.mesh)
    walls.allow_only(sides);
  for (int i = 0; i < 2 * dim && !s.domain.mesh; ++i)
  {
    // A periodic axis has no sides: the flow leaves through one face and enters through
    // the other, so its sides get no condition (and a wall there is a contradiction).
    if (s.domain.is_periodic(i / 2))
    {
      if (walls.has(sides[i]))
        walls.fail(sides[i], std::string("domain.periodic has axis ") + "xyz"[i / 2]
                                 + ", so the " + sides[i]
                                 + " side is not a boundary; remove this wall or the axis");
      flow.walls[i].type = WallType::open;
      continue;
    }
    if (walls.has(sides[i]))
      flow.walls[i] = read_wall(walls, sides[i], dim);
  }
  if (f.has("coupling_stabilisation"))
  {
    // A term of forms/helfrich_hm1.py and forms/helfrich_l2.py (Taylor linearisation: the
    // stabilised scheme's matrix is constant, and the term would make it change every step).
    const bool l2 = m == Model::helfrich_lagrange || m == Model::helfrich_penalty;
    if (m != Model::helfrich_hm1 && !l2)
      f.fail("coupling_stabilisation", std::string("model ") + to_string(m)
                                           + " has no coupling stabilisation; it is a term of "
                                             "helfrich_hm1, helfrich_lagrange and helfrich_penalty");
    if (l2 && s.numerics.linearisation != Linearisation::taylor)
      f.fail("coupling_stabilisation",
             std::string("model ") + to_string(m)
                 + " takes it with numerics.linearisation: taylor only (the stabilised "
                   "linearisation keeps the matrix constant, which this term would break)");
    flow.coupling_stabilisation = f.number("coupling_stabilisation", non_negative());
  }
  read_petsc_options(f.section("petsc"), flow.petsc);
  if (f.has("solver"))
    flow.solver = read_solver(f, Numerics::Solver::direct);
  flow.inextensibility = read_inextensibility(f, m);
  s.flow = flow;
  check_cell_viscosities(top, s);
}

} // namespace cellphase::scene
