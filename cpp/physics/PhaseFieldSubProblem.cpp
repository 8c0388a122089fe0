#include "physics/PhaseFieldSubProblem.h"
#include <algorithm>
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
    : SubProblem(std::move(step)), group_(std::move(group)), groups_(groups),
      scene_(scene::group_scene(scene, group_)), module_(scene_, comm)
{
}

void PhaseFieldSubProblem::declare(FieldRegistry& fields)
{
  fields_ = &fields;
  for (const auto& f : scene::model_fields(scene_.phase_field.model))
    fields.declare({field(f), f + group_.label_suffix, name(), FieldSpace::scalar_p2,
                    f == "phi" ? Transfer::keep_integral : Transfer::interpolate, true});
  // dE/dphi for the flow's interface force: mu or w itself, or the projection of (3.84),
  // which is recomputed from phi and mu on every mesh.
  const std::string potential = field("potential");
  if (std::count(writes().begin(), writes().end(), potential))
    fields.declare({potential, "potential" + group_.label_suffix, name(), FieldSpace::scalar_p2,
                    Transfer::recompute, false});
}

void PhaseFieldSubProblem::attach(FieldRegistry& fields)
{
  auto phi = fields.get(field("phi"));
  FieldMap given;
  for (const auto& f : scene::model_fields(scene_.phase_field.model))
    if (auto u = fields.find(field(f)))
      given[f] = u;
  module_.attach(std::const_pointer_cast<Space>(phi->function_space()), given);
  for (const auto& [f, u] : module_.fields())
    fields.set(field(f), u);
  // The multipliers of a checkpoint are in place (restore() comes before attach): the
  // projection of (3.84) uses them.
  if (fields.declared(field("potential")))
    fields.set(field("potential"),
               std::const_pointer_cast<Function>(module_.interface_potential()));
  observables_ = std::make_unique<Observables>(scene_, module_);
}

void PhaseFieldSubProblem::connect(FieldRegistry& fields)
{
  if (std::count(reads().begin(), reads().end(), "flow.v"))
    module_.set_velocity(fields.get("flow.v"));
  const std::string sums = "interaction." + group_.name;
  if (fields.declared(sums + ".w_sum"))
  {
    const auto& in = *scene_.interaction;
    auto c = [](double v) { return std::make_shared<const Constant>(v); };
    module_.set_interaction(fields.get(sums + ".w_sum"), fields.get(sums + ".B_sum"),
                            {{"In_inv", c(1 / in.In)}, {"r1", c(in.r1)}, {"r2", c(in.r2)},
                             {"a1", c(in.a1)}, {"a2", c(in.a2)}, {"a3", c(in.a3)}});
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
  initial_volume_ = v.volume;
  publish_targets();
}

StepTimings PhaseFieldSubProblem::step(double dt) { return module_.step(dt); }

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
  unwrap_centre(v.center);
  last_ = v;
  if (row.phase_fields++ == 0)
  {
    // The standard columns: this phase field's, then sums over the others (below).
    row.values = v;
    row.values.total_with_kinetic = v.total_energy; // the flow adds its kinetic energy
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
  if (groups_ > 1)
  {
    const std::string g = group_.name + ".";
    row.extra.insert(row.extra.end(),
                     {{g + "volume", v.volume}, {g + "surface", v.surface},
                      {g + "helfrich_energy", v.helfrich}, {g + "total_energy", v.total_energy},
                      {g + "center_x", v.center[0]}, {g + "center_y", v.center[1]},
                      {g + "center_z", v.center[2]}, {g + "circularity", v.circularity},
                      {g + "lambda_area", module_.multipliers()[1]}});
  }
}

std::string PhaseFieldSubProblem::health(const Observation&) const
{
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
  // dE/dphi of the L2 Helfrich flows (the next flow step's force) uses them
  data.set(key("multipliers.volume"), module_.multipliers()[0]);
  data.set(key("multipliers.area"), module_.multipliers()[1]);
  for (int a = 0; a < 3; ++a)
  {
    data.set(key("centre.shift." + std::to_string(a)), centre_shift_[a]);
    data.set(key("centre.last." + std::to_string(a)), last_centre_[a]);
  }
  data.set(key("centre.have_last"), have_last_centre_ ? 1 : 0);
}

void PhaseFieldSubProblem::restore(const CheckpointData& data)
{
  module_.set_targets({data.scalar(key("targets.volume")), data.scalar(key("targets.area"))});
  initial_volume_ = data.scalar(key("initial_volume"));
  module_.set_multipliers({data.scalar(key("multipliers.volume")),
                           data.scalar(key("multipliers.area"))});
  for (int a = 0; a < 3; ++a)
  {
    centre_shift_[a] = data.scalar(key("centre.shift." + std::to_string(a)));
    last_centre_[a] = data.scalar(key("centre.last." + std::to_string(a)));
  }
  have_last_centre_ = data.scalar(key("centre.have_last")) != 0;
  publish_targets();
}
} // namespace cellphase
