#include "physics/PolarGelSubProblem.h"
#include "mesh/FieldTransfer.h"
#include "physics/FlowVelocity.h"
#include "scene/Plan.h"
#include "solve/Assemble.h"
#include "util/Clock.h"
#include "util/Random.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <stdexcept>

namespace cellphase
{
namespace
{
std::shared_ptr<Constant> constant(double v) { return std::make_shared<Constant>(v); }

} // namespace

PolarGelSubProblem::PolarGelSubProblem(scene::PlanStep step, const scene::Scene& scene,
                                       MPI_Comm comm)
    : SubProblem(std::move(step)), scene_(scene), gel_(*scene.polar_gel), comm_(comm)
{
  phi_name_ = reads().front();
  if (scene::own_meshes(scene))
    mesh_key_ = scene::cell_groups(scene).front().prefix;
  forms_ = polar_gel_forms(scene.domain.dim);
  mass_forms_ = interface_force_forms(scene.domain.dim);
  dt_ = constant(1.0);
  constants_ = {{"dt", dt_},
                {"Pa", constant(scene.numbers.Pa)},
                {"c1", constant(gel_.c1)},
                {"beta", constant(gel_.beta)},
                {"xi", constant(gel_.xi)},
                {"kappa", constant(gel_.kappa)},
                {"activity", constant(gel_.activity)},
                {"S", constant(gel_.stabilisation)}};
  if (scene.numerics.adaptive_dt)
    estimate_.emplace(std::vector<std::string>{"polar.P"});
}

void PolarGelSubProblem::declare(FieldRegistry& fields)
{
  // On a cell's own mesh P and P# are written there as own_P, own_P_sharp (as P, P_sharp in
  // the cell's field output), and their copies on the shared mesh as P, P_sharp.
  const std::string own = mesh_key_.empty() ? "" : "own_";
  fields.declare({"polar.P", own + "P", name(), FieldSpace::vector_p2, Transfer::interpolate,
                  true, mesh_key_});
  fields.declare({"polar.P_sharp", own + "P_sharp", name(), FieldSpace::vector_p2,
                  Transfer::interpolate, true, mesh_key_});
  if (!mesh_key_.empty())
    for (const char* f : {"P", "P_sharp"})
      fields.declare({std::string("polar.shared.") + f, f, name(), FieldSpace::vector_p2,
                      Transfer::recompute, false});
  if (scene_.flow)
    fields.declare({"polar.force", "polar_force", name(), FieldSpace::other, Transfer::recompute,
                    false});
  if (estimate_)
    estimate_->declare(fields);
}

void PolarGelSubProblem::set_initial(Function& P) const
{
  // delta at every mesh node, or at the nodes of a lattice of spacing noise_length (fitted
  // to the period along periodic axes, so that the noise is periodic too), bilinear in
  // between. A value depends only on the seed and a snapped position or lattice index:
  // the same on any partition.
  const auto& dom = scene_.domain;
  std::array<double, 2> spacing{gel_.noise_length, gel_.noise_length};
  std::array<std::int64_t, 2> period{0, 0}; // lattice cells per period, 0: not periodic
  for (int a = 0; a < 2; ++a)
    if (dom.is_periodic(a) && gel_.noise_length > 0)
    {
      const double length = dom.upper[a] - dom.lower[a];
      period[a] = std::max<std::int64_t>(1, std::llround(length / gel_.noise_length));
      spacing[a] = length / double(period[a]);
    }
  const std::uint64_t seed = gel_.seed;
  auto node_value = [&](std::uint64_t component, std::int64_t i, std::int64_t j)
  {
    if (period[0])
      i = ((i % period[0]) + period[0]) % period[0];
    if (period[1])
      j = ((j % period[1]) + period[1]) % period[1];
    return 2 * random::uniform(seed, component, double(i), double(j), 0) - 1;
  };
  const auto d = gel_.direction;
  const double noise = gel_.noise;
  const random::Snap snap(dom.largest_extent());
  auto delta = [&](std::uint64_t c, double x, double y)
  {
    if (gel_.noise_length == 0) // at every node, from its snapped coordinates
      return noise * (2 * random::uniform(seed, c, snap(x), snap(y), 0) - 1);
    const double s = (x - dom.lower[0]) / spacing[0], t = (y - dom.lower[1]) / spacing[1];
    // Snapped, so that a node's last-bit noise between cells cannot change its lattice cell.
    const double fs = std::floor(s + 1e-9), ft = std::floor(t + 1e-9);
    const double u = std::clamp(s - fs, 0.0, 1.0), w = std::clamp(t - ft, 0.0, 1.0);
    const auto i = std::int64_t(fs), j = std::int64_t(ft);
    return noise * ((1 - u) * (1 - w) * node_value(c, i, j) + u * (1 - w) * node_value(c, i + 1, j)
                    + (1 - u) * w * node_value(c, i, j + 1) + u * w * node_value(c, i + 1, j + 1));
  };
  // Mirrored: R P^0(R x), R the reflection about the domain's centre line in x (Fig. 6.7).
  const double centre = (dom.lower[0] + dom.upper[0]) / 2;
  const double centre_y = (dom.lower[1] + dom.upper[1]) / 2;
  const std::array<double, 2> n{-d[1], d[0]}; // the splay's direction, d turned by +90 degrees
  compat::interpolate_vector(P, [&](double x_node, double y_node, double)
  {
    // Mirrored first, then into the period: a node and its mirror image take the same
    // noise, also on the periodic side (x = upper is x = lower) and beyond it on a
    // wrapped patch's nodes, which take the values a period down.
    const double mirrored = gel_.mirror ? snap(2 * centre - x_node) : x_node;
    const auto [xs, y, z] = dom.into_period(mirrored, y_node, 0);
    const double fan = gel_.splay * ((xs - centre) * n[0] + (y - centre_y) * n[1]);
    const double px = d[0] + fan * n[0] + delta(1, xs, y), py = d[1] + fan * n[1] + delta(2, xs, y);
    return std::array<double, 3>{gel_.mirror ? -px : px, py, 0};
  });
  if (!gel_.inside_only)
    return;
  // P^0 phi~(phi^0): the filaments only in the cell, where the double well keeps them.
  const auto& V = *P.function_space();
  const auto& Vphi = *phi_->function_space();
  auto p = P.x()->mutable_array();
  auto phi = phi_->x()->array();
  const auto& topology = V.mesh()->topology();
  const auto& cells = *topology.index_map(topology.dim());
  std::vector<char> done(p.size() / 2, 0);
  for (std::int32_t c = 0; c < cells.size_local() + cells.num_ghosts(); ++c)
  {
    auto vd = V.dofmap()->cell_dofs(c);
    auto sd = Vphi.dofmap()->cell_dofs(c);
    for (std::size_t k = 0; k < vd.size(); ++k)
      if (!done[vd[k]])
      {
        const double weight = std::clamp((1 + phi[sd[k]]) / 2, 0.0, 1.0);
        p[2 * vd[k]] *= weight;
        p[2 * vd[k] + 1] *= weight;
        done[vd[k]] = 1;
      }
  }
}

void PolarGelSubProblem::attach(FieldRegistry& fields)
{
  phi_ = fields.get(phi_name_);
  auto mesh = phi_->function_space()->mesh();
  auto V = fields.space(mesh_key_, FieldSpace::vector_p2);
  bool fresh_P = false, fresh_sharp = false;
  P_ = fields.take("polar.P", V, fresh_P); // moved from the last mesh or restored
  P_sharp_ = fields.take("polar.P_sharp", V, fresh_sharp);
  if (fresh_P)
    set_initial(*P_);
  if (fresh_sharp)
    project_sharp();
  if (estimate_)
    estimate_->attach(fields);
  if (!mesh_key_.empty())
  {
    // Copies on the shared mesh (0 beyond the patch), made again after every step.
    const auto cells = compat::cells_inside(*fields.mesh(""), mesh);
    to_shared_.clear();
    for (auto [from, to] : {std::pair{P_, "polar.shared.P"}, {P_sharp_, "polar.shared.P_sharp"}})
    {
      auto copy = std::make_shared<Function>(fields.space("", FieldSpace::vector_p2));
      copy->x()->set(0.0);
      copy->name = fields.info(to).label;
      to_shared_.push_back(std::make_unique<compat::Resampler>(from, copy, cells, 0.0));
      to_shared_.back()->apply();
      fields.set(to, copy);
    }
  }

  const CoefficientMap coeffs{{"Pi", P_}, {"Psi", P_sharp_}, {"phi", phi_}};
  energy_ = compat::create_form(*forms_.energy, {}, coeffs, constants_, mesh);
  dissipation_ = compat::create_form(*forms_.dissipation, {}, coeffs, constants_, mesh);
  for (int i = 0; i < 2; ++i)
    P_cell_[i] = compat::create_form(*forms_.P_cell[i], {}, coeffs, constants_, mesh);
  cell_weight_ = compat::create_form(*flow_forms(scene_.domain.dim).phase_weight, {},
                                     {{"phi", phi_}}, {}, mesh);
  system_.reset(); // on this mesh, built by connect
  force_.reset();
  sharp_L_.reset(); // on this mesh's P, built at the next projection
}

void PolarGelSubProblem::project_sharp()
{
  auto V = std::const_pointer_cast<Space>(P_->function_space());
  if (!sharp_L_ || sharp_L_->function_spaces()[0] != V)
  {
    sharp_L_ = compat::create_form(*forms_.L_sharp, {V}, {{"Pi", P_}, {"phi", phi_}}, constants_);
    sharp_projection_ = std::make_unique<L2Projection>(
        *compat::create_form(*mass_forms_.a, {V, V}, {}, {}), scene_.domain, comm_, "polar_sharp_");
  }
  sharp_projection_->project(*sharp_L_, *P_sharp_, "the projection of P# (6.17)");
}

void PolarGelSubProblem::connect(FieldRegistry& fields)
{
  v_ = flow_velocity_or_zero(fields);
  velocity_in_.reset();
  force_out_.reset();
  auto mesh = P_->function_space()->mesh();
  if (!mesh_key_.empty())
  {
    // The own mesh: v^{n+1} resampled onto it before each step (zero without a flow).
    velocity_ = std::make_shared<Function>(create_vector_p2_space(mesh, scene_.domain.dim));
    velocity_->x()->set(0.0);
    if (fields.find("flow.v"))
      velocity_in_ = std::make_unique<compat::Resampler>(fields.get("flow.v"), velocity_,
                                                         compat::local_cells(*mesh), 0.0);
    v_ = velocity_;
  }
  // P^n and P#^n are the registry's fields themselves: the step assembles from them before
  // it overwrites P.
  auto V = std::const_pointer_cast<Space>(P_->function_space());
  const CoefficientMap coeffs{{"Pi", P_}, {"Psi", P_sharp_}, {"phi", phi_}, {"v", v_}};
  system_ = std::make_unique<PeriodicSystem>(
      compat::create_form(*forms_.a, {V, V}, coeffs, constants_),
      compat::create_form(*forms_.L, {V}, coeffs, constants_), scene_, comm_, "polar_",
      scene_.numerics.petsc, scene::polar_gel_solver(scene_));

  if (scene_.flow)
  {
    // On the flow's velocity space, so that the flow adds it to its free force directly.
    auto Vf = std::const_pointer_cast<Space>(fields.get("flow.v")->function_space());
    force_ = std::make_shared<Function>(Vf);
    force_->name = "polar_force";
    auto Vp = Vf; // where the force is projected: P's mesh
    if (!mesh_key_.empty())
    {
      Vp = create_vector_p2_space(mesh, scene_.domain.dim);
      force_on_patch_ = std::make_shared<Function>(Vp);
      force_->x()->set(0.0);
      force_out_ = std::make_unique<compat::Resampler>(
          force_on_patch_, force_, compat::cells_inside(*Vf->mesh(), mesh), 0.0);
    }
    force_L_ = compat::create_form(*forms_.force_L, {Vp},
                                   {{"Pi", P_}, {"Psi", P_sharp_}, {"phi", phi_}}, constants_);
    force_projection_ = std::make_unique<L2Projection>(
        *compat::create_form(*mass_forms_.a, {Vp, Vp}, {}, {}), scene_.domain, comm_, "polar_force_");
    update_force();
    fields.set("polar.force", force_);
  }
}

void PolarGelSubProblem::update_force()
{
  const char* what = "the projection of the orientation force (6.13)";
  if (!force_out_)
    return force_projection_->project(*force_L_, *force_, what);
  force_projection_->project(*force_L_, *force_on_patch_, what);
  force_out_->apply();
}

StepTimings PolarGelSubProblem::step(double dt)
{
  if (!system_)
    throw std::logic_error("polar_gel: step before connect");
  auto t0 = Clock::now();
  dt_->value[0] = dt;
  if (velocity_in_)
    velocity_in_->apply();
  if (estimate_)
    estimate_->begin_step();
  // The matrix holds v^{n+1}, phi^n and the linearisation at P^n: new every step.
  const double before = seconds_since(t0);
  StepTimings t = system_->solve("the orientation field (6.16)-(6.17) of forms/polar_gel.py");
  t.assemble += before;
  const auto [factorised, iterations] = system_->take_counts();
  factorisations_ += factorised;
  last_iterations_ = iterations;
  {
    // P^{n+1}; P# follows in finish_step, from P^{n+1} and phi^{n+1}. The solution lives on
    // P's dofs, the periodic constraint's extra ghosts (several ranks) after them.
    auto x = system_->solution();
    auto p = P_->x()->mutable_array();
    if (x.size() < p.size())
      throw std::logic_error("polar_gel: the solution is not on P's space");
    std::copy_n(x.begin(), p.size(), p.begin());
  }
  if (estimate_)
    time_error_ = estimate_->end_step(dt, comm_);
  last_wall_ = seconds_since(t0);
  return t;
}

StepTimings PolarGelSubProblem::finish_step()
{
  // The flow's next step takes phi#^{n+1} (with P^{n+1} and phi^{n+1}) and the P terms of
  // (6.13). The P# of the coupled (P#, P) step would hold phi^n; the large terms c1 phi P
  // of P# and -(c1/2) |P|^2 of phi# cancel in the force only when both hold the same phi,
  // and a force from phi^n against phi^{n+1} pushes back on the cell's own velocity, a
  // delayed feedback that oscillates and grows with dt. So P# and the force are made from
  // P^{n+1} and phi^{n+1} (differing from the step's P# by O(dt)); the step itself needs
  // no P#^{n+1} (forms/polar_gel.py eliminates it).
  StepTimings t;
  auto t0 = Clock::now();
  project_sharp();
  if (force_)
    update_force();
  for (auto& copy : to_shared_)
    copy->apply();
  t.assemble = seconds_since(t0);
  last_wall_ += t.assemble;
  return t;
}

void PolarGelSubProblem::save(CheckpointData& data) const
{
  if (estimate_)
    estimate_->save(data, name() + ".");
}

void PolarGelSubProblem::restore(const CheckpointData& data)
{
  if (estimate_)
    estimate_->restore(data, name() + ".");
}

void PolarGelSubProblem::observe(Observation& row)
{
  const double energy = compat::assemble_scalar(*energy_); // (6.4)
  row.values.total_energy += energy;                        // (6.1) with E_S of the phase field
  row.values.total_with_kinetic += energy;
  row.extra.push_back({"polar_energy", energy});
  row.extra.push_back({"polar_dissipation", compat::assemble_scalar(*dissipation_)});
  // The mean orientation in the cell, int phi~ P / int phi~: its direction and order.
  const double weight = compat::assemble_scalar(*cell_weight_);
  const double px = compat::assemble_scalar(*P_cell_[0]) / weight;
  const double py = compat::assemble_scalar(*P_cell_[1]) / weight;
  row.extra.push_back({"polar_P_cell_x", px});
  row.extra.push_back({"polar_P_cell_y", py});
  row.extra.push_back({"wall_polar", last_wall_});
  row.extra.push_back({"polar_factorisations", double(factorisations_)});
  row.extra.push_back({"polar_krylov_iterations", double(last_iterations_)});
}

std::int64_t PolarGelSubProblem::num_dofs() const
{
  return P_ ? compat::num_global_dofs(*P_->function_space()) : 0;
}
} // namespace cellphase
