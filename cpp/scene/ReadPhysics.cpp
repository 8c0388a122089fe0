// phase_field, and the dimensionless numbers given directly or through physical units.
#include "scene/Sections.h"
#include "scene/Units.h"

namespace cellphase::scene
{
using namespace yaml;

void read_phase_field(const Section& top, Scene& s)
{
  if (!top.has("phase_field"))
    top.fail("phase_field", "missing; every scene needs phase_field.model");
  const Section p = top.section("phase_field");
  p.allow_only({"model", "mobility", "spontaneous_curvature", "penalty_volume", "penalty_area",
                "constraint_relaxation", "surface_tension", "mobility_law"});
  if (!p.has("model"))
    p.fail("model", "missing; choose one of allen_cahn, allen_cahn_volume, cahn_hilliard, "
                    "helfrich_lagrange, helfrich_penalty, helfrich_hm1");
  PhaseField& f = s.phase_field;
  f.model = p.choice<Model>("model", f.model,
                            {{"allen_cahn", Model::allen_cahn},
                             {"allen_cahn_volume", Model::allen_cahn_volume},
                             {"cahn_hilliard", Model::cahn_hilliard},
                             {"helfrich_lagrange", Model::helfrich_lagrange},
                             {"helfrich_penalty", Model::helfrich_penalty},
                             {"helfrich_hm1", Model::helfrich_hm1}});
  f.mobility = p.number("mobility", f.mobility, positive());
  f.spontaneous_curvature = p.number("spontaneous_curvature", f.spontaneous_curvature, any());
  f.penalty_volume = p.number("penalty_volume", f.penalty_volume, non_negative());
  f.penalty_area = p.number("penalty_area", f.penalty_area, non_negative());
  f.constraint_relaxation = p.number("constraint_relaxation", f.constraint_relaxation,
                                     closed(0, 1));
  f.surface_tension = p.boolean("surface_tension", f.surface_tension);
  enum class Law { constant, degenerate };
  const Law law = p.choice<Law>("mobility_law", Law::constant,
                                {{"constant", Law::constant}, {"degenerate", Law::degenerate}});
  f.degenerate_mobility = law == Law::degenerate;
  if (f.degenerate_mobility && f.model != Model::cahn_hilliard)
    p.fail("mobility_law", std::string("degenerate (gamma W(phi), section 2.8) is for "
                                       "cahn_hilliard; model ")
                               + to_string(f.model) + " has a constant mobility");
  if (f.surface_tension && !is_helfrich(f.model))
    p.fail("surface_tension", std::string("adds (1/Ca) E_CH to the Helfrich energy (3.78); model ")
                                  + to_string(f.model) + " has E_CH as its energy already (the "
                                  "flow's capillary force takes flow.surface_tension or 1/Ca)");
}

void read_numbers(const Section& top, Scene& s)
{
  if (top.has("numbers") && top.has("units"))
    top.fail("units", "give either numbers (Re, Ca, Be directly) or units (from which they "
                      "are derived), not both");

  const Section n = top.section("numbers");
  n.allow_only({"Re", "Ca", "Be", "Fa", "Pa"});
  s.numbers.Re = n.number("Re", s.numbers.Re, non_negative());
  s.numbers.Ca = n.number("Ca", s.numbers.Ca, positive());
  s.numbers.Be = n.number("Be", s.numbers.Be, positive());
  s.numbers.Fa = n.optional_number("Fa", positive());
  s.numbers.Pa = n.number("Pa", s.numbers.Pa, positive());

  const Section u = top.section("units");
  u.allow_only({"length", "velocity", "density", "viscosity", "bending_rigidity",
                "surface_tension", "protrusion_coefficient", "frank_constant",
                "activity_parameter", "rotational_viscosity"});
  PhysicalUnits& pu = s.units;
  pu.length = u.optional_number("length", positive());
  pu.velocity = u.optional_number("velocity", positive());
  pu.density = u.optional_number("density", positive());
  pu.viscosity = u.optional_number("viscosity", positive());
  pu.bending_rigidity = u.optional_number("bending_rigidity", positive());
  pu.surface_tension = u.optional_number("surface_tension", positive());
  pu.protrusion_coefficient = u.optional_number("protrusion_coefficient", positive());
  pu.frank_constant = u.optional_number("frank_constant", positive());
  pu.activity_parameter = u.optional_number("activity_parameter", any());
  pu.rotational_viscosity = u.optional_number("rotational_viscosity", positive());
  if (top.has("units"))
    s.numbers = derive_numbers(pu);
}

} // namespace cellphase::scene
