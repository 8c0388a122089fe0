#include "app/SubProblems.h"
#include "physics/FlowSubProblem.h"
#include "physics/InteractionSubProblem.h"
#include "physics/MembraneSubProblems.h"
#include "physics/PhaseFieldSubProblem.h"
#include "physics/PolarGelSubProblem.h"
#include "physics/ReactionDiffusionSubProblem.h"
#include <algorithm>
#include <stdexcept>

namespace cellphase
{
std::vector<std::unique_ptr<SubProblem>> build_sub_problems(const scene::Scene& scene,
                                                            MPI_Comm comm)
{
  std::vector<std::unique_ptr<SubProblem>> out;
  const auto groups = scene::cell_groups(scene);
  std::vector<std::string> phis;
  for (const auto& g : groups)
    phis.push_back(g.prefix + ".phi");
  for (const auto& step : scene::make_plan(scene).steps)
  {
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const scene::CellGroup& g) { return g.step == step.name; });
    if (group != groups.end())
      out.push_back(std::make_unique<PhaseFieldSubProblem>(step, scene, comm, *group,
                                                           int(groups.size())));
    else if (step.name == "interaction")
      out.push_back(std::make_unique<InteractionSubProblem>(step, scene, comm));
    else if (step.name == "flow")
      out.push_back(std::make_unique<FlowSubProblem>(step, scene, comm));
    else if (step.name == "membrane")
      out.push_back(std::make_unique<MembraneUnionSubProblem>(step, phis));
    else if (step.name == "reaction_diffusion")
      out.push_back(std::make_unique<ReactionDiffusionSubProblem>(step, scene, comm));
    else if (step.name == "polar_gel")
      out.push_back(std::make_unique<PolarGelSubProblem>(step, scene, comm));
    else if (step.name == "concentration")
      out.push_back(std::make_unique<ConcentrationSubProblem>(step, scene, comm));
    else
      throw std::logic_error("no sub-problem is built for plan step " + step.name);
  }
  return out;
}
} // namespace cellphase
