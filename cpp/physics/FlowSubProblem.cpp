#include "physics/FlowSubProblem.h"
#include "app/FlowSetup.h"

namespace cellphase
{
FlowSubProblem::FlowSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm)
    : SubProblem(std::move(step)), scene_(scene), flow_(flow_parameters(scene), comm)
{
}

void FlowSubProblem::declare(FieldRegistry& fields)
{
  fields_ = &fields;
  // v^n is the flow's only history; p is recomputed each step (checkpointed for the
  // output), lambda too.
  fields.declare({"flow.v", "v", name(), FieldSpace::vector_p2, Transfer::interpolate, true});
  fields.declare({"flow.p", "p", name(), FieldSpace::other, Transfer::recompute, true});
  if (std::count(writes().begin(), writes().end(), "flow.lambda"))
    fields.declare({"flow.lambda", "lambda", name(), FieldSpace::other, Transfer::recompute,
                    false});
}

void FlowSubProblem::attach(FieldRegistry& fields)
{
  auto phi = fields.get("cell.phi");
  MembraneFields membrane;
  membrane.phi_cells = fields.find("membrane.phi_cells");
  membrane.concentration = fields.find("membrane.c");
  // v^n moved from the last mesh or read from a checkpoint; null: the fluid at rest.
  flow_.attach(phi->function_space()->mesh(), phi, fields.get("cell.potential"),
               fields.find("flow.v"), membrane);
  fields.set("flow.v", flow_.velocity());
  fields.set("flow.p", flow_.pressure());
  if (flow_.multiplier())
    fields.set("flow.lambda", flow_.multiplier());
}

StepTimings FlowSubProblem::step(double dt)
{
  flow_.set_area_target(fields_->scalar("cell.area_target")); // (3.69), fixed at the start
  const FlowTimings f = flow_.step(dt);
  StepTimings t;
  t.assemble = f.assemble;
  t.factorise = f.factorise;
  t.solve = f.solve;
  t.flow = f.assemble + f.factorise + f.solve;
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
}
} // namespace cellphase
