#include "mesh/BaseMesh.h"
#include "compat/Patch.h"
#include "compat/PeriodicImages.h"
#include "scene/Resolution.h"
#include <cmath>

namespace cellphase
{
double stripe_width(const scene::Scene& scene)
{
  return scene.numerics.mesh.stripe_width.value_or(2 * scene::base_cell_size(scene.domain));
}

int stripe_axis(const scene::Domain& domain)
{
  int axis = 0;
  for (int a = 1; a < domain.dim; ++a)
    if (domain.upper[a] - domain.lower[a] > domain.upper[axis] - domain.lower[axis])
      axis = a;
  return axis;
}

std::shared_ptr<Mesh> create_partitioned_base_mesh(const scene::Scene& scene, MPI_Comm comm)
{
  // The periods of the domain that all meshes from now on are built in (wrapped patches
  // and the transfers between them and the shared mesh, compat/PeriodicImages.h).
  std::array<double, 3> periods{0, 0, 0};
  for (int a : scene.domain.periodic)
    periods[a] = scene.domain.upper[a] - scene.domain.lower[a];
  compat::set_periods(periods);
  auto base = compat::create_base_mesh(comm, scene.domain);
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size == 1 || scene.numerics.mesh.partition_or_default() != scene::Mesh::Partition::stripes)
    return base;
  // Stripe k of the midpoints goes to rank k mod size.
  const int axis = stripe_axis(scene.domain);
  const double lower = scene.domain.lower[axis], width = stripe_width(scene);
  std::vector<int> dest(compat::num_owned_cells(*base));
  for (std::int32_t c = 0; c < std::int32_t(dest.size()); ++c)
  {
    const double mid = compat::cell_centroid(*base, c)[axis];
    const auto stripe = std::int64_t(std::floor((mid - lower) / width));
    dest[c] = int(((stripe % size) + size) % size);
  }
  return compat::redistribute(*base, dest);
}
} // namespace cellphase
