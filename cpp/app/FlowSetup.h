// The flow module's parameters from a scene's flow section (section 2.8, (3.17)).
#pragma once
#include "physics/FlowModule.h"
#include "scene/Scene.h"

namespace cellphase
{
/// Re (0 for Stokes), relative densities and viscosities, body forces, the interface-force
/// prefactor, walls (open sides get none) and solver options. Requires scene.flow.
FlowParameters flow_parameters(const scene::Scene& scene);

} // namespace cellphase
