#include "scene/Plan.h"
#include "scene/Sections.h"

namespace cellphase::scene
{
using namespace yaml;

void read_interaction(const Section& top, Scene& s)
{
  if (!top.has("interaction"))
    return;
  const Section in = top.section("interaction");
  in.allow_only({"potential", "In", "r1", "r2", "a1", "a2", "a3", "refresh"});
  if (s.phase_field.model != Model::helfrich_hm1)
    in.fail(std::string("is built for the H^-1 Helfrich flow of chapter 7 (phase_field.model: "
                        "helfrich_hm1); model ")
            + to_string(s.phase_field.model) + " has no interaction term");
  if (cell_groups(s).size() < 2)
    in.fail("acts between the phase fields of different cells, but the scene has one phase "
            "field (give each cell its own, or leave out `group`)");
  if (!in.has("In"))
    in.fail("In", "missing; the interaction number In of (7.5), e.g. In: 0.01 (smaller is "
                  "stronger)");
  Interaction i;
  i.In = in.number("In", positive());
  enum class Potential { repulsive, lennard_jones };
  const Potential p = in.choice<Potential>("potential", Potential::repulsive,
                                           {{"repulsive", Potential::repulsive},
                                            {"lennard_jones", Potential::lennard_jones}});
  if (p == Potential::repulsive)
  {
    // The Gaussian w of (7.2); r1 and r2 may scale it (Fig. 7.7a), no adhesion.
    for (const char* key : {"a1", "a2", "a3"})
      if (in.has(key))
        in.fail(key, "is a parameter of potential: lennard_jones (the adhesive part of Fig. 7.7)");
    i.r1 = in.number("r1", 1.0, positive());
    i.r2 = in.number("r2", 1.0, positive());
  }
  else
  {
    for (const char* key : {"r1", "r2", "a1", "a2", "a3"})
      if (!in.has(key))
        in.fail(key, "missing; potential lennard_jones needs r1, r2, a1, a2, a3 (Fig. 7.7: "
                     "r1: 2, r2: 1, a1: 1, a2: 0, a3: 20)");
    i.r1 = in.number("r1", non_negative());
    i.r2 = in.number("r2", positive());
    i.a1 = in.number("a1", non_negative());
    i.a2 = in.number("a2", any());
    i.a3 = in.number("a3", positive());
  }
  i.refresh = in.boolean("refresh", false);
  s.interaction = i;
}
} // namespace cellphase::scene
