#include "mesh/OwnMesh.h"
#include "scene/Resolution.h"
#include <algorithm>
#include <limits>

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
  // A patch is not wrapped around a periodic side: a cell whose patch would come within
  // two base cells of one gets the whole domain (its cut box then covers the domain), where
  // it crosses the side as on the shared mesh.
  const auto& d = scene_.domain;
  const double h = scene::base_cell_size(d);
  for (int a : d.periodic)
    if (box_[a] < d.lower[a] + 2 * h || box_[3 + a] > d.upper[a] - 2 * h)
      for (int b = 0; b < 3; ++b)
      {
        box_[b] = std::min(box_[b], d.lower[b] - margin_);
        box_[3 + b] = std::max(box_[3 + b], d.upper[b] + margin_);
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

bool covers_domain(const compat::Box& box, const scene::Domain& d)
{
  for (int a = 0; a < d.dim; ++a)
    if (box[a] > d.lower[a] || box[3 + a] < d.upper[a])
      return false;
  return true;
}
} // namespace cellphase
