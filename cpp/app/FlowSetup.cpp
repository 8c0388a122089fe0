#include "app/FlowSetup.h"
#include "mesh/BoundaryTags.h"
#include "scene/Formula.h"
#include "scene/MeshDomain.h"
#include "scene/Plan.h"
#include <algorithm>

namespace cellphase
{
namespace
{
/// The module's wall for a scene wall that is not open.
Wall wall_of(const scene::WallSpec& w, int dim)
{
  Wall wall;
  switch (w.type)
  {
  case scene::WallType::open: break; // callers skip open walls
  case scene::WallType::no_slip: wall.kind = WallKind::no_slip; break;
  case scene::WallType::free_slip: wall.kind = WallKind::free_slip; break;
  case scene::WallType::moving:
    wall.kind = WallKind::moving;
    wall.velocity = w.velocity;
    break;
  case scene::WallType::prescribed:
    wall.kind = WallKind::prescribed;
    wall.profile = scene::VectorFormula(w.profile, dim);
    break;
  }
  return wall;
}

/// Walls of a mesh-file domain, one per tag (unlisted tags and the untagged boundary are
/// no_slip), and the pressure pin if no part of the boundary is open.
void tag_walls(const scene::Scene& scene, FlowParameters& p)
{
  const auto mesh = scene.domain.mesh;
  p.tagged_walls = true;
  bool closed = true;
  auto add = [&](const scene::WallSpec& w, int tag)
  {
    if (w.type == scene::WallType::open)
    {
      closed = false;
      return;
    }
    Wall wall = wall_of(w, 2);
    wall.facets = [mesh, tag](const Mesh& m) { return tagged_facets(m, *mesh, {tag}); };
    wall.normal_axis = mesh->normal_axis({tag});
    p.walls.push_back(wall);
  };
  for (const std::string& name : mesh->tag_names())
  {
    const auto it = scene.flow->tag_walls.find(name);
    add(it != scene.flow->tag_walls.end() ? it->second : scene::WallSpec{}, mesh->tag(name));
  }
  if (mesh->tag_length(scene::MeshDomain::untagged) > 0)
    add(scene::WallSpec{}, scene::MeshDomain::untagged);
  if (closed)
  {
    // A closed boundary fixes the pressure up to a constant: pin it at the lowest
    // boundary vertex (lexicographic in y, x; the same on every rank).
    std::array<double, 2> pin = mesh->boundary().front().a;
    for (const auto& e : mesh->boundary())
      for (const auto& q : {e.a, e.b})
        if (std::tie(q[1], q[0]) < std::tie(pin[1], pin[0]))
          pin = q;
    p.pressure_pin = std::array<double, 3>{pin[0], pin[1], 0};
  }
}
} // namespace

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
  for (int i = 0; i < 2 * scene.domain.dim && !scene.domain.mesh; ++i)
  {
    const scene::WallSpec& w = f.walls[i];
    if (w.type == scene::WallType::open)
      continue; // traction-free: no condition
    Wall wall = wall_of(w, scene.domain.dim);
    wall.side = Side(i);
    p.walls.push_back(wall);
  }
  if (scene.domain.mesh)
    tag_walls(scene, p);
  p.periodic = scene.domain.periodic; // their sides are open above: no wall there
  p.petsc = f.petsc;
  p.reuse_factorisations = scene::flow_solver(scene) == scene::Numerics::Solver::reuse;
  p.second_order = !scene::flow_history_fields(scene).empty();
  p.extrapolate_phase = scene.numerics.coupling == scene::Numerics::Coupling::extrapolated;
  p.extrapolate_potential = scene::flow_extrapolates_potential(scene);
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
