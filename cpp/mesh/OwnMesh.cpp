#include "mesh/OwnMesh.h"
#include "scene/SceneLoader.h"
#include <cstdio>
#include <limits>
#include <string>

namespace cellphase
{
OwnMesh::OwnMesh(const scene::Scene& scene, std::shared_ptr<Mesh> base)
    : scene_(scene), base_(base),
      margin_(scene.numerics.mesh.own_margin_or_default(scene.numerics.epsilon))
{
}

std::shared_ptr<Mesh> OwnMesh::build(const PointEvaluator& phi, const compat::Box& band)
{
  for (int a = 0; a < 3; ++a)
  {
    box_[a] = band[a] - margin_;
    box_[3 + a] = band[3 + a] + margin_;
  }
  const auto& d = scene_.domain;
  for (int a : d.periodic) // a patch is not wrapped around a periodic side
    if (box_[a] <= d.lower[a] || box_[3 + a] >= d.upper[a])
    {
      char text[400];
      std::snprintf(text, sizeof text,
                    "numerics.mesh.cell_meshes: own: a cell's own mesh (its band phi > -0.9 "
                    "grown by numerics.mesh.own_margin = %g) reaches the periodic side %c = %g "
                    "of the domain: own meshes do not wrap around periodic sides; move the "
                    "cell, lengthen the domain or use numerics.mesh.cell_meshes: shared",
                    margin_, char('x' + a), box_[a] <= d.lower[a] ? d.lower[a] : d.upper[a]);
      throw scene::SceneError(text);
    }
  refined_ = std::make_unique<AdaptiveMesh>(scene_, compat::create_patch(*base_, box_));
  return refined_->build(phi);
}

std::shared_ptr<Mesh> OwnMesh::replay(const compat::Box& patch_box,
                                      const std::vector<std::vector<double>>& history)
{
  box_ = patch_box;
  refined_ = std::make_unique<AdaptiveMesh>(scene_, compat::create_patch(*base_, box_));
  return refined_->replay(history);
}

compat::Box box_above(const Function& f, double level)
{
  const double inf = std::numeric_limits<double>::infinity();
  compat::Box box{inf, inf, inf, -inf, -inf, -inf};
  auto x = f.function_space()->tabulate_dof_coordinates(false);
  auto values = f.x()->array();
  const std::size_t owned = f.function_space()->dofmap()->index_map->size_local();
  for (std::size_t i = 0; i < owned; ++i)
    if (values[i] > level)
      for (int a = 0; a < 3; ++a)
      {
        box[a] = std::min(box[a], x[3 * i + a]);
        box[3 + a] = std::max(box[3 + a], x[3 * i + a]);
      }
  for (int a = 0; a < 3; ++a)
    box[3 + a] = -box[3 + a]; // one MIN reduction for both ends
  MPI_Allreduce(MPI_IN_PLACE, box.data(), 6, MPI_DOUBLE, MPI_MIN, f.function_space()->mesh()->comm());
  for (int a = 0; a < 3; ++a)
    box[3 + a] = -box[3 + a];
  return box;
}
} // namespace cellphase
