// The membrane fields of the inextensibility constraint (section 3.4.3) as sub-problems:
// the union phi_cells = max_i phi_i of the cells' phase fields (7.14), recomputed every
// step, and the membrane concentration c of (3.70) (ConcentrationModule).
#pragma once
#include "core/SubProblem.h"
#include "physics/ConcentrationModule.h"
#include "scene/Scene.h"
#include <memory>

namespace cellphase
{
class MembraneUnionSubProblem : public SubProblem
{
public:
  /// `phase_fields`: the qualified names of the cells' phase fields.
  MembraneUnionSubProblem(scene::PlanStep step, std::vector<std::string> phase_fields);
  std::vector<std::string> attach_reads() const override { return reads(); }
  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  StepTimings step(double dt) override;

private:
  std::vector<std::string> phase_fields_;
  FieldRegistry* fields_ = nullptr;
};

class ConcentrationSubProblem : public SubProblem
{
public:
  ConcentrationSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm);
  std::vector<std::string> attach_reads() const override { return {"membrane.phi_cells"}; }
  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  void connect(FieldRegistry& fields) override;
  StepTimings step(double dt) override;

private:
  ConcentrationModule module_;
};
} // namespace cellphase
