#include "core/ExtrapolationEstimate.h"
#include "core/Bdf2.h"
#include <algorithm>
#include <cmath>

namespace cellphase
{
void ExtrapolationEstimate::declare(FieldRegistry& registry) const
{
  for (const auto& name : fields_)
  {
    FieldInfo info = registry.info(name);
    info.name = name + "_prev";
    info.label = info.label + "_prev";
    info.level_set = false;
    info.history = true; // moves as its field does, never shapes the mesh
    registry.declare(info);
  }
}

void ExtrapolationEstimate::attach(FieldRegistry& registry)
{
  now_.clear();
  prev_.clear();
  for (const auto& name : fields_)
  {
    auto u = registry.get(name);
    auto V = std::const_pointer_cast<Space>(u->function_space());
    bool fresh = false;
    auto p = registry.take(name + "_prev", V, fresh);
    if (fresh) // a new run: no u^{n-1} until the first step is done
      have_ = false;
    now_.push_back(u);
    prev_.push_back(p);
  }
}

void ExtrapolationEstimate::begin_step()
{
  before_.resize(now_.size());
  for (std::size_t i = 0; i < now_.size(); ++i)
  {
    auto x = now_[i]->x()->array();
    before_[i].assign(x.begin(), x.end());
  }
}

double ExtrapolationEstimate::end_step(double dt, MPI_Comm comm)
{
  // Per field: the largest |u^{n+1} - u*| and |u^{n+1}| over the owned dofs.
  std::vector<double> largest(2 * now_.size(), 0.0);
  const double w = have_ ? dt / dt_prev_ : 0;
  for (std::size_t i = 0; i < now_.size(); ++i)
  {
    auto space = now_[i]->function_space();
    const auto& map = space->dofmap()->index_map;
    const std::size_t owned = std::size_t(map->size_local()) * space->dofmap()->index_map_bs();
    auto now = now_[i]->x()->array();
    auto prev = prev_[i]->x()->mutable_array();
    for (std::size_t d = 0; d < owned; ++d)
    {
      const double extrapolated = extrapolate(before_[i][d], prev[d], w);
      largest[2 * i] = std::max(largest[2 * i], std::abs(now[d] - extrapolated));
      largest[2 * i + 1] = std::max(largest[2 * i + 1], std::abs(now[d]));
    }
    // u^{n-1} <- u^n, ghosts included (a remesh evaluates _prev in every local cell)
    std::copy(before_[i].begin(), before_[i].end(), prev.begin());
  }
  MPI_Allreduce(MPI_IN_PLACE, largest.data(), int(largest.size()), MPI_DOUBLE, MPI_MAX, comm);
  double estimate = -1;
  if (have_)
    for (std::size_t i = 0; i < now_.size(); ++i)
      estimate = std::max(estimate, largest[2 * i] / std::max(1.0, largest[2 * i + 1]) * dt
                                        / (dt + dt_prev_));
  have_ = true;
  dt_prev_ = dt;
  return estimate;
}

void ExtrapolationEstimate::save(CheckpointData& data, const std::string& prefix) const
{
  data.set(prefix + "estimate.have", have_ ? 1.0 : 0.0);
  data.set(prefix + "estimate.dt_prev", dt_prev_);
}

void ExtrapolationEstimate::restore(const CheckpointData& data, const std::string& prefix)
{
  have_ = data.scalar(prefix + "estimate.have") != 0;
  dt_prev_ = data.scalar(prefix + "estimate.dt_prev");
}
} // namespace cellphase
