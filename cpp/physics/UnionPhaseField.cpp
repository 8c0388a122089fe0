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
  for (const auto& phi : phis)
    if (phi->function_space() != phis.front()->function_space())
      throw std::invalid_argument("union_phase_field: the fields live on different spaces");
  auto out = std::make_shared<Function>(phis.front()->function_space());
  out->name = "phi_cells";
  update_union(phis, *out);
  return out;
}

void update_union(const std::vector<std::shared_ptr<const Function>>& phis, Function& out)
{
  auto u = out.x()->mutable_array();
  auto first = phis.front()->x()->array();
  std::copy(first.begin(), first.end(), u.begin());
  for (std::size_t k = 1; k < phis.size(); ++k)
  {
    auto x = phis[k]->x()->array();
    for (std::size_t i = 0; i < u.size(); ++i)
      u[i] = std::max(u[i], x[i]);
  }
}
} // namespace cellphase
