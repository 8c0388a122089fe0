// The sub-problems of a scene, built from its plan (scene/Plan.h): one object per step of
// the split. A new kind of sub-problem adds its constructor here and its step to the plan.
#pragma once
#include "core/SubProblem.h"
#include "scene/Scene.h"
#include <memory>
#include <vector>

namespace cellphase
{
std::vector<std::unique_ptr<SubProblem>> build_sub_problems(const scene::Scene& scene,
                                                            MPI_Comm comm);
} // namespace cellphase
