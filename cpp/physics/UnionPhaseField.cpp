#include "physics/UnionPhaseField.h"
#include <algorithm>
#include <stdexcept>

namespace cellphase
{
std::shared_ptr<const Function> union_phase_field(
    const std::vector<std::shared_ptr<const Function>>& phis)
{
  if (phis.empty())
    throw std::invalid_argument("union_phase_field: no phase fields");
  if (phis.size() == 1)
    return phis.front();
  auto out = std::make_shared<Function>(phis.front()->function_space());
  out->name = "phi_cells";
  auto u = out->x()->mutable_array();
  auto first = phis.front()->x()->array();
  std::copy(first.begin(), first.end(), u.begin());
  for (std::size_t k = 1; k < phis.size(); ++k)
  {
    if (phis[k]->function_space() != out->function_space())
      throw std::invalid_argument("union_phase_field: the fields live on different spaces");
    auto x = phis[k]->x()->array();
    for (std::size_t i = 0; i < u.size(); ++i)
      u[i] = std::max(u[i], x[i]);
  }
  return out;
}
} // namespace cellphase
