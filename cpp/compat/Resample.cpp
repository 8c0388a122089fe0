#include "compat/Resample.h"
#include "compat/PointLocator.h"
#include "compat/PointWeights.h"
#include "compat/RemotePoints.h"
#include <dolfinx/fem/interpolate.h>
#include <dolfinx/la/Vector.h>
#include <functional>

namespace cellphase::compat
{
using namespace dolfinx;
using detail::PointLocator;
using detail::RemotePoints;

namespace
{
/// One locator per live mesh: the shared mesh serves every cell's transfers, and its trees
/// are built once per remesh instead of once per cell.
std::shared_ptr<const PointLocator> locator_of(std::shared_ptr<const Mesh> mesh)
{
  static std::vector<std::pair<std::weak_ptr<const Mesh>, std::shared_ptr<const PointLocator>>> cache;
  std::erase_if(cache, [](const auto& e) { return e.first.expired(); });
  for (const auto& [m, locator] : cache)
    if (m.lock() == mesh)
      return locator;
  cache.emplace_back(mesh, std::make_shared<const PointLocator>(mesh));
  return cache.back().second;
}
} // namespace

PointEvaluator make_evaluator(std::shared_ptr<const Function> u, double outside)
{
  auto locator = locator_of(u->function_space()->mesh());
  return [u, locator, outside](std::span<const double> given, std::span<double> values)
  {
    const std::size_t n = given.size() / 3;
    std::vector<double> moved;
    std::span<const double> pts = given;
    if (any_periodic()) // points beyond a periodic side: their images in u's mesh
    {
      moved.assign(given.begin(), given.end());
      locator->move_into_mesh(moved);
      pts = moved;
    }
    auto cells = locator->locate(pts, true);
    u->eval(pts, {n, 3}, cells, values, {n, 1}); // leaves the values of cells -1 untouched
    for (std::size_t i = 0; i < n; ++i)
      if (cells[i] < 0)
        values[i] = outside;
    if (dolfinx::MPI::size(u->function_space()->mesh()->comm()) > 1)
      RemotePoints(u->function_space()->mesh(), *locator, pts, cells).fill(*u, values);
  };
}

Resampler::Resampler(std::shared_ptr<const Function> from, std::shared_ptr<Function> to,
                     std::vector<std::int32_t> cells, double outside)
    : from_(from), to_(to), cells_(std::move(cells)), outside_(outside)
{
  auto V = to->function_space();
  value_size_ = V->element()->value_size();
  if (from->function_space()->element()->value_size() != value_size_)
    throw std::invalid_argument("Resampler: the fields differ in value size");
  // interpolation_coords returns 3 rows (x, y, z) of N points; eval wants N rows of 3.
  const std::vector<double> X = fem::interpolation_coords(*V->element(), *V->mesh(), cells_);
  const std::size_t n = X.size() / 3;
  points_.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      points_[3 * i + d] = X[d * n + i];
  auto from_mesh = from->function_space()->mesh();
  auto locator = locator_of(from_mesh);
  locator->move_into_mesh(points_);
  from_cells_ = locator->locate(points_, true);
  if (PointWeights::applicable(*from->function_space()))
    weights_ = std::make_shared<const PointWeights>(*from->function_space(), points_, from_cells_);
  if (dolfinx::MPI::size(from_mesh->comm()) > 1)
    remote_ = std::make_shared<const RemotePoints>(from_mesh, *locator, points_, from_cells_);

  // The dofs that the cells write here and, on several ranks, anywhere: a dof on a rank
  // boundary may be written by the cells of one rank only (a patch's edge along it).
  const auto& dofmap = *V->dofmap();
  auto map = dofmap.index_map;
  written_here_.assign(map->size_local() + map->num_ghosts(), 0);
  for (std::int32_t c : cells_)
    for (std::int32_t d : dofmap.cell_dofs(c))
      written_here_[d] = 1;
  written_anywhere_ = written_here_;
  if (dolfinx::MPI::size(map->comm()) > 1)
  {
    writes_ = std::make_shared<la::Vector<T>>(map, dofmap.index_map_bs());
    writers_ = std::make_shared<la::Vector<T>>(map, 1);
    auto n = writers_->mutable_array();
    std::copy(written_here_.begin(), written_here_.end(), n.begin());
    writers_->scatter_rev(std::plus<T>());
    writers_->scatter_fwd();
    for (std::size_t d = 0; d < n.size(); ++d)
      written_anywhere_[d] = n[d] > 0;
  }
}

void Resampler::apply() { apply(*from_, *to_, outside_); }

void Resampler::apply(const Function& from, Function& to, double outside) const
{
  if (from.function_space()->mesh() != from_->function_space()->mesh()
      || to.function_space() != to_->function_space())
    throw std::invalid_argument("Resampler: the fields are not on its meshes and spaces");
  const std::size_t n = points_.size() / 3, vs = value_size_;
  std::vector<double> values(n * vs, outside); // N rows of vs
  if (weights_ && weights_->fits(from))
    weights_->eval(from, values);
  else
    from.eval(points_, {n, 3}, from_cells_, values, {n, vs});
  for (std::size_t i = 0; i < n; ++i)
    if (from_cells_[i] < 0)
      for (std::size_t c = 0; c < vs; ++c)
        values[i * vs + c] = outside;
  if (remote_)
    remote_->fill(from, values);
  std::vector<double> rows(n * vs); // vs rows of N, as interpolate wants
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < vs; ++c)
      rows[c * n + i] = values[i * vs + c];
  fem::interpolate(to, std::span<const T>(rows), {vs, n}, std::span<const std::int32_t>(cells_));
  if (writes_)
    share_writes(to);
}

