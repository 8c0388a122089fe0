#include "mesh/OwnMesh.h"
#include "compat/PeriodicImages.h"
#include "scene/Resolution.h"
#include <algorithm>
#include <cmath>
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
  // A patch reaching across a periodic side is wrapped (compat::create_patch): its part
  // beyond the side lies a period up, where the cell goes on. Its lower end is brought
  // into [lower, upper) first. A patch may end on a side: the side is then one of its
  // cut edges. Only a patch nearly as long as the period gets the whole domain.
  const auto& d = scene_.domain;
  const double h = scene::base_cell_size(d);
  for (int a : d.periodic)
  {
    const double L = d.upper[a] - d.lower[a];
    if (box_[3 + a] - box_[a] > L - 4 * h) // a wrapped patch's two parts at least 2 cells apart
    {
      for (int b = 0; b < 3; ++b)
      {
        box_[b] = std::min(box_[b], d.lower[b] - margin_);
        box_[3 + b] = std::max(box_[3 + b], d.upper[b] + margin_);
      }
      break;
    }
    const double periods_below = std::floor((box_[a] - d.lower[a]) / L);
    box_[a] -= periods_below * L, box_[3 + a] -= periods_below * L;
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

namespace
{
/// The box of the nodes where f > level along periodic axis a on a mesh that spans the
/// whole period, where they may lie on both sides of the periodic side: the complement of
/// the longest stretch of the axis without such nodes (in bins of 1/1024 of the period,
/// rounded outwards). Its upper end may lie beyond the side. Collective.
compat::Box box_across_side(const Function& f, double level, int a, compat::Box box)
{
  const double L = compat::periods()[a];
  const auto [mesh_lo, mesh_hi] = compat::bounding_box(*f.function_space()->mesh());
  constexpr int bins = 1024;
  const double width = L / bins;
  std::vector<int> occupied(bins, 0);
  auto x = f.function_space()->tabulate_dof_coordinates(false);
  auto values = f.x()->array();
  const std::size_t owned = f.function_space()->dofmap()->index_map->size_local();
  for (std::size_t i = 0; i < owned; ++i)
    if (values[i] > level)
      occupied[std::clamp(int((x[3 * i + a] - mesh_lo[a]) / width), 0, bins - 1)] = 1;
  MPI_Allreduce(MPI_IN_PLACE, occupied.data(), bins, MPI_INT, MPI_MAX,
                f.function_space()->mesh()->comm());
  // The longest circular run of empty bins: the band is the rest.
  int best_start = -1, best_length = 0;
  for (int start = 0; start < bins; ++start)
  {
    if (occupied[start] || occupied[(start + bins - 1) % bins] == 0)
      continue; // not the start of an empty run
    int length = 0;
    while (length < bins && !occupied[(start + length) % bins])
      ++length;
    if (length > best_length)
      best_start = start, best_length = length;
  }
  if (best_start < 0)
    return box; // no empty bin, or none occupied: the plain box
  const int first = (best_start + best_length) % bins; // first occupied bin after the gap
  box[a] = mesh_lo[a] + first * width;
  box[3 + a] = box[a] + (bins - best_length) * width;
  return box;
}
} // namespace

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
  for (int a = 0; a < 3; ++a)
    if (const double L = compat::periods()[a]; L > 0 && box[3 + a] - box[a] > L / 2)
      box = box_across_side(f, level, a, box);
  return box;
}

bool covers_domain(const compat::Box& box, const scene::Domain& d)
{
  for (int a = 0; a < d.dim; ++a)
    if (box[a] > d.lower[a] || box[3 + a] < d.upper[a])
      return false;
  return true;
}

compat::Box image_near(const compat::Box& box, const compat::Box& near, const scene::Domain& d)
{
  compat::Box moved = box;
  for (int a : d.periodic)
  {
    // Whole periods that bring the centres closest.
    const double L = d.upper[a] - d.lower[a];
    const double offset = (near[a] + near[3 + a] - box[a] - box[3 + a]) / 2;
    if (!std::isfinite(offset))
      continue; // an empty box
    const double k = std::round(offset / L);
    moved[a] += k * L, moved[3 + a] += k * L;
  }
  return moved;
}
} // namespace cellphase
