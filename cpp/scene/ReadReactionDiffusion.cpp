// reaction_diffusion: the species of a bulk-surface model (forms/gtpase.py), their
// diffusion and initial values, the kinetics (Table 5.1 by default), the frozen start of
// the pre-polarisation and the chemotactic signal (5.21).
#include "scene/Formula.h"
#include "scene/MeshDomain.h"
#include "scene/Plan.h"
#include "scene/Sections.h"
#include "reaction_models.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cellphase::scene
{
using namespace yaml;

namespace
{
/// The models of the form files (python/reaction_models.py), by name.
const generated::ReactionModel* find_model(const std::string& name)
{
  for (std::size_t i = 0; i < generated::reaction_model_count; ++i)
    if (name == generated::reaction_models[i].name)
      return &generated::reaction_models[i];
  return nullptr;
}

SpeciesInitial read_initial(const Section& sp, const std::string& name)
{
  SpeciesInitial init;
  if (!sp.has("initial"))
    return init;
  const Value v = sp.value("initial");
  if (v.node.IsScalar())
  {
    init.value = v.number(any());
    return init;
  }
  const Section in = sp.section("initial");
  in.allow_only({"value", "where", "otherwise", "random"});
  if (in.has("random"))
  {
    for (const char* key : {"value", "where", "otherwise"})
      if (in.has(key))
        in.fail(key, "cannot be combined with random (uniform values in [low, high])");
    const auto r = in.numbers("random", {2}, any());
    if (!(r[0] <= r[1]))
      in.fail("random", "must be [low, high] with low <= high, found [" + fmt(r[0]) + ", "
                            + fmt(r[1]) + "]");
    init.random = std::array<double, 2>{r[0], r[1]};
    return init;
  }
  if (!in.has("value"))
    in.fail("value", "missing; the initial value of " + name + " (or random: [low, high])");
  init.value = in.number("value", any());
  init.where = in.string("where", "");
  init.otherwise = in.number("otherwise", 0.0, any());
  if (!init.where.empty())
  {
    try
    {
      VectorFormula({init.where, "0", "0"}, 1)(0, 0, 0);
    }
    catch (const std::exception& e)
    {
      in.fail("where", std::string("is not a condition in x, y, z: ") + e.what());
    }
  }
  return init;
}

Chemotaxis read_chemotaxis(const Section& top, const Scene& s)
{
  const Section c = top.section("chemotaxis");
  c.allow_only({"mode", "xi", "omega", "theta", "direction", "x0"});
  using Mode = Chemotaxis::Mode;
  if (!c.has("mode"))
    c.fail("mode", "missing; one of rotating, sinusoidal, random_turns, point_source "
                   "(section 5.4.3, modes 1-4)");
  Chemotaxis ch;
  ch.mode = c.choice<Mode>("mode", Mode::rotating,
                           {{"rotating", Mode::rotating},
                            {"sinusoidal", Mode::sinusoidal},
                            {"random_turns", Mode::random_turns},
                            {"point_source", Mode::point_source}});
  ch.xi = c.number("xi", ch.xi, non_negative());
  auto need = [&](const char* key, const char* what)
  {
    if (!c.has(key))
      c.fail(key, std::string("missing; mode ") + c.value("mode").string() + " needs " + what);
  };
  auto refuse = [&](const char* key)
  {
    if (c.has(key))
      c.fail(key, "is not a parameter of mode " + c.value("mode").string());
  };
  switch (ch.mode)
  {
  case Mode::rotating:
  case Mode::sinusoidal:
    need("omega", "omega, the angular velocity of the signal's direction (dimensionless)");
    ch.omega = c.number("omega", any());
    refuse("theta"), refuse("x0"), refuse("direction");
    break;
  case Mode::random_turns:
    need("omega", "omega, the angle (degrees) of each random turn");
    need("theta", "theta, the number of steps between two turns");
    ch.omega = c.number("omega", closed(0, 180)) * M_PI / 180;
    ch.theta = c.integer("theta", 1, closed(1, 1e9));
    ch.direction_deg = c.number("direction", 0.0, any());
    refuse("x0");
    break;
  case Mode::point_source:
  {
    need("x0", "x0, the source point outside the domain");
    const auto x0 = c.numbers("x0", {std::size_t(s.domain.dim)}, any());
    std::copy(x0.begin(), x0.end(), ch.x0.begin());
    bool inside = true;
    if (s.domain.mesh)
      inside = s.domain.mesh->contains(ch.x0.data());
    else
      for (int a = 0; a < s.domain.dim; ++a)
        inside = inside && ch.x0[a] > s.domain.lower[a] && ch.x0[a] < s.domain.upper[a];
    if (inside)
      c.fail("x0", "lies inside the domain; the source of mode 4 is outside it, where "
                   "grad c~ = -xi (x - x0)/|x - x0| has no singularity");
    refuse("omega"), refuse("theta"), refuse("direction");
    break;
  }
  }
  return ch;
}
} // namespace

void read_reaction_diffusion(const Section& top, Scene& s)
{
  if (s.numbers.Fa && !(s.flow && top.has("reaction_diffusion")))
  {
    // Fa scales the protrusion force of the species on the flow: without both it would
    // be silently unused.
    const std::string why = std::string("sets the protrusion force -(1/Fa) c1 grad phi (5.7) of "
                                        "reaction_diffusion on the flow; this scene has no ")
                            + (s.flow ? "reaction_diffusion section" : "flow");
    if (top.has("units"))
      top.section("units").fail("protrusion_coefficient", why);
    top.section("numbers").fail("Fa", why);
  }
  if (!top.has("reaction_diffusion"))
    return;
  const Section rd = top.section("reaction_diffusion");
  rd.allow_only({"model", "species", "kinetics", "regularisation", "seed", "frozen_until",
                 "chemotaxis", "petsc", "solver"});
  ReactionDiffusion r;
  std::vector<std::string> models;
  for (std::size_t i = 0; i < generated::reaction_model_count; ++i)
    models.push_back(generated::reaction_models[i].name);
  r.model = rd.string("model", models.front());
  const generated::ReactionModel* model = find_model(r.model);
  if (!model)
    rd.fail("model", "\"" + r.model + "\" is not a reaction-diffusion model; the form files "
                     "declare " + join(models) + " (forms/<model>.py)");
  if (cell_groups(s).size() != 1)
    rd.fail("acts on the phase field of one cell; the scene has "
            + std::to_string(cell_groups(s).size()) + " phase fields");
  if (own_meshes(s))
    rd.fail("is solved on the shared mesh; numerics.mesh.cell_meshes: own is not available "
            "with it");

  const Section species = rd.section("species");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < model->species_count; ++i)
    names.push_back(model->species[i].name);
  for (const auto& key : species.keys())
    if (std::find(names.begin(), names.end(), key) == names.end())
      species.fail(key, "is not a species of model " + r.model + " (forms/" + r.model
                            + ".py); its species are " + join(names));
  for (std::size_t i = 0; i < model->species_count; ++i)
  {
    const generated::ReactionSpecies& d = model->species[i];
    const Section sp = species.section(d.name);
    sp.allow_only({"region", "diffusion", "initial"});
    Species x;
    x.name = d.name;
    x.membrane = d.membrane;
    const std::string region = d.membrane ? "membrane" : "bulk";
    if (sp.has("region"))
    {
      const std::string given = sp.value("region").string();
      if (given != "membrane" && given != "bulk")
        sp.fail("region", "\"" + given + "\" is not a region; a species lives on the "
                          "membrane or in the bulk");
      if (given != region)
        sp.fail("region", std::string(d.name) + " lives in the " + region + " in forms/"
                              + r.model + ".py (weight "
                              + (d.membrane ? "|grad phi~|" : "phi~")
                              + "); another region is an edit of its `species`");
    }
    x.diffusion = sp.number("diffusion", d.diffusion, non_negative());
    x.initial = read_initial(sp, d.name);
    r.species.push_back(x);
  }
  r.protrusion = model->protrusion;

  const Section k = rd.section("kinetics");
  std::vector<std::string> kin;
  for (std::size_t i = 0; i < model->kinetics_count; ++i)
    kin.push_back(model->kinetics[i].name);
  k.allow_only(kin);
  for (std::size_t i = 0; i < model->kinetics_count; ++i)
    r.kinetics[model->kinetics[i].name] = k.number(model->kinetics[i].name,
                                                   model->kinetics[i].value, non_negative());
  for (const char* b : {"b1", "b2"}) // gtpase: the saturation c1/(b + c1) of (5.5)
    if (r.kinetics.count(b) && r.kinetics[b] <= 0)
      k.fail(b, "must be > 0 (the saturation c1/(b + c1) of (5.5) divides by it)");

  r.regularisation = rd.number("regularisation", r.regularisation, open(0, 1));
  r.seed = std::uint64_t(rd.integer("seed", 1, closed(0, 2147483647)));
  r.frozen_until = rd.number("frozen_until", 0.0, non_negative());
  if (rd.has("chemotaxis"))
    r.chemotaxis = read_chemotaxis(rd, s);
  if (rd.has("petsc"))
  {
    std::map<std::string, std::string> own;
    read_petsc_options(rd.section("petsc"), own);
    r.petsc = own;
  }
  if (rd.has("solver"))
    r.solver = read_solver(rd, Numerics::Solver::direct);
  s.reaction_diffusion = r;
}
} // namespace cellphase::scene
