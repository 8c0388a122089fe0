#include "physics/ReactionDiffusionSubProblem.h"
#include "scene/Formula.h"
#include "physics/FlowVelocity.h"
#include "scene/Plan.h"
#include "solve/Assemble.h"
#include "util/Clock.h"
#include "util/Random.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <numbers>
#include <stdexcept>

namespace cellphase
{
namespace
{
std::shared_ptr<Constant> constant(double v) { return std::make_shared<Constant>(v); }

std::shared_ptr<Constant> vector_constant(const std::array<double, 3>& v, int dim)
{
  return std::make_shared<Constant>(std::span<const double>(v.data(), std::size_t(dim)));
}

} // namespace

ReactionDiffusionSubProblem::ReactionDiffusionSubProblem(scene::PlanStep step,
                                                         const scene::Scene& scene, MPI_Comm comm)
    : SubProblem(std::move(step)), scene_(scene), rd_(*scene.reaction_diffusion), comm_(comm)
{
  phi_name_ = reads().front();
  const int dim = scene.domain.dim;
  forms_ = reaction_forms(rd_.model, dim);
  for (std::size_t i = 0; i < rd_.species.size(); ++i)
    if (rd_.species[i].name == rd_.protrusion)
      protrusion_ = i;
  force_forms_ = interface_force_forms(dim);
  dt_ = constant(1.0);
  chem_dir_ = vector_constant({0, 0, 0}, dim);
  chem_x0_ = vector_constant(rd_.chemotaxis ? rd_.chemotaxis->x0 : std::array<double, 3>{0, 0, 0},
                             dim);
  const bool point = rd_.chemotaxis
                     && rd_.chemotaxis->mode == scene::Chemotaxis::Mode::point_source;
  chem_point_ = constant(point ? 1.0 : 0.0);
  chem_xi_ = constant(rd_.chemotaxis ? rd_.chemotaxis->xi : 0.0);
  constants_ = {{"dt", dt_},
                {"rho", constant(rd_.regularisation)},
                {"chem_dir", chem_dir_},
                {"chem_x0", chem_x0_},
                {"chem_point", chem_point_},
                {"chem_xi", chem_xi_}};
  // The form's own constants by name: D_<species> and its kinetics.
  for (const auto& sp : rd_.species)
    constants_["D_" + sp.name] = constant(sp.diffusion);
  for (const auto& [name, value] : rd_.kinetics)
    constants_[name] = constant(value);
  if (scene.numerics.adaptive_dt)
  {
    std::vector<std::string> names;
    for (const auto& sp : rd_.species)
      names.push_back("rd." + sp.name);
    estimate_.emplace(names);
  }
}

void ReactionDiffusionSubProblem::declare(FieldRegistry& fields)
{
  for (const auto& sp : rd_.species)
    fields.declare({"rd." + sp.name, sp.name, name(), FieldSpace::scalar_p2, Transfer::interpolate,
                    true});
  if (scene::has_protrusion(scene_))
    fields.declare({"rd.force", "protrusion_force", name(), FieldSpace::other,
                    Transfer::recompute, false});
  if (estimate_)
    estimate_->declare(fields);
}

void ReactionDiffusionSubProblem::set_initial(std::size_t i, Function& c) const
{
  // Snapped (random::Snap), a node on "x > 0"'s line x = 0 or under the random hash gets
  // the same value on any number of ranks.
  const random::Snap snap(scene_.domain.largest_extent());
  const scene::SpeciesInitial& init = rd_.species[i].initial;
  if (init.random)
  {
    const double lo = (*init.random)[0], hi = (*init.random)[1];
    const std::uint64_t seed = rd_.seed;
    compat::interpolate(c, [&](double x, double y, double z)
                        { return lo + (hi - lo) * random::uniform(seed, i + 1, snap(x), snap(y), snap(z)); });
    return;
  }
  if (init.where.empty())
  {
    c.x()->set(init.value);
    return;
  }
  const scene::VectorFormula where({init.where, "0", "0"}, 1);
  compat::interpolate(c, [&](double x, double y, double z)
                      { return where(snap(x), snap(y), snap(z))[0] != 0 ? init.value : init.otherwise; });
}

void ReactionDiffusionSubProblem::attach(FieldRegistry& fields)
{
  phi_ = fields.get(phi_name_);
  auto V = std::const_pointer_cast<Space>(phi_->function_space());
  auto mesh = V->mesh();
  W_ = compat::create_space(forms_.space, "u0", mesh);
  species_.clear();
  for (std::size_t i = 0; i < rd_.species.size(); ++i)
  {
    const std::string name = "rd." + rd_.species[i].name;
    bool fresh = false;
    auto c = fields.take(name, V, fresh); // moved from the last mesh or restored
    if (fresh)
      set_initial(i, *c);
    species_.push_back(c);
  }
  if (estimate_)
    estimate_->attach(fields);
  node_x_ = V->tabulate_dof_coordinates(false); // for the observables, once per mesh
  phi_old_ = std::make_shared<Function>(V);
  std::copy(phi_->x()->array().begin(), phi_->x()->array().end(),
            phi_old_->x()->mutable_array().begin());

  // V dof -> W dof per species (W's sub-elements are V's element).
  to_mixed_.clear();
  for (std::size_t i = 0; i < rd_.species.size(); ++i)
    to_mixed_.push_back(compat::dofs_in_sub_space(*V, *W_->sub({int(i)})));
  u0_ = std::make_shared<Function>(W_);
  amount_.clear();
  amount_cell_.clear();
  for (std::size_t i = 0; i < species_.size(); ++i)
  {
    const bool membrane = rd_.species[i].membrane;
    CoefficientMap coeffs{{"z", species_[i]}, {"phi_h", phi_}};
    amount_.push_back(compat::create_form(membrane ? *forms_.membrane_amount : *forms_.bulk_amount,
                                          {}, coeffs, constants_, mesh));
    amount_cell_.push_back(compat::create_form(
        membrane ? *forms_.membrane_amount_cell : *forms_.bulk_amount_cell, {}, coeffs,
        constants_, mesh));
  }
  // A remesh moved the species by interpolation, and the phase field with its volume kept:
  // scale each species back to its amount before the remesh (positive factors keep c >= 0).
  if (!kept_.empty())
  {
    const auto now = amounts();
    for (std::size_t i = 0; i < species_.size(); ++i)
      if (now[i] != 0)
      {
        const double f = kept_[i] / now[i];
        for (double& x : species_[i]->x()->mutable_array())
          x *= f;
      }
  }
  kept_ = amounts();
  system_.reset(); // on this mesh, built by connect
  force_.reset();
}

void ReactionDiffusionSubProblem::connect(FieldRegistry& fields)
{
  v_ = flow_velocity_or_zero(fields);
  CoefficientMap coeffs{{"u0", u0_}, {"phi", phi_}, {"phi_old", phi_old_}, {"v", v_}};
  system_ = std::make_unique<PeriodicSystem>(
      compat::create_form(*forms_.a, {W_, W_}, coeffs, constants_),
      compat::create_form(*forms_.L, {W_}, coeffs, constants_), scene_, comm_, "rd_",
      rd_.petsc ? *rd_.petsc : scene_.numerics.petsc, scene::reaction_diffusion_solver(scene_));

  if (scene::has_protrusion(scene_))
  {
    // On the flow's velocity space, so that the flow adds it to its free force directly.
    auto Vf = std::const_pointer_cast<Space>(fields.get("flow.v")->function_space());
    force_ = std::make_shared<Function>(Vf);
    force_->name = "protrusion_force";
    ConstantMap c{{"capillary", constant(-1.0 / *scene_.numbers.Fa)}};
    force_L_ = compat::create_form(*force_forms_.L, {Vf},
                                   {{"phi", phi_}, {"mu", species_[protrusion_]}}, c);
    force_projection_ = std::make_unique<L2Projection>(
        *compat::create_form(*force_forms_.a, {Vf, Vf}, {}, {}), scene_.domain, comm_, "rd_force_");
    update_force();
    fields.set("rd.force", force_);
  }
}

void ReactionDiffusionSubProblem::update_force()
{
  force_projection_->project(*force_L_, *force_, "the projection of the protrusion force (5.7)");
}

std::array<double, 3> ReactionDiffusionSubProblem::signal_gradient(double t) const
{
  using Mode = scene::Chemotaxis::Mode;
  const scene::Chemotaxis& ch = *rd_.chemotaxis;
  switch (ch.mode)
  {
  case Mode::rotating: // mode 1: xi (cos wt, sin wt)
    return {ch.xi * std::cos(ch.omega * t), ch.xi * std::sin(ch.omega * t), 0};
  case Mode::sinusoidal: // mode 2: xi (1, sin wt)
    return {ch.xi, ch.xi * std::sin(ch.omega * t), 0};
  case Mode::random_turns: // mode 3: a turn by -w, 0 or w every theta steps
  {
    double angle = ch.direction_deg * std::numbers::pi / 180;
    const std::int64_t turns = std::int64_t(std::llround(t / scene_.numerics.dt)) / ch.theta;
    for (std::int64_t j = 1; j <= turns; ++j)
      angle += ch.omega * double(std::int64_t(random::mix(rd_.seed ^ random::mix(1000 + j)) % 3) - 1);
    return {ch.xi * std::cos(angle), ch.xi * std::sin(angle), 0};
  }
  case Mode::point_source: // mode 4: in the form, from x0
    break;
  }
  return {0, 0, 0};
}

void ReactionDiffusionSubProblem::update_signal(double t)
{
  if (!rd_.chemotaxis)
    return;
  const auto g = signal_gradient(t);
  for (int a = 0; a < scene_.domain.dim; ++a)
    chem_dir_->value[a] = g[a];
}

double ReactionDiffusionSubProblem::signal_angle(const std::array<double, 3>& centre) const
{
  auto g = signal_gradient(time_);
  if (rd_.chemotaxis->mode == scene::Chemotaxis::Mode::point_source) // -xi (x - x0)/|x - x0|
    g = {rd_.chemotaxis->x0[0] - centre[0], rd_.chemotaxis->x0[1] - centre[1], 0};
  return std::atan2(g[1], g[0]) * 180 / std::numbers::pi;
}

StepTimings ReactionDiffusionSubProblem::step(double dt)
{
  if (!system_)
    throw std::logic_error("reaction_diffusion: step before connect");
  StepTimings t;
  auto t0 = Clock::now();
  dt_->value[0] = dt;
  update_signal(time_ + dt);
  if (estimate_)
    estimate_->begin_step();
  {
    auto u = u0_->x()->mutable_array();
    for (std::size_t i = 0; i < species_.size(); ++i)
    {
      auto c = species_[i]->x()->array();
      for (std::size_t d = 0; d < to_mixed_[i].size(); ++d)
        u[to_mixed_[i][d]] = c[d];
    }
  }
  // The matrix holds phi^{n+1}, v^{n+1} and the kinetics at c^n: new every step.
  const double before = seconds_since(t0);
  t = system_->solve("the reaction-diffusion system of forms/" + rd_.model + ".py");
  t.assemble += before;
  const auto [factorised, iterations] = system_->take_counts();
  factorisations_ += factorised;
  last_iterations_ = iterations;
  auto x = system_->solution();
  for (std::size_t i = 0; i < species_.size(); ++i)
  {
    auto c = species_[i]->x()->mutable_array();
    for (std::size_t d = 0; d < to_mixed_[i].size(); ++d)
      c[d] = x[to_mixed_[i][d]];
  }
  if (estimate_)
    time_error_ = estimate_->end_step(dt, comm_);
  // phi^{n+1} becomes the old weight of the next step.
  std::copy(phi_->x()->array().begin(), phi_->x()->array().end(),
            phi_old_->x()->mutable_array().begin());
  time_ += dt;
  kept_ = amounts();
  if (force_)
  {
    auto t3 = Clock::now();
    update_force(); // c1^{n+1} grad phi^{n+1}: the next flow step's c^n grad phi^n
    t.assemble += seconds_since(t3);
  }
  last_wall_ = seconds_since(t0);
  return t;
}

std::vector<double> ReactionDiffusionSubProblem::amounts() const
{
  std::vector<double> out;
  for (const auto& f : amount_)
    out.push_back(compat::assemble_scalar(*f));
  return out;
}

void ReactionDiffusionSubProblem::observe(Observation& row)
{
  const auto kept = amounts();
  double membrane = 0, bulk = 0, cell = 0;
  for (std::size_t i = 0; i < species_.size(); ++i)
  {
    (rd_.species[i].membrane ? membrane : bulk) += kept[i];
    cell += compat::assemble_scalar(*amount_cell_[i]);
  }
  row.extra.push_back({"rd_mass", membrane + bulk});
  row.extra.push_back({"rd_mass_membrane", membrane});
  row.extra.push_back({"rd_mass_bulk", bulk});
  row.extra.push_back({"rd_mass_cell", cell});
  row.extra.push_back({"wall_rd", last_wall_}); // this sub-problem's part of the step
  row.extra.push_back({"rd_factorisations", double(factorisations_)});
  row.extra.push_back({"rd_krylov_iterations", double(last_iterations_)});

  // The largest and smallest protrusion species (c1) on the membrane (|phi| < 0.9), and
  // their angles about the cell's centre: the polarity of the pattern (front at the maximum).
  for (const double sign : {1.0, -1.0})
  {
    const auto [value, angle] = membrane_extremum(sign, row.values.center);
    const std::string column = "rd_" + rd_.protrusion + (sign > 0 ? "_max" : "_min");
    row.extra.push_back({column, value});
    row.extra.push_back({column + "_angle_deg", angle});
  }
  if (rd_.chemotaxis)
    row.extra.push_back({"rd_signal_angle_deg", signal_angle(row.values.center)});
}

std::pair<double, double>
ReactionDiffusionSubProblem::membrane_extremum(double sign, const std::array<double, 3>& centre) const
{
  const auto& c = species_[protrusion_];
  const auto& x = node_x_;
  auto c1 = c->x()->array();
  auto phi = phi_->x()->array();
  const std::int32_t owned = c->function_space()->dofmap()->index_map->size_local();
  struct
  {
    double value;
    int rank;
  } best{-INFINITY, 0}, global;
  std::int32_t at = -1;
  for (std::int32_t d = 0; d < owned; ++d)
    if (std::abs(phi[d]) < 0.9 && sign * c1[d] > best.value)
    {
      best.value = sign * c1[d];
      at = d;
    }
  MPI_Comm_rank(comm_, &best.rank);
  MPI_Allreduce(&best, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_);
  if (!std::isfinite(global.value))
    return {0.0, 0.0}; // no membrane node (not reached for a cell inside the domain)
  std::array<double, 2> where{0, 0};
  if (best.rank == global.rank && at >= 0)
    where = {x[3 * at], x[3 * at + 1]};
  MPI_Bcast(where.data(), 2, MPI_DOUBLE, global.rank, comm_);
  return {sign * global.value,
          std::atan2(where[1] - centre[1], where[0] - centre[0]) * 180 / std::numbers::pi};
}

void ReactionDiffusionSubProblem::save(CheckpointData& data) const
{
  data.set(name() + ".time", time_);
  if (estimate_)
    estimate_->save(data, name() + ".");
}

void ReactionDiffusionSubProblem::restore(const CheckpointData& data)
{
  time_ = data.scalar(name() + ".time");
  kept_.clear(); // amounts of the restored mesh, computed at attach
  if (estimate_)
    estimate_->restore(data, name() + ".");
}

void ReactionDiffusionSubProblem::rewind()
{
  // phi is phi^n again: the old weight of the repeated step, and the amounts at t^n.
  std::copy(phi_->x()->array().begin(), phi_->x()->array().end(),
            phi_old_->x()->mutable_array().begin());
  kept_ = amounts();
  time_error_ = -1;
}

std::int64_t ReactionDiffusionSubProblem::num_dofs() const
{
  return W_ ? compat::num_global_dofs(*W_) : 0;
}
} // namespace cellphase
