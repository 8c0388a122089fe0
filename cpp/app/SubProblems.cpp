#include "app/SubProblems.h"
#include "physics/FlowSubProblem.h"
#include "physics/MembraneSubProblems.h"
#include "physics/PhaseFieldSubProblem.h"
#include <stdexcept>

namespace cellphase
{
std::vector<std::unique_ptr<SubProblem>> build_sub_problems(const scene::Scene& scene,
                                                            MPI_Comm comm)
{
  std::vector<std::unique_ptr<SubProblem>> out;
  for (const auto& step : scene::make_plan(scene).steps)
  {
    if (step.name == "phase_field")
      out.push_back(std::make_unique<PhaseFieldSubProblem>(step, scene, comm));
    else if (step.name == "flow")
      out.push_back(std::make_unique<FlowSubProblem>(step, scene, comm));
    else if (step.name == "membrane")
      out.push_back(std::make_unique<MembraneUnionSubProblem>(step, std::vector<std::string>{"cell.phi"}));
    else if (step.name == "concentration")
      out.push_back(std::make_unique<ConcentrationSubProblem>(step, scene, comm));
    else
      throw std::logic_error("no sub-problem is built for plan step " + step.name);
  }
  return out;
}
} // namespace cellphase
