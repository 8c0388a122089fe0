// The flow (section 5.3, step 1) as a sub-problem: FlowModule on the mesh of the phase
// field, reading phi, the interface potential dE/dphi and, with inextensibility, the
// membrane union and concentration from the registry.
#pragma once
#include "core/SubProblem.h"
#include "physics/FlowModule.h"
#include "scene/Scene.h"
#include <memory>

namespace cellphase
{
class FlowSubProblem : public SubProblem
{
public:
  FlowSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm);

  std::vector<std::string> attach_reads() const override { return reads(); }
  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  StepTimings step(double dt) override;
  void observe(Observation& row) override;
  std::int64_t num_dofs() const override { return flow_.num_dofs(); }
  int factorisations() const override { return flow_.factorisations(); }

private:
  const scene::Scene& scene_;
  FlowModule flow_;
  FieldRegistry* fields_ = nullptr;
};
} // namespace cellphase
