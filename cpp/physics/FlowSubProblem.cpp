#include "physics/FlowSubProblem.h"
#include "app/FlowSetup.h"
#include "mesh/PointLookup.h"
#include "scene/Formula.h"
#include "physics/FormTable.h"
#include "solve/Assemble.h"
#include "util/Clock.h"
#include <algorithm>
#include <dolfinx/fem/assembler.h>

namespace cellphase
{
FlowSubProblem::FlowSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm)
    : SubProblem(std::move(step)), scene_(scene), comm_(comm), groups_(scene::cell_groups(scene)),
      flow_(flow_parameters(scene), comm)
{
  bool own = false;
  for (const auto& c : scene.cells)
    own = own || c.viscosity.has_value();
  if (own && groups_.size() > 1)
    for (const auto& g : groups_)
      group_viscosity_.push_back(
          scene.cells[g.cells.front()].viscosity.value_or(scene.flow->viscosity[1]));
  for (const auto& r : reads())
    if (r.ends_with(".force"))
      force_fields_.push_back(r);
}

std::vector<std::string> FlowSubProblem::attach_reads() const
{
  std::vector<std::string> out;
  for (const auto& r : reads())
    if (std::find(force_fields_.begin(), force_fields_.end(), r) == force_fields_.end())
      out.push_back(r);
  return out;
}

void FlowSubProblem::add_sub_problem_forces()
{
  auto f = flow_.membrane_force();
  for (const auto& name : force_fields_)
  {
    auto g = fields_->get(name);
    if (g->function_space() != f->function_space())
      throw std::logic_error(name + " must live on the flow's velocity space");
    auto to = f->x()->mutable_array();
    auto from = g->x()->array();
    for (std::size_t k = 0; k < to.size(); ++k)
      to[k] += from[k];
  }
}

void FlowSubProblem::declare(FieldRegistry& fields)
{
  fields_ = &fields;
  // v^n is the flow's only history; p is recomputed each step (checkpointed for the
  // output), lambda too.
  fields.declare({"flow.v", "v", name(), FieldSpace::vector_p2, Transfer::interpolate, true});
  fields.declare({"flow.p", "p", name(), FieldSpace::other, Transfer::recompute, true});
  // Second order (numerics.time_scheme: bdf2): the state one step back, moved at a remesh
  // like the fields it copies but never shaping the mesh.
  for (const auto& f : scene::flow_history_fields(scene_))
    fields.declare({f, f == "flow.v_prev" ? "flow_v_prev" : f == "flow.phi_prev" ? "flow_phi_prev"
                                                                                 : "flow_potential_prev",
                    name(), f == "flow.v_prev" ? FieldSpace::vector_p2 : FieldSpace::scalar_p2,
                    Transfer::interpolate, true, "", f == "flow.phi_prev" ? -1.0 : 0.0, false, true});
  if (std::count(writes().begin(), writes().end(), "flow.lambda"))
    fields.declare({"flow.lambda", "lambda", name(), FieldSpace::other, Transfer::recompute,
                    false});
}

