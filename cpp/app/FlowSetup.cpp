#include "app/FlowSetup.h"

namespace cellphase
{
FlowParameters flow_parameters(const scene::Scene& scene)
{
  const scene::Flow& f = *scene.flow;
  FlowParameters p;
  p.Re = scene::flow_reynolds(scene);
  p.density = f.density;
  p.viscosity = f.viscosity;
  // The variable-density flux J (2.8) needs the H^-1 flux -gamma grad mu of Cahn-Hilliard;
  // the Helfrich coupling of 3.4.2 assumes equal densities.
  p.mobility = scene.phase_field.model == scene::Model::cahn_hilliard ? scene.phase_field.mobility
                                                                       : 0.0;
  p.degenerate_mobility = scene.phase_field.degenerate_mobility;
  p.capillary = scene::flow_capillary(scene);
  p.gravity = f.gravity;
  p.force = f.force;
  for (int i = 0; i < 2 * scene.domain.dim; ++i)
  {
    const scene::WallSpec& w = f.walls[i];
    Wall wall;
    wall.side = Side(i);
    switch (w.type)
    {
    case scene::WallType::open: continue; // traction-free: no condition
    case scene::WallType::no_slip: wall.kind = WallKind::no_slip; break;
    case scene::WallType::free_slip: wall.kind = WallKind::free_slip; break;
    case scene::WallType::moving:
      wall.kind = WallKind::moving;
      wall.velocity = w.velocity;
      break;
    }
    p.walls.push_back(wall);
  }
  p.periodic = scene.domain.periodic; // their sides are open above: no wall there
  p.petsc = f.petsc;
  if (f.inextensibility)
  {
    const scene::Inextensibility& in = *f.inextensibility;
    p.inextensibility.enabled = true;
    p.inextensibility.xi = in.xi;
    p.inextensibility.epsilon = scene.numerics.epsilon;
    p.inextensibility.global_area = in.global_area;
    p.inextensibility.xi2 = in.concentration ? in.concentration->penalty : 0.0;
  }
  return p;
}

} // namespace cellphase