void Resampler::share_writes(Function& to) const
{
  // Owners take the values that only other ranks wrote (a patch's edge on a rank boundary),
  // keep their own, and pass theirs to the ghosts: every copy of a dof is the same, as on
  // one rank.
  const int bs = to.function_space()->dofmap()->index_map_bs();
  auto x = to.x()->mutable_array();
  auto sum = writes_->mutable_array();
  auto n = writers_->mutable_array();
  for (std::size_t d = 0; d < written_here_.size(); ++d)
  {
    n[d] = written_here_[d];
    for (int k = 0; k < bs; ++k)
      sum[d * bs + k] = written_here_[d] ? x[d * bs + k] : 0.0;
  }
  writes_->scatter_rev(std::plus<T>());
  writers_->scatter_rev(std::plus<T>());
  const std::int32_t owned = to.function_space()->dofmap()->index_map->size_local();
  for (std::int32_t d = 0; d < owned; ++d)
    if (!written_here_[d] && n[d] > 0)
      for (int k = 0; k < bs; ++k)
        x[d * bs + k] = sum[d * bs + k] / n[d];
  to.x()->scatter_fwd();
}

std::vector<std::int32_t> Resampler::support() const
{
  auto V = to_->function_space();
  const auto& dofmap = *V->dofmap();
  std::vector<std::int32_t> cells;
  for (std::int32_t c = 0; c < num_owned_cells(*V->mesh()); ++c)
  {
    auto dofs = dofmap.cell_dofs(c);
    if (std::any_of(dofs.begin(), dofs.end(),
                    [&](std::int32_t d) { return written_anywhere_[d] != 0; }))
      cells.push_back(c);
  }
  return cells;
}

std::vector<std::int32_t> local_cells(const Mesh& mesh) { return detail::all_local_cells(mesh); }

std::vector<std::int32_t> cells_inside(const Mesh& mesh, std::shared_ptr<const Mesh> patch)
{
  // Candidates by the patch's local bounding box (cheap), then located in the patch.
  const auto locator = locator_of(patch);
  const std::array<double, 6>& box = locator->box();
  std::vector<std::int32_t> candidates;
  std::vector<double> mid;
  for (std::int32_t c = 0; c < num_owned_cells(mesh); ++c)
  {
    const auto v = cell_vertex_coordinates(mesh, c);
    const std::size_t nv = v.size() / 3;
    std::array<double, 3> m{0, 0, 0};
    bool in_box = true;
    for (int d = 0; d < 3; ++d)
      for (std::size_t i = 0; i < nv; ++i)
        m[d] += v[3 * i + d] / double(nv);
    locator->move_into_mesh(m); // a wrapped patch's part beyond a periodic side
    for (int d = 0; d < 3; ++d)
      in_box = in_box && m[d] >= box[d] && m[d] <= box[3 + d];
    if (in_box)
    {
      candidates.push_back(c);
      mid.insert(mid.end(), m.begin(), m.end());
    }
  }
  const auto found = locator->locate(mid, true);
  std::vector<std::int32_t> inside;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (found[k] >= 0)
      inside.push_back(candidates[k]);
  return inside;
}
} // namespace cellphase::compat
