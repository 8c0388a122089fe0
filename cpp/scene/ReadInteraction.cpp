#include "scene/Plan.h"
#include "scene/Sections.h"
#include <algorithm>

namespace cellphase::scene
{
using namespace yaml;

namespace
{
/// `potential` and its parameters r1, r2, a1, a2, a3, at the scene level or of one pair.
InteractionPotential read_potential(const Section& in)
{
  enum class Kind { repulsive, lennard_jones };
  const Kind kind = in.choice<Kind>("potential", Kind::repulsive,
                                    {{"repulsive", Kind::repulsive},
                                     {"lennard_jones", Kind::lennard_jones}});
  InteractionPotential p;
  if (kind == Kind::repulsive)
  {
    // The Gaussian w of (7.2); r1 and r2 may scale it (Fig. 7.7a), no adhesion.
    for (const char* key : {"a1", "a2", "a3"})
      if (in.has(key))
        in.fail(key, "is a parameter of potential: lennard_jones (the adhesive part of Fig. 7.7)");
    p.r1 = in.number("r1", 1.0, positive());
    p.r2 = in.number("r2", 1.0, positive());
    return p;
  }
  for (const char* key : {"r1", "r2", "a1", "a2", "a3"})
    if (!in.has(key))
      in.fail(key, "missing; potential lennard_jones needs r1, r2, a1, a2, a3 (Fig. 7.7: "
                   "r1: 2, r2: 1, a1: 1, a2: 0, a3: 20)");
  p.r1 = in.number("r1", non_negative());
  p.r2 = in.number("r2", positive());
  p.a1 = in.number("a1", non_negative());
  p.a2 = in.number("a2", any());
  p.a3 = in.number("a3", positive());
  return p;
}

/// The phase field (group) a name in interaction.pairs stands for: a group's name, or the
/// name of a cell, which stands for its group.
std::string pair_member(const Section& pair, const std::string& name, const Scene& s)
{
  std::vector<std::string> names;
  for (const auto& cell : s.cells)
  {
    if (cell.name == name || cell.group == name)
      return cell.group;
    names.push_back(cell.name);
  }
  pair.fail("cells", "names \"" + name + "\", which is no cell or group of the scene (cells: "
                         + join(names) + ")");
}

/// interaction.pairs: In and, optionally, a potential of their own for some pairs.
std::vector<InteractionPair> read_pairs(const Section& in, const Interaction& scene_wide,
                                        const Scene& s)
{
  std::vector<InteractionPair> pairs;
  if (!in.has("pairs"))
    return pairs;
  for (const Section& entry : in.list_of_sections("pairs"))
  {
    entry.allow_only({"cells", "In", "potential", "r1", "r2", "a1", "a2", "a3"});
    if (!entry.has("cells"))
      entry.fail("cells", "missing; name the pair's two cells, e.g. cells: [wbc, rbc1]");
    const auto names = entry.strings("cells");
    if (names.size() != 2)
      entry.fail("cells", "lists " + std::to_string(names.size())
                              + " names; a pair is two cells, e.g. cells: [wbc, rbc1]");
    InteractionPair pair;
    pair.first = pair_member(entry, names[0], s);
    pair.second = pair_member(entry, names[1], s);
    if (pair.first == pair.second)
      entry.fail("cells", "names one phase field twice (\"" + pair.first
                              + "\"); a pair interacts between two cells' phase fields");
    for (const auto& other : pairs)
      if ((other.first == pair.first && other.second == pair.second)
          || (other.first == pair.second && other.second == pair.first))
        entry.fail("cells", "repeats the pair " + pair.first + ", " + pair.second
                                + " listed before; give each pair once");
    pair.In = entry.number("In", scene_wide.In, positive());
    // A pair that names any part of a potential gives all of it, as the scene level does.
    const std::vector<std::string> potential_keys{"potential", "r1", "r2", "a1", "a2", "a3"};
    const bool own = std::any_of(potential_keys.begin(), potential_keys.end(),
                                 [&](const std::string& key) { return entry.has(key); });
    pair.potential = own ? read_potential(entry) : scene_wide.potential;
    pairs.push_back(pair);
  }
  return pairs;
}
} // namespace

void read_interaction(const Section& top, Scene& s)
{
  if (!top.has("interaction"))
    return;
  const Section in = top.section("interaction");
  in.allow_only({"potential", "In", "r1", "r2", "a1", "a2", "a3", "refresh", "pairs",
                 "derivative_reach", "flow_force"});
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
  i.potential = read_potential(in);
  i.pairs = read_pairs(in, i, s);
  i.refresh = in.boolean("refresh", false);
  i.flow_force = in.boolean("flow_force", true);
  if (i.refresh && !i.flow_force)
    in.fail("refresh", "makes the interaction part of the flow's force again after the step, "
                       "but flow_force: false leaves that part out; give one of the two");
  if (in.has("derivative_reach"))
    i.derivative_reach = in.number("derivative_reach", positive());
  s.interaction = i;
}
} // namespace cellphase::scene
