// The union of the cells' phase fields, phi_cells = max_i phi_i (7.14): +1 inside any cell,
// -1 outside all of them. The inextensibility constraint of 3.4.3 acts on its level set,
// so that one multiplier serves every membrane (7.15)-(7.16).
#pragma once
#include "compat/Dolfinx.h"
#include <memory>
#include <vector>

namespace cellphase
{
/// Pointwise maximum of fields on one space (dof by dof: exact at the Lagrange nodes).
/// One field is returned as it is (no copy).
std::shared_ptr<const Function> union_phase_field(
    const std::vector<std::shared_ptr<const Function>>& phis);

/// out = max_i phis[i] dof by dof, in place (out lives on the fields' space).
void update_union(const std::vector<std::shared_ptr<const Function>>& phis, Function& out);
} // namespace cellphase