void FlowSubProblem::attach(FieldRegistry& fields)
{
  MembraneFields membrane;
  membrane.phi_cells = fields.find("membrane.phi_cells");
  membrane.concentration = fields.find("membrane.c");
  auto v = fields.find("flow.v"); // moved from the last mesh or from a checkpoint; null: at rest
  if (groups_.size() == 1)
  {
    auto phi = fields.get("cell.phi");
    const PreviousFlowState previous{fields.find("flow.v_prev"), fields.find("flow.phi_prev"),
                                     fields.find("flow.potential_prev")};
    flow_.attach(phi->function_space()->mesh(), phi, fields.get("cell.potential"), v, membrane,
                 previous);
    prepare_cell_force(phi);
    if (flow_.velocity_prev())
    {
      fields.set("flow.v_prev", flow_.velocity_prev());
      if (flow_.phi_prev())
        fields.set("flow.phi_prev", flow_.phi_prev());
      if (flow_.mu_prev())
        fields.set("flow.potential_prev", flow_.mu_prev());
    }
  }
  else
  {
    // eta and rho of phi_cells = max_i phi_i, no force in the (mu, phi) slot of the forms
    // (mu = 0): the summed force comes as f_membrane (7.12).
    auto phi_cells = fields.get("membrane.phi_cells");
    auto mesh = phi_cells->function_space()->mesh();
    phi_cells_ = phi_cells;
    cell_phis_.clear();
    for (const auto& g : groups_)
      cell_phis_.push_back(fields.get(g.prefix + ".phi"));
    if (!group_viscosity_.empty())
    {
      viscosity_ = std::make_shared<Function>(std::const_pointer_cast<Space>(phi_cells->function_space()));
      update_viscosity();
      membrane.viscosity = viscosity_;
    }
    flow_.attach(mesh, phi_cells, nullptr, v, membrane);
    auto Vf = flow_.membrane_force()->function_space();
    const auto forms = interface_force_forms(mesh->topology().dim());
    ConstantMap c{{"capillary", std::make_shared<const Constant>(scene::flow_capillary(scene_))}};
    force_forms_.clear();
    for (const auto& g : groups_)
    {
      auto L = compat::create_form(*forms.L, {Vf},
                                   {{"phi", fields.get(g.prefix + ".phi")},
                                    {"mu", fields.get(g.prefix + ".potential")}},
                                   c);
      // A cell on its own mesh: its potential's copy is exactly 0 outside its patch, and
      // so is mu grad phi; assembled there only, the cost follows the cell, not the mesh.
      const std::string mu = g.prefix + ".potential";
      if (const auto* support = fields.support(mu);
          support && fields.declared(mu) && fields.info(mu).outside == 0)
        L = compat::restrict_to_cells(*L, *support);
      force_forms_.push_back(L);
    }
    force_projection_ = std::make_unique<L2Projection>(
        *compat::create_form(*forms.a, {Vf, Vf}, {}, {}), scene_.domain, comm_, "force_");
    prepare_cell_force(phi_cells);
  }
  fields.set("flow.v", flow_.velocity());
  fields.set("flow.p", flow_.pressure());
  if (flow_.multiplier())
    fields.set("flow.lambda", flow_.multiplier());
}

double FlowSubProblem::project_interface_force()
{
  auto t0 = Clock::now();
  std::vector<const Form*> forms;
  for (const auto& L : force_forms_)
    forms.push_back(L.get());
  force_projection_->project(forms, *flow_.membrane_force(),
                             "the projection of the cells' interface force (7.12)");
  return seconds_since(t0);
}

void FlowSubProblem::prepare_cell_force(std::shared_ptr<const Function> phi_cells)
{
  phi_cells_ = phi_cells;
  cell_force_.clear();
  phi_dof_at_node_.clear();
  if (!scene_.flow->cell_force)
    return;
  const int dim = scene_.domain.dim;
  const scene::VectorFormula F(*scene_.flow->cell_force, dim);
  auto V = flow_.membrane_force()->function_space();
  const auto x = V->tabulate_dof_coordinates(false); // one row of 3 per node
  const auto y = phi_cells->function_space()->tabulate_dof_coordinates(false);
  // The two spaces have the same P2 nodes, numbered independently: match them by position.
  const PointLookup nodes(y, 1e-10 * scene_.domain.largest_extent());
  for (std::size_t n = 0; n < x.size() / 3; ++n)
  {
    const auto f = F(x[3 * n], x[3 * n + 1], x[3 * n + 2]);
    cell_force_.insert(cell_force_.end(), f.begin(), f.begin() + dim);
    const std::int64_t k = nodes.find(&x[3 * n]);
    if (k < 0)
      throw std::logic_error("flow.cell_force: a velocity node has no phase-field dof");
    phi_dof_at_node_.push_back(std::int32_t(k));
  }
}

