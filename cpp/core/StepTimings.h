// Wall time of the parts of one step, summed over the sub-problems that took it.
#pragma once

namespace cellphase
{
struct StepTimings
{
  double assemble = 0, factorise = 0, solve = 0;
  double flow = 0; ///< the flow's part of the three above (coupled runs)

  StepTimings& operator+=(const StepTimings& o)
  {
    assemble += o.assemble;
    factorise += o.factorise;
    solve += o.solve;
    flow += o.flow;
    return *this;
  }
};
} // namespace cellphase
