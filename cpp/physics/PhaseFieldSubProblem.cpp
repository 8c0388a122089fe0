#include "physics/PhaseFieldSubProblem.h"
#include "physics/SharpInterface.h"
#include "mesh/FieldTransfer.h"
#include "mesh/OwnMesh.h"
#include "physics/FormTable.h"
#include "scene/InteractionPairs.h"
#include "util/Clock.h"
#include <algorithm>
#include <limits>
#include <cmath>
#include <cstdio>

namespace cellphase
{
namespace
{
template <typename... Args>
std::string format(const char* fmt, Args... args)
{
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}
} // namespace

PhaseFieldSubProblem::PhaseFieldSubProblem(scene::PlanStep step, const scene::Scene& scene,
                                           MPI_Comm comm, scene::CellGroup group, int groups)
    : SubProblem(std::move(step)), group_(std::move(group)),
      solver_columns_(groups > 1 ? group_.name + ".phase_field" : "phase_field"), groups_(groups),
      scene_(scene::group_scene(scene, group_)), module_(scene_, comm),
      own_(scene::own_meshes(scene_))
{
}


void PhaseFieldSubProblem::declare(FieldRegistry& fields)
{
  fields_ = &fields;
  for (const auto& f : scene::model_fields(scene_.phase_field.model))
  {
    const double outside = f == "phi" ? -1 : 0; // no cell, no potential
    if (!own_)
    {
      fields.declare({field(f), f + group_.label_suffix, name(), FieldSpace::scalar_p2,
                      f == "phi" ? Transfer::keep_integral : Transfer::interpolate, true});
      continue;
    }
    // The state on this cell's mesh (key: the group's prefix), its copy on the shared mesh.
    fields.declare({state(f), "own_" + f + group_.label_suffix, name(), FieldSpace::scalar_p2,
                    f == "phi" ? Transfer::keep_integral : Transfer::interpolate, true,
                    group_.prefix, outside});
    fields.declare({field(f), f + group_.label_suffix, name(), FieldSpace::scalar_p2,
                    Transfer::recompute, false, "", outside, f == "phi"});
  }
  // numerics.time_scheme: bdf2 keeps phi^{n-1} (and mu^{n-1}) where the state lives;
  // phi_prev keeps its integral at a remesh as phi does, so that BDF2 keeps int phi.
  for (const auto& f : scene::history_fields(scene_))
    fields.declare({state(f), (own_ ? "own_" : "") + f + group_.label_suffix, name(),
                    FieldSpace::scalar_p2,
                    f == "phi_prev" ? Transfer::keep_integral : Transfer::interpolate, true,
                    own_ ? group_.prefix : "", f == "phi_prev" ? -1.0 : 0.0, false, true});
  // dE/dphi for the flow's interface force: mu or w itself, or the projection of (3.84),
  // which is recomputed from phi and mu on every mesh.
  const std::string potential = field("potential");
  if (std::count(writes().begin(), writes().end(), potential))
    fields.declare({potential, "potential" + group_.label_suffix, name(), FieldSpace::scalar_p2,
                    Transfer::recompute, false});
}

void PhaseFieldSubProblem::attach(FieldRegistry& fields)
{
  auto phi = fields.get(state("phi"));
  FieldMap given;
  auto known = scene::model_fields(scene_.phase_field.model);
  for (const auto& f : scene::history_fields(scene_))
    known.push_back(f);
  for (const auto& f : known)
    if (auto u = fields.find(state(f)))
      given[f] = u;
  module_.attach(std::const_pointer_cast<Space>(phi->function_space()), given);
  for (const auto& [f, u] : module_.fields())
    fields.set(state(f), u);
  // The multipliers of a checkpoint are in place (restore() comes before attach): the
  // projection of (3.84) uses them.
  std::shared_ptr<const Function> potential;
  if (fields.declared(field("potential")))
    potential = module_.interface_potential();
  if (own_)
  {
    // Copies on the shared mesh: its cells inside this patch are resampled after every
    // step, the others hold the value outside the cell (phi = -1, potentials 0).
    auto patch = module_.space()->mesh();
    const auto cells = compat::cells_inside(*fields.mesh(""), patch);
    to_shared_.clear();
    auto copy = [&](const std::string& name, std::shared_ptr<const Function> from, double outside)
    {
      auto to = std::make_shared<Function>(fields.space("", FieldSpace::scalar_p2));
      to->x()->set(outside);
      to_shared_.push_back(std::make_unique<compat::Resampler>(from, to, cells, outside));
      to->name = fields.info(name).label;
      fields.set(name, to);
      fields.set_support(name, to_shared_.back()->support());
      return to;
    };
    std::string potential_copy; // the potential's copy if it is one of the module's fields
    for (const auto& [f, u] : module_.fields())
    {
      if (!fields.declared(field(f)))
        continue; // a history field (BDF2): no copy on the shared mesh
      copy(field(f), u, fields.info(field(f)).outside);
      if (u == potential)
        potential_copy = field(f);
    }
    if (potential && potential_copy.empty())
      copy(field("potential"), potential, 0);
    else if (potential) // one copy under two names
    {
      fields.set(field("potential"), fields.get(potential_copy));
      fields.set_support(field("potential"), *fields.support(potential_copy));
    }
    update_copies();
    patch_volume_ = mesh_volume(module_.space());
    shared_volume_ = mesh_volume(fields.space("", FieldSpace::scalar_p2));
    cut_box_ = fields.cut_box(group_.prefix).value();
    // A cell nearly as long as a periodic side has the whole domain as its mesh
    // (OwnMesh::build): no cut edges, phi advected as on the shared mesh.
    whole_domain_ = covers_domain(cut_box_, scene_.domain);
    module_.set_patch_edges(!whole_domain_);
    if (cell_volume_target_ >= 0) // int phi over this patch for the same int (1 + phi)
      module_.set_targets({cell_volume_target_ - patch_volume_, module_.targets().area});
  }
  else if (potential)
    fields.set(field("potential"), std::const_pointer_cast<Function>(potential));
  observables_ = std::make_unique<Observables>(scene_, module_);
}

void PhaseFieldSubProblem::update_copies()
{
  for (auto& r : to_shared_)
    r->apply();
}

void PhaseFieldSubProblem::connect(FieldRegistry& fields)
{
  if (std::count(reads().begin(), reads().end(), "flow.v"))
  {
    if (!own_)
      module_.set_velocity(fields.get("flow.v"));
    else
    {
      // v^{n+1} resampled onto this cell's mesh before each of its steps.
      const int dim = module_.space()->mesh()->topology().dim();
      velocity_ = std::make_shared<Function>(create_vector_p2_space(module_.space()->mesh(), dim));
      velocity_in_ = std::make_unique<compat::Resampler>(
          fields.get("flow.v"), velocity_, compat::local_cells(*velocity_->function_space()->mesh()), 0.0);
      velocity_in_->apply();
      module_.set_velocity(velocity_);
      auto phi = module_.fields().at("phi");
      edge_outflow_form_.reset();
      if (!whole_domain_)
        edge_outflow_form_ = compat::create_form(*observable_forms(dim).edge_outflow, {},
                                               {{"phi", phi}, {"v", velocity_}}, {},
                                               phi->function_space()->mesh());
    }
    // The cell's velocity int phi~ v / int phi~ (as the flow's cell_velocity, of one cell).
    auto v = own_ ? std::shared_ptr<const Function>(velocity_) : fields.get("flow.v");
    auto phi = module_.fields().at("phi");
    auto mesh = phi->function_space()->mesh();
    const FlowForms forms = flow_forms(mesh->topology().dim(), false);
    const CoefficientMap coeffs{{"phi", phi}, {"v0", v}};
    weight_form_ = compat::create_form(*forms.phase_weight, {}, coeffs, {}, mesh);
    velocity_forms_.clear();
    for (int d = 0; d < mesh->topology().dim(); ++d)
      velocity_forms_.push_back(compat::create_form(*forms.phase_velocity[d], {}, coeffs, {}, mesh));
  }
  if (fields.declared(scene::interaction_sum_field(group_.name, "w_sum", 0)))
  {
    // One source (7.11) per potential, each from the sums over the pairs that have it.
    const auto& in = *scene_.interaction;
    auto c = [](double v) { return std::make_shared<const Constant>(v); };
    const auto potentials = scene::interaction_potentials(in);
    for (std::size_t k = 0; k < potentials.size(); ++k)
    {
      const auto& p = potentials[k];
      module_.set_interaction(fields.get(scene::interaction_sum_field(group_.name, "w_sum", k)),
                              fields.get(scene::interaction_sum_field(group_.name, "B_sum", k)),
                              {{"In_inv", c(1 / in.In)}, {"r1", c(p.r1)}, {"r2", c(p.r2)},
                               {"a1", c(p.a1)}, {"a2", c(p.a2)}, {"a3", c(p.a3)},
                               {"dw_reach", c(in.derivative_reach.value_or(
                                                std::numeric_limits<double>::max()))}},
                              in.refresh, in.flow_force);
    }
  }
  if (std::count(reads().begin(), reads().end(), "polar.P"))
  {
    // The orientation field's terms of phi# (6.15), with P^{n+1} of the polar step.
    const auto& gel = *scene_.polar_gel;
    auto c = [](double v) { return std::make_shared<const Constant>(v); };
    module_.set_orientation(fields.get("polar.P"), {{"Pa_inv", c(1 / scene_.numbers.Pa)},
                                                    {"polar_c1", c(gel.c1)},
                                                    {"polar_beta", c(gel.beta)}});
  }
}

void PhaseFieldSubProblem::publish_targets()
{
  fields_->set_scalar(field("area_target"), module_.targets().area);
}

void PhaseFieldSubProblem::start()
{
  // Targets of the constraints, (3.10)-(3.11): the volume and E_CH at t = 0.
  const ObservableValues v = observables_->evaluate();
  module_.set_targets({v.phi_integral, v.energy_ch});
  if (own_)
    cell_volume_target_ = v.phi_integral + patch_volume_;
  initial_volume_ = v.volume;
  publish_targets();
}

StepTimings PhaseFieldSubProblem::step(double dt)
{
  if (!own_)
    return module_.step(dt);
  auto t0 = Clock::now();
  if (velocity_in_)
    velocity_in_->apply();
  const double in = seconds_since(t0);
  StepTimings t = module_.step(dt);
  t0 = Clock::now();
  if (edge_outflow_form_)
  {
    // The advection lets phi + 1 leave where the fluid leaves the patch (forms/cellphase_ufl,
    // own_mesh_outflow): the cell's diffuse tail and what it sheds. On the shared mesh it
    // would stay in the domain and in int (1 + phi). The H^-1 flows keep int phi by
    // themselves, so it is put back into the cell's interface; the L2 flows' volume
    // multiplier or penalty restores the volume itself, and Allen-Cahn does not keep it.
    const double left = dt * compat::assemble_scalar(*edge_outflow_form_);
    const auto model = scene_.phase_field.model;
    if (model == scene::Model::helfrich_hm1 || model == scene::Model::cahn_hilliard)
      add_in_interface(module_.fields().at("phi"), left);
    edge_outflow_ += left;
  }
  update_copies();
  t.assemble += in + seconds_since(t0); // the transfers between the meshes
  return t;
}

StepTimings PhaseFieldSubProblem::finish_step()
{
  StepTimings t;
  if (!scene_.interaction || !scene_.interaction->refresh)
    return t;
  auto t0 = Clock::now();
  module_.refresh_interaction(); // the sums are those of phi^{n+1} (InteractionSubProblem)
  if (own_)
    update_copies(); // w on the shared mesh, which the flow reads
  t.assemble = seconds_since(t0);
  return t;
}

void PhaseFieldSubProblem::unwrap_centre(std::array<double, 3>& centre)
{
  const auto& d = scene_.domain;
  for (int a : d.periodic)
  {
    // The centre moves less than half a period per step; a larger jump is a crossing.
    const double period = d.upper[a] - d.lower[a];
    double c = centre[a] + centre_shift_[a];
    if (have_last_centre_)
    {
      const double periods = std::round((last_centre_[a] - c) / period);
      centre_shift_[a] += periods * period;
      c += periods * period;
    }
    centre[a] = c;
  }
  last_centre_ = centre;
  have_last_centre_ = true;
}

void PhaseFieldSubProblem::observe(Observation& row)
{
  ObservableValues v = observables_->evaluate();
  if (own_) // int phi over the domain: phi = -1 outside the patch
    v.phi_integral -= shared_volume_ - patch_volume_;
  unwrap_centre(v.center);
  last_ = v;
  if (row.phase_fields++ == 0)
  {
    // The standard columns: this phase field's, then sums over the others (below). The
    // energies other sub-problems observed before it (interaction, orientation) stay.
    const double added = row.values.total_energy, added_kinetic = row.values.total_with_kinetic;
    row.values = v;
    row.values.total_energy += added;
    row.values.total_with_kinetic = v.total_energy + added_kinetic; // the flow adds its kinetic energy
    row.lam_v = module_.multipliers()[0];
    row.lam_a = module_.multipliers()[1];
  }
  else
  {
    auto& r = row.values;
    r.phi_integral += v.phi_integral;
    r.volume += v.volume;
    r.surface += v.surface;
    r.energy_ch += v.energy_ch;
    r.helfrich += v.helfrich;
    r.total_energy += v.total_energy; // (7.4) without E_int, which the interaction adds
    r.total_with_kinetic += v.total_energy;
    r.phi_min = std::min(r.phi_min, v.phi_min);
    r.phi_max = std::max(r.phi_max, v.phi_max);
  }
  // The sharp-interface limits (docs/scenes.md): summed over the phase fields.
  const bool bending = scene::is_helfrich(scene_.phase_field.model);
  const SharpMeasures sharp = sharp_measures(
      *module_.fields().at("phi"), bending ? module_.fields().at("mu").get() : nullptr,
      scene_.phase_field.spontaneous_curvature, scene_.numerics.epsilon);
  std::vector<std::pair<std::string, double>> limits{{"volume_sharp", sharp.inside},
                                                     {"surface_sharp", sharp.surface}};
  if (bending)
    limits.push_back({"bending_energy_sharp", sharp.bending / scene_.numbers.Be}); // (3.1)
  for (const auto& [name, value] : limits)
  {
    auto it = std::find_if(row.extra.begin(), row.extra.end(),
                           [&](const auto& e) { return e.first == name; });
    if (it == row.extra.end())
      row.extra.push_back({name, value});
    else
      it->second += value;
  }
  std::array<double, 3> velocity{0, 0, 0};
  if (weight_form_)
  {
    const double weight = compat::assemble_scalar(*weight_form_);
    for (std::size_t d = 0; d < velocity_forms_.size() && weight > 0; ++d)
      velocity[d] = compat::assemble_scalar(*velocity_forms_[d]) / weight;
  }
  if (velocity_) // int (1 + phi)/2 carried out so far, relative to the cell volume (own mesh)
    row.extra.push_back({(groups_ > 1 ? group_.name + "." : "") + "edge_outflow",
                         edge_outflow_ / 2 / v.volume});
  if (groups_ > 1)
  {
    const std::string g = group_.name + ".";
    if (weight_form_)
      row.extra.insert(row.extra.end(), {{g + "velocity_x", velocity[0]},
                                         {g + "velocity_y", velocity[1]},
                                         {g + "velocity_z", velocity[2]}});
    row.extra.insert(row.extra.end(),
                     {{g + "volume", v.volume}, {g + "surface", v.surface},
                      {g + "helfrich_energy", v.helfrich}, {g + "total_energy", v.total_energy},
                      {g + "center_x", v.center[0]}, {g + "center_y", v.center[1]},
                      {g + "center_z", v.center[2]}, {g + "circularity", v.circularity},
                      {g + "lambda_area", module_.multipliers()[1]}});
    for (const auto& [name, value] : limits)
      row.extra.push_back({g + name, value});
  }
  if (scene_.numerics.solver == scene::Numerics::Solver::reuse)
    solver_columns_.add(row, module_.factorisations(), module_.krylov_iterations());
}

std::string PhaseFieldSubProblem::patch_problem() const
{
  // The cell's band may approach the box its mesh was cut around to a quarter of the
  // margin: beyond, phi is no longer -1 where the mesh ends. (A side of the box beyond a
  // wall is never approached: the band stays inside the domain.)
  const double margin = scene_.numerics.mesh.own_margin_or_default(scene_.numerics.epsilon);
  const auto band = image_near(box_above(*module_.fields().at("phi"), own_band_level), cut_box_,
                               scene_.domain);
  double gap = 1e300;
  for (int a = 0; a < scene_.domain.dim; ++a)
    gap = std::min({gap, band[a] - cut_box_[a], cut_box_[3 + a] - band[3 + a]});
  if (gap < margin / 4)
    return format("cell%s came within %.3g of the edge of its own mesh (band phi > "
                  "-0.9, numerics.mesh.own_margin = %g): remesh more often "
                  "(numerics.mesh.remesh_every) or widen the margin",
                  groups_ > 1 ? (" " + group_.name).c_str() : "", gap, margin);
  return "";
}

std::string PhaseFieldSubProblem::health(const Observation&) const
{
  if (own_)
  {
    const std::string problem = patch_problem();
    if (!problem.empty())
      return problem;
  }
  const auto& v = last_; // this phase field's own values
  const auto& limits = scene_.numerics.limits;
  const double phi_abs = std::max(-v.phi_min, v.phi_max);
  if (phi_abs > limits.phi_bound)
    return format("field phi%s reaches %.4g, beyond the bound +-%g (numerics.limits.phi_bound); "
                  "the time step may be too large",
                  group_.label_suffix.c_str(), v.phi_max > -v.phi_min ? v.phi_max : v.phi_min,
                  limits.phi_bound);
  if (limits.volume_drift && initial_volume_ != 0)
  {
    const double drift = std::abs(v.volume - initial_volume_) / std::abs(initial_volume_);
    if (drift > *limits.volume_drift)
      return format("the %s drifted by %.3g (relative) from %.6g to %.6g, beyond "
                    "numerics.limits.volume_drift = %g",
                    groups_ > 1 ? ("volume of " + group_.name).c_str() : "cell volume", drift,
                    initial_volume_, v.volume, *limits.volume_drift);
  }
  return "";
}

void PhaseFieldSubProblem::save(CheckpointData& data) const
{
  data.set(key("targets.volume"), module_.targets().volume);
  data.set(key("targets.area"), module_.targets().area);
  data.set(key("initial_volume"), initial_volume_);
  if (own_)
  {
    data.set(key("targets.cell_volume"), cell_volume_target_);
    data.set(key("edge_outflow"), edge_outflow_);
  }
  // dE/dphi of the L2 Helfrich flows (the next flow step's force) uses them
  data.set(key("multipliers.volume"), module_.multipliers()[0]);
  data.set(key("multipliers.area"), module_.multipliers()[1]);
  for (int a = 0; a < 3; ++a)
  {
    data.set(key("centre.shift." + std::to_string(a)), centre_shift_[a]);
    data.set(key("centre.last." + std::to_string(a)), last_centre_[a]);
  }
  data.set(key("centre.have_last"), have_last_centre_ ? 1 : 0);
  const auto history = module_.history(); // BDF2: whether phi_prev holds a state, its step
  data.set(key("history.have"), history.have ? 1 : 0);
  data.set(key("history.dt_prev"), history.dt_prev);
}

void PhaseFieldSubProblem::restore(const CheckpointData& data)
{
  module_.set_targets({data.scalar(key("targets.volume")), data.scalar(key("targets.area"))});
  initial_volume_ = data.scalar(key("initial_volume"));
  if (own_)
  {
    cell_volume_target_ = data.scalar(key("targets.cell_volume"));
    if (data.arrays.count(key("edge_outflow"))) // (checkpoints from before 2026-12-05 lack it)
      edge_outflow_ = data.scalar(key("edge_outflow"));
  }
  module_.set_multipliers({data.scalar(key("multipliers.volume")),
                           data.scalar(key("multipliers.area"))});
  for (int a = 0; a < 3; ++a)
  {
    centre_shift_[a] = data.scalar(key("centre.shift." + std::to_string(a)));
    last_centre_[a] = data.scalar(key("centre.last." + std::to_string(a)));
  }
  have_last_centre_ = data.scalar(key("centre.have_last")) != 0;
  if (data.arrays.count(key("history.have")))
    module_.set_history({data.scalar(key("history.have")) != 0,
                         data.scalar(key("history.dt_prev"))});
  publish_targets();
}
} // namespace cellphase
