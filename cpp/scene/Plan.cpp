#include "scene/Plan.h"
#include "scene/InteractionPairs.h"
#include "scene/YamlRead.h"
#include <algorithm>
#include <cstdio>
#include <map>

namespace cellphase::scene
{
namespace
{
bool advected(Model m) { return m != Model::allen_cahn && m != Model::allen_cahn_volume; }

/// phi_cells (7.14) for the inextensibility, and with several cells for the flow's eta, rho.
bool has_membrane_union(const Scene& s);

bool has_concentration(const Scene& s)
{
  return s.flow && s.flow->inextensibility && s.flow->inextensibility->concentration.has_value();
}

std::vector<std::string> qualified(const std::string& group, const std::vector<std::string>& f)
{
  std::vector<std::string> out;
  for (const auto& name : f)
    out.push_back(group + "." + name);
  return out;
}

/// Every step the scene could have, by name.
std::map<std::string, PlanStep> available_steps(const Scene& s)
{
  std::map<std::string, PlanStep> steps;
  const Model m = s.phase_field.model;
  const auto groups = cell_groups(s);
  PlanStep interaction{"interaction", "interaction between cells (7.5), (7.11)", {}, {}};
  if (s.interaction && s.interaction->refresh)
    interaction.description += "; sums and w made again from phi^{n+1} after the step (refresh)";
  if (s.interaction && !s.interaction->flow_force)
    interaction.description += "; not in the flow's force (flow_force: false, a gradient the "
                               "pressure absorbs): in the phase fields' mobility term";
  if (s.interaction && s.interaction->derivative_reach)
    interaction.description += "; w'_i of (7.11) within " + yaml::fmt(*s.interaction->derivative_reach)
                               + " epsilon of the membrane (derivative_reach)";
  if (s.interaction && !s.interaction->pairs.empty())
    interaction.description += "; " + std::to_string(s.interaction->pairs.size())
                               + " pair(s) with In or potential of their own ("
                               + std::to_string(interaction_potentials(*s.interaction).size())
                               + " potential(s), one source each)";
  for (const auto& g : groups)
  {
    PlanStep pf{g.step, std::string("phase-field module (") + to_string(m) + ")"
                            + (groups.size() > 1 ? " of " + g.name : ""),
                {}, qualified(g.prefix, model_fields(m))};
    if (own_meshes(s))
      for (const auto& f : qualified(g.prefix + ".own", model_fields(m)))
        pf.writes.push_back(f);
    // A two-step scheme's previous state: on the mesh of the state (no shared copy).
    for (const auto& f : history_fields(s))
      pf.writes.push_back(state_field(s, g, f));
    if (s.flow)
    {
      pf.writes.push_back(g.prefix + ".potential"); // dE/dphi, the interface force's potential
      if (advected(m))
        pf.reads.push_back("flow.v");
    }
    if (s.interaction)
    {
      interaction.reads.push_back(state_field(s, g, "phi"));
      for (std::size_t k = 0; k < interaction_potentials(*s.interaction).size(); ++k)
        for (const char* sum : {"w_sum", "B_sum"})
        {
          pf.reads.push_back(interaction_sum_field(g.name, sum, k));
          interaction.writes.push_back(interaction_sum_field(g.name, sum, k));
        }
    }
    steps[pf.name] = pf;
  }
  if (groups.size() > 1)
  {
    if (!s.interaction)
    {
      interaction.description = "overlap of the cells (no interaction potential)";
      for (const auto& g : groups)
        interaction.reads.push_back(state_field(s, g, "phi"));
    }
    steps[interaction.name] = interaction;
  }
  if (has_membrane_union(s))
  {
    PlanStep membrane{"membrane", "membrane union module (phi_cells = max_i phi_i, 7.14)", {},
                      {"membrane.phi_cells"}};
    for (const auto& g : groups)
      membrane.reads.push_back(g.prefix + ".phi");
    steps[membrane.name] = membrane;
  }
  if (s.flow)
  {
    PlanStep flow{"flow",
                  s.flow->inextensibility ? "flow module (with inextensibility, 3.67-3.68)"
                                          : "flow module",
                  {}, {"flow.v", "flow.p"}};
    // With several cells: eta(phi_cells), rho(phi_cells) and the summed force (7.12).
    if (groups.size() > 1)
      flow.reads.push_back("membrane.phi_cells");
    for (const auto& g : groups)
      flow.reads.insert(flow.reads.end(), {g.prefix + ".phi", g.prefix + ".potential"});
    if (s.flow->inextensibility)
    {
      if (groups.size() == 1)
        flow.reads.push_back("membrane.phi_cells");
      flow.writes.push_back("flow.lambda");
    }
    if (has_concentration(s))
      flow.reads.push_back("membrane.c");
    if (has_protrusion(s))
      flow.reads.push_back("rd.force");
    if (s.polar_gel)
      flow.reads.push_back("polar.force");
    for (const auto& f : flow_history_fields(s))
      flow.writes.push_back(f);
    steps[flow.name] = flow;
  }
  if (s.reaction_diffusion)
  {
    PlanStep rd{"reaction_diffusion",
                "reaction-diffusion module (forms/" + s.reaction_diffusion->model + ".py"
                    + (s.reaction_diffusion->model == "gtpase" ? ", 5.16-5.18" : "")
                    + (s.reaction_diffusion->chemotaxis ? ", 5.21" : "") + ")",
                {state_field(s, groups.front(), "phi")}, species_fields(s)};
    if (s.flow)
      rd.reads.push_back("flow.v");
    if (has_protrusion(s))
      rd.writes.push_back("rd.force");
    if (s.numerics.adaptive_dt) // the species at the step before: their time-error estimate
      for (const auto& f : species_fields(s))
        rd.writes.push_back(f + "_prev");
    steps[rd.name] = rd;
    // The shape and the flow wait while the pattern forms (section 5.4.1).
    for (auto& [name, step] : steps)
      if (name != rd.name)
        step.active_from = s.reaction_diffusion->frozen_until;
  }
  if (s.polar_gel)
  {
    // Section 6.3: flow, orientation field (with phi^n, v^{n+1}), phase field (with P^{n+1}).
    // On the mesh of phi (a cell's own mesh: P lives in the cell, section 6.3).
    PlanStep polar{"polar_gel", "orientation field of the active polar gel (forms/polar_gel.py, 6.16-6.17)",
                   {state_field(s, groups.front(), "phi")}, {"polar.P", "polar.P_sharp"}};
    if (s.flow)
    {
      polar.reads.push_back("flow.v");
      polar.writes.push_back("polar.force");
    }
    if (s.numerics.adaptive_dt) // P at the step before: its time-error estimate
      polar.writes.push_back("polar.P_prev");
    if (own_meshes(s)) // P on the cell's own mesh; copies on the shared mesh for the output
      polar.writes.insert(polar.writes.end(), {"polar.shared.P", "polar.shared.P_sharp"});
    steps[polar.name] = polar;
    steps.at(groups.front().step).reads.push_back("polar.P");
  }
  if (has_concentration(s))
    steps["concentration"] = {"concentration", "membrane concentration module (3.70)",
                              {"membrane.phi_cells", "flow.v"}, {"membrane.c"}};
  return steps;
}
bool has_membrane_union(const Scene& s)
{
  return s.flow && (s.flow->inextensibility || cell_groups(s).size() > 1);
}
} // namespace

std::vector<std::string> default_split(const Scene& s)
{
  std::vector<std::string> order;
  const auto steps = available_steps(s);
  for (const char* name : {"interaction", "membrane", "flow", "polar_gel"})
    if (steps.count(name))
      order.push_back(name);
  for (const auto& g : cell_groups(s))
    order.push_back(g.step);
  if (steps.count("reaction_diffusion"))
    order.push_back("reaction_diffusion");
  if (steps.count("concentration"))
    order.push_back("concentration");
  return order;
}

Plan make_plan(const Scene& s)
{
  const auto steps = available_steps(s);
  Plan plan;
  for (const auto& name : s.numerics.split ? *s.numerics.split : default_split(s))
    plan.steps.push_back(steps.at(name));
  for (const auto& g : cell_groups(s))
    plan.initial.push_back(state_field(s, g, "phi"));
  return plan;
}

std::vector<std::string> species_fields(const Scene& s)
{
  std::vector<std::string> out;
  if (s.reaction_diffusion)
    for (const auto& sp : s.reaction_diffusion->species)
      out.push_back("rd." + sp.name);
  return out;
}

bool has_protrusion(const Scene& s)
{
  return s.flow && s.reaction_diffusion && s.numbers.Fa.has_value();
}

bool own_meshes(const Scene& s) { return s.numerics.mesh.cell_meshes == Mesh::CellMeshes::own; }

std::string state_field(const Scene& s, const CellGroup& g, const std::string& field)
{
  return g.prefix + (own_meshes(s) ? ".own." : ".") + field;
}

std::vector<std::string> flow_history_fields(const Scene& s)
{
  if (!s.flow || s.numerics.time_scheme != Numerics::TimeScheme::bdf2 || cell_groups(s).size() != 1)
    return {};
  if (s.numerics.coupling == Numerics::Coupling::lagged)
    return {"flow.v_prev"};
  if (!flow_extrapolates_potential(s))
    return {"flow.v_prev", "flow.phi_prev"};
  return {"flow.v_prev", "flow.phi_prev", "flow.potential_prev"};
}

bool flow_extrapolates_potential(const Scene& s)
{
  const Model m = s.phase_field.model;
  return m != Model::helfrich_lagrange && m != Model::helfrich_penalty;
}

std::vector<CellGroup> cell_groups(const Scene& s)
{
  std::vector<CellGroup> groups;
  for (std::size_t i = 0; i < s.cells.size(); ++i)
  {
    const std::string& name = s.cells[i].group.empty() ? s.cells[i].name : s.cells[i].group;
    auto it = std::find_if(groups.begin(), groups.end(), [&](const CellGroup& g) { return g.name == name; });
    if (it == groups.end())
      it = groups.insert(groups.end(), CellGroup{name, "", "", "", {}});
    it->cells.push_back(i);
  }
  const bool one = groups.size() == 1;
  for (auto& g : groups)
  {
    g.prefix = one ? "cell" : "cell." + g.name;
    g.label_suffix = one ? "" : "_" + g.name;
    g.step = one ? "phase_field" : "phase_field." + g.name;
  }
  return groups;
}

Scene group_scene(const Scene& s, const CellGroup& g)
{
  Scene out = s;
  out.cells.clear();
  for (std::size_t i : g.cells)
    out.cells.push_back(s.cells[i]);
  const Cell& first = out.cells.front();
  if (first.Be)
    out.numbers.Be = *first.Be;
  if (first.spontaneous_curvature)
    out.phase_field.spontaneous_curvature = *first.spontaneous_curvature;
  if (first.mobility)
    out.phase_field.mobility = *first.mobility;
  if (first.penalty_area)
    out.phase_field.penalty_area = *first.penalty_area;
  return out;
}

std::string plan_problem(const Plan& plan)
{
  for (const auto& step : plan.steps)
    for (const auto& field : step.reads)
    {
      const bool initial = std::count(plan.initial.begin(), plan.initial.end(), field) > 0;
      const bool written = std::any_of(plan.steps.begin(), plan.steps.end(), [&](const PlanStep& p)
                                       { return std::count(p.writes.begin(), p.writes.end(), field) > 0; });
      if (!initial && !written)
        return step.name + " reads " + field + ", which no sub-problem of the split writes and "
               + "the scene gives no initial value for";
    }
  return "";
}

std::string plan_text(const Plan& plan)
{
  auto fmt_time = [](double t)
  {
    char b[32];
    std::snprintf(b, sizeof b, "%g", t);
    return std::string(b);
  };
  auto list = [](const std::vector<std::string>& v)
  {
    std::string s;
    for (const auto& x : v)
      s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? std::string("-") : s;
  };
  std::string text;
  int i = 1;
  for (const auto& step : plan.steps)
    text += "  " + std::to_string(i++) + ". " + step.name + ": " + step.description
            + (step.active_from > 0 ? " (from t = " + fmt_time(step.active_from) + ")" : "")
            + "\n       reads " + list(step.reads) + "; writes " + list(step.writes) + "\n";
  text += "  initial data: " + list(plan.initial) + "\n";
  return text;
}
} // namespace cellphase::scene
