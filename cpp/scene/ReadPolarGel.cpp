// polar_gel: the orientation field of an active polar gel in the cell (chapter 6): the
// active stress 1/Fa (6.11), flow alignment xi and rotational viscosity ratio kappa of
// (6.16), the Frank energy's c1 and beta (6.4), and the perturbed initial orientation of
// section 6.2.5. Defaults: Table 6.1.
#include "scene/Plan.h"
#include "scene/Sections.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{
using namespace yaml;

void read_polar_gel(const Section& top, Scene& s)
{
  const bool units_polar = s.units.frank_constant || s.units.activity_parameter
                           || s.units.rotational_viscosity;
  if (!top.has("polar_gel"))
  {
    if (units_polar)
      top.section("units").fail(s.units.frank_constant       ? "frank_constant"
                                : s.units.activity_parameter ? "activity_parameter"
                                                             : "rotational_viscosity",
                                "is a parameter of the orientation field; this scene has no "
                                "polar_gel section");
    return;
  }
  const Section p = top.section("polar_gel");
  p.allow_only({"activity", "xi", "kappa", "c1", "beta", "stabilisation", "initial", "solver"});
  if (s.phase_field.model != Model::helfrich_hm1)
    top.section("phase_field").fail("model", std::string("is ") + to_string(s.phase_field.model)
                                                 + "; polar_gel needs helfrich_hm1 (the H^-1 "
                                                   "flow (6.14)-(6.15) whose phi# takes the "
                                                   "orientation field's terms)");
  if (s.domain.dim != 2)
    p.fail("is solved in 2D (thesis chapter 6); the domain is " + std::to_string(s.domain.dim) + "D");
  if (cell_groups(s).size() != 1)
    p.fail("fills one cell's phase field; the scene has " + std::to_string(cell_groups(s).size())
           + " phase fields");
  if (s.reaction_diffusion)
    p.fail("cannot be combined with reaction_diffusion in one scene");

  PolarGel g;
  // With units, the numbers of Table 6.1 come from eta, V, L and k, zeta, eta_rot.
  auto from_units = [&](const char* key, const std::optional<double>& unit)
  {
    if (p.has(key) && unit)
      p.fail(key, std::string("is given twice: here and through units (")
                      + (std::string(key) == "activity" ? "activity_parameter" : "rotational_viscosity")
                      + ")");
  };
  from_units("activity", s.units.activity_parameter);
  from_units("kappa", s.units.rotational_viscosity);
  const PhysicalUnits& u = s.units;
  const bool flow_units = u.viscosity && u.velocity && u.length;
  if ((u.activity_parameter || u.rotational_viscosity) && !flow_units)
    top.section("units").fail(u.activity_parameter ? "activity_parameter" : "rotational_viscosity",
                              "needs units.viscosity, velocity and length as well (1/Fa = zeta L "
                              "/ (eta V), kappa = eta_rot / eta)");
  if (u.activity_parameter)
    g.activity = *u.activity_parameter * *u.length / (*u.viscosity * *u.velocity); // 1/Fa (6.11)
  if (u.rotational_viscosity)
    g.kappa = *u.rotational_viscosity / *u.viscosity;

  g.activity = p.number("activity", g.activity, any());
  g.xi = p.number("xi", g.xi, any());
  g.kappa = p.number("kappa", g.kappa, positive());
  g.c1 = p.number("c1", g.c1, non_negative());
  g.beta = p.number("beta", g.beta, any());
  if (p.has("solver"))
    g.solver = read_solver(p, Numerics::Solver::direct);
  // Twice the feedback (1 + xi)^2 |P|^2 / (4 eta) of the explicit alignment stress on P
  // (|P| ~ 1 in the cell), which the stabilisation must exceed (forms/polar_gel.py).
  const double eta_min = s.flow ? std::min(s.flow->viscosity[0], s.flow->viscosity[1]) : 0;
  g.stabilisation = p.number("stabilisation",
                             s.flow ? (1 + std::abs(g.xi)) * (1 + std::abs(g.xi)) / (2 * eta_min) : 0.0,
                             non_negative());
  if (g.activity != 0 && !s.flow)
    p.fail("activity", "is 1/Fa of the active stress (6.11), which acts through the flow; add "
                       "a flow section or set activity: 0");

  const Section in = p.section("initial");
  in.allow_only({"direction", "noise", "noise_length", "inside_only", "splay", "mirror",
                 "seed"});
  if (in.has("direction"))
  {
    const auto d = in.numbers("direction", {2}, any());
    g.direction = {d[0], d[1], 0};
  }
  g.noise = in.number("noise", g.noise, non_negative());
  g.noise_length = in.number("noise_length", g.noise_length, non_negative());
  g.inside_only = in.boolean("inside_only", g.inside_only);
  if (own_meshes(s) && !g.inside_only)
    in.fail("inside_only", "is false; with numerics.mesh.cell_meshes: own, P lives on the cell's "
                           "own mesh and is 0 beyond it, so P^0 must be 0 outside the cell too: "
                           "set inside_only: true");
  g.splay = in.number("splay", g.splay, any());
  g.mirror = in.boolean("mirror", g.mirror);
  g.seed = std::uint64_t(in.integer("seed", int(g.seed), closed(0, 2147483647)));
  s.polar_gel = g;
}
} // namespace cellphase::scene
