// The velocity that transports a field: the flow's v (flow.v) when the scene has a flow,
// else a zero vector field on the shared mesh, so that the transport terms of the forms
// stay and vanish.
#pragma once
#include "core/FieldRegistry.h"
#include <memory>

namespace cellphase
{
inline std::shared_ptr<const Function> flow_velocity_or_zero(FieldRegistry& fields)
{
  if (auto v = fields.find("flow.v"))
    return v;
  auto zero = std::make_shared<Function>(fields.space("", FieldSpace::vector_p2));
  zero->x()->set(0.0);
  return zero;
}
} // namespace cellphase
