#include "physics/MembraneSubProblems.h"
#include "physics/UnionPhaseField.h"
#include "util/Clock.h"

namespace cellphase
{
MembraneUnionSubProblem::MembraneUnionSubProblem(scene::PlanStep step,
                                                 std::vector<std::string> phase_fields)
    : SubProblem(std::move(step)), phase_fields_(std::move(phase_fields))
{
}

void MembraneUnionSubProblem::declare(FieldRegistry& fields)
{
  fields_ = &fields;
  fields.declare({"membrane.phi_cells", "phi_cells", name(), FieldSpace::scalar_p2,
                  Transfer::recompute, false});
}

void MembraneUnionSubProblem::attach(FieldRegistry& fields)
{
  std::vector<std::shared_ptr<const Function>> phis;
  for (const auto& f : phase_fields_)
    phis.push_back(fields.get(f));
  // One phase field: phi_cells is phi itself (no copy, always current).
  fields.set("membrane.phi_cells", std::const_pointer_cast<Function>(union_phase_field(phis)));
}

StepTimings MembraneUnionSubProblem::step(double)
{
  StepTimings t;
  if (phase_fields_.size() < 2)
    return t;
  auto t0 = Clock::now();
  // (7.14) with the phase fields of the last step, in place (the flow holds this function).
  std::vector<std::shared_ptr<const Function>> phis;
  for (const auto& f : phase_fields_)
    phis.push_back(fields_->get(f));
  update_union(phis, *fields_->get("membrane.phi_cells"));
  t.assemble = seconds_since(t0);
  return t;
}

ConcentrationSubProblem::ConcentrationSubProblem(scene::PlanStep step, const scene::Scene& scene,
                                                 MPI_Comm comm)
    : SubProblem(std::move(step)),
      module_(scene.flow->inextensibility->concentration->diffusion, scene.domain.periodic, comm)
{
}

void ConcentrationSubProblem::declare(FieldRegistry& fields)
{
  fields.declare({"membrane.c", "c", name(), FieldSpace::scalar_p2, Transfer::interpolate, true});
}

void ConcentrationSubProblem::attach(FieldRegistry& fields)
{
  module_.attach(fields.get("membrane.phi_cells"), fields.find("membrane.c")); // null: c = 1
  fields.set("membrane.c", module_.concentration());
}

void ConcentrationSubProblem::connect(FieldRegistry& fields)
{
  module_.set_velocity(fields.get("flow.v"));
}

StepTimings ConcentrationSubProblem::step(double dt)
{
  StepTimings t; // (3.70) with v^{n+1} and phi^{n+1}
  const double seconds = module_.step(dt);
  t.solve = seconds;
  t.flow = seconds;
  return t;
}
} // namespace cellphase