void FlowSubProblem::update_viscosity()
{
  // At the P2 nodes, phi clipped to [-1, 1] as in forms/flow.py; the phase fields and
  // phi_cells share one space (the cells' fields on the shared mesh).
  auto eta = viscosity_->x()->mutable_array();
  auto phi_cells = phi_cells_->x()->array();
  const double eta0 = scene_.flow->viscosity[0];
  auto clip = [](double p) { return std::clamp(p, -1.0, 1.0); };
  for (std::size_t k = 0; k < eta.size(); ++k)
    eta[k] = eta0 * (1 - clip(phi_cells[k])) / 2;
  for (std::size_t i = 0; i < cell_phis_.size(); ++i)
  {
    auto phi = cell_phis_[i]->x()->array();
    for (std::size_t k = 0; k < eta.size(); ++k)
      eta[k] += group_viscosity_[i] * (1 + clip(phi[k])) / 2;
  }
}

void FlowSubProblem::add_cell_force()
{
  auto f = flow_.membrane_force()->x()->mutable_array();
  auto phi = phi_cells_->x()->array();
  const std::size_t dim = scene_.domain.dim;
  for (std::size_t n = 0; n < phi_dof_at_node_.size(); ++n)
  {
    const double weight = (1 + phi[phi_dof_at_node_[n]]) / 2; // phi~ of the cells, (2.14)
    for (std::size_t c = 0; c < dim; ++c)
      f[n * dim + c] += weight * cell_force_[n * dim + c];
  }
}

StepTimings FlowSubProblem::step(double dt)
{
  StepTimings t;
  if (groups_.size() == 1)
  {
    flow_.set_area_target(fields_->scalar("cell.area_target")); // (3.69), fixed at the start
    if (!cell_force_.empty() || !force_fields_.empty())
      flow_.membrane_force()->x()->set(0.0); // f_membrane holds only the added forces
  }
  else
  {
    t.assemble += project_interface_force(); // of phi^n, mu^n as the single-cell force
    if (viscosity_)
      update_viscosity(); // of phi^n
  }
  if (!cell_force_.empty())
    add_cell_force();
  add_sub_problem_forces();
  const FlowTimings f = flow_.step(dt);
  t.assemble += f.assemble;
  t.factorise = f.factorise;
  t.solve = f.solve;
  t.flow = t.assemble + f.factorise + f.solve;
  return t;
}

void FlowSubProblem::observe(Observation& row)
{
  const FlowObservables f = flow_.observables();
  auto& v = row.values;
  v.kinetic_energy = scene::flow_reynolds(scene_) * f.kinetic_energy; // (3.12)
  v.cell_velocity = f.cell_velocity;
  v.tension_mean = f.tension_mean;
  // Cahn-Hilliard: the interface energy is (1/Ca) E_CH (3.13); Helfrich: the model's own.
  const double interface = scene_.phase_field.model == scene::Model::cahn_hilliard
                               ? scene::flow_capillary(scene_) * v.energy_ch
                               : v.total_energy;
  v.total_with_kinetic = v.kinetic_energy + interface;
  row.extra.push_back({"flow_dofs", double(flow_.num_dofs())}); // the rest of `dofs` is the cells'
  if (scene::flow_solver(scene_) == scene::Numerics::Solver::reuse)
    solver_columns_.add(row, flow_.factorisations(), flow_.krylov_iterations());
}

void FlowSubProblem::save(CheckpointData& data) const
{
  const auto history = flow_.history();
  data.set(name() + ".history.have", history.have ? 1 : 0);
  data.set(name() + ".history.dt_prev", history.dt_prev);
}

void FlowSubProblem::restore(const CheckpointData& data)
{
  if (data.arrays.count(name() + ".history.have")) // older checkpoints have none
    flow_.set_history({data.scalar(name() + ".history.have") != 0,
                       data.scalar(name() + ".history.dt_prev")});
}
} // namespace cellphase
