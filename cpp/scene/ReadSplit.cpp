#include "scene/Plan.h"
#include "scene/Sections.h"
#include <algorithm>

namespace cellphase::scene
{
using namespace yaml;

void check_split(const Section& top, const Scene& s)
{
  const Section n = top.section("numerics");
  if (s.flow && cell_groups(s).size() > 1)
  {
    // The summed interface force (7.12) is built for the membrane models; Cahn-Hilliard's
    // flux J (2.8) and the global area (3.69) are of one phase field.
    if (s.phase_field.model == Model::cahn_hilliard)
      top.fail("flow", "with several phase fields the flow is coupled to the Helfrich models "
                       "only (chapter 7); for cahn_hilliard put the cells into one phase field "
                       "with the same `group:` in each cell");
    if (s.flow->inextensibility && s.flow->inextensibility->global_area)
      top.section("flow").section("inextensibility").fail(
          "global_area", "restores the area of one phase field (3.69); with several cells "
                         "use each cell's area penalty (cells[].penalty_area) instead");
  }
  if (s.numerics.split)
  {
    const auto available = default_split(s);
    const auto& split = *s.numerics.split;
    const Value v = n.value("split");
    if (split.empty())
      v.fail("is empty; list the sub-problems to step, out of " + join(available));
    for (std::size_t i = 0; i < split.size(); ++i)
    {
      if (std::find(available.begin(), available.end(), split[i]) == available.end())
        v.element(i).fail("found \"" + split[i] + "\", expected one of the sub-problems of this "
                          "scene: " + join(available));
      if (std::find(split.begin(), split.begin() + i, split[i]) != split.begin() + i)
        v.element(i).fail("sub-problem " + split[i] + " is listed twice");
    }
  }
  const std::string problem = plan_problem(make_plan(s));
  if (!problem.empty() && s.numerics.split)
    n.fail("split", problem + " (numerics.split lists " + join(*s.numerics.split) + ")");
  if (!problem.empty()) // the default split always closes; this is a bug of Plan.cpp
    top.fail("the thesis' split of this scene does not close: " + problem);
}
} // namespace cellphase::scene
