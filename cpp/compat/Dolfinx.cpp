#include "compat/Dolfinx.h"
#include "compat/PointLocator.h"
#include "scene/MeshDomain.h"
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <dolfinx/geometry/utils.h>
#include <dolfinx/refinement/refine.h>
#include <limits>
#include <numeric>
#include <xtensor/xarray.hpp>

namespace cellphase::compat
{
using namespace dolfinx;

std::shared_ptr<Mesh> create_base_mesh(MPI_Comm comm, const scene::Domain& d)
{
  if (d.mesh)
  {
    // Every rank has read the file; rank 0 gives it to the partitioner.
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    const auto& m = d.mesh->data();
    return rank == 0 ? create_triangle_mesh(comm, m.points, m.cells)
                     : create_triangle_mesh(comm, {}, {});
  }
  const auto& lo = d.lower;
  const auto& up = d.upper;
  const auto& n = d.resolution;
  if (d.dim == 2)
    return std::make_shared<Mesh>(mesh::create_rectangle(
        comm, {{{lo[0], lo[1]}, {up[0], up[1]}}},
        {std::size_t(n[0]), std::size_t(n[1])}, mesh::CellType::triangle,
        mesh::GhostMode::none, mesh::DiagonalType::crossed));
  return std::make_shared<Mesh>(mesh::create_box(
      comm, {{{lo[0], lo[1], lo[2]}, {up[0], up[1], up[2]}}},
      {std::size_t(n[0]), std::size_t(n[1]), std::size_t(n[2])}, mesh::CellType::tetrahedron,
      mesh::GhostMode::none));
}

std::shared_ptr<Mesh> create_triangle_mesh(MPI_Comm comm, std::span<const double> points,
                                           std::span<const std::int64_t> cells)
{
  const std::size_t n = points.size() / 3;
  std::vector<double> xy(2 * n);
  for (std::size_t i = 0; i < n; ++i)
    xy[2 * i] = points[3 * i], xy[2 * i + 1] = points[3 * i + 1];
  std::vector<std::int64_t> c(cells.begin(), cells.end());
  std::vector<std::int32_t> offsets(c.size() / 3 + 1);
  for (std::size_t i = 0; i < offsets.size(); ++i)
    offsets[i] = std::int32_t(3 * i);
  graph::AdjacencyList<std::int64_t> adjacency(std::move(c), std::move(offsets));
  const fem::CoordinateElement element(mesh::CellType::triangle, 1);
  return std::make_shared<Mesh>(
      mesh::create_mesh(comm, adjacency, element, xy, {n, 2}, mesh::GhostMode::none));
}

std::vector<std::int32_t> boundary_facets_by_midpoint(const Mesh& m, const PointMarker& on)
{
  const int tdim = m.topology().dim();
  auto& topology = const_cast<Mesh&>(m).topology_mutable();
  topology.create_entities(tdim - 1);
  topology.create_connectivity(tdim - 1, tdim);
  topology.create_connectivity(tdim, tdim - 1); // for the facets' geometry nodes
  const auto facets = mesh::exterior_facet_indices(m.topology());
  const auto mid = mesh::compute_midpoints(m, tdim - 1, facets);
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < facets.size(); ++i)
    if (on(mid[3 * i], mid[3 * i + 1], mid[3 * i + 2]))
      out.push_back(facets[i]);
  return out;
}

std::shared_ptr<Mesh> refine_cells(Mesh& m, const std::vector<std::int32_t>& cells)
{
  const int tdim = m.topology().dim();
  m.topology_mutable().create_entities(1);
  m.topology_mutable().create_connectivity(tdim, 1);
  auto edges = mesh::compute_incident_entities(m, std::span<const std::int32_t>(cells), tdim, 1);
  // No redistribution: children stay with their parent's rank, so that point evaluation
  // between two refinements of the same base mesh stays rank-local.
  return std::make_shared<Mesh>(refinement::refine(m, std::span<const std::int32_t>(edges), false));
}

std::shared_ptr<Mesh> refine_uniform(const Mesh& m)
{
  return std::make_shared<Mesh>(refinement::refine(m, false));
}

std::shared_ptr<Space> create_space(ufcx_space_fn fn, const std::string& name,
                                    std::shared_ptr<const Mesh> mesh)
{
  // 0.5.2 wants a mutable mesh here although it only reads it.
  return std::make_shared<Space>(
      fem::create_functionspace(fn, name, std::const_pointer_cast<Mesh>(mesh)));
}

std::shared_ptr<Form> create_form(const ufcx_form& form,
                                  const std::vector<std::shared_ptr<const Space>>& spaces,
                                  const CoefficientMap& coefficients, const ConstantMap& constants,
                                  std::shared_ptr<const Mesh> mesh)
{
  // Names the form does not use are ignored; a missing name throws, naming it.
  const std::map<fem::IntegralType, const mesh::MeshTags<int>*> subdomains;
  return std::make_shared<Form>(
      fem::create_form<T>(form, spaces, coefficients, constants, subdomains, mesh));
}

std::shared_ptr<Form> restrict_to_cells(const Form& form, std::vector<std::int32_t> cells)
{
  using fem::IntegralType;
  if (form.num_integrals(IntegralType::exterior_facet) > 0
      || form.num_integrals(IntegralType::interior_facet) > 0)
    throw std::invalid_argument("restrict_to_cells: the form has facet integrals");
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  // Every cell integral under one tag (0) that marks the cells; 0.5.2 gives the default
  // integral (-1) all owned cells, so the kernels are re-registered under the tag.
  std::vector<int> tags(cells.size(), 0);
  const mesh::MeshTags<int> marked(form.mesh(), form.mesh()->topology().dim(), std::move(cells),
                                   std::move(tags));
  using Kernel = std::function<void(T*, const T*, const T*, const double*, const int*,
                                    const std::uint8_t*)>;
  std::vector<std::pair<int, Kernel>> kernels;
  for (int i = 0; i < form.num_integrals(IntegralType::cell); ++i)
    kernels.emplace_back(0, form.kernel(IntegralType::cell, form.integral_ids(IntegralType::cell)[i]));
  if (kernels.size() != 1)
    throw std::invalid_argument("restrict_to_cells: the form needs exactly one cell integral");
  const std::map<IntegralType, std::pair<std::vector<std::pair<int, Kernel>>,
                                         const mesh::MeshTags<int>*>>
      integrals{{IntegralType::cell, {kernels, &marked}}};
  return std::make_shared<Form>(form.function_spaces(), integrals, form.coefficients(),
                                form.constants(), form.needs_facet_permutations(), form.mesh());
}

double assemble_scalar(const Form& form)
{
  T local = fem::assemble_scalar(form), global = 0;
  MPI_Allreduce(&local, &global, 1, MPIU_SCALAR, MPI_SUM, form.mesh()->comm());
  return global;
}

void interpolate(Function& u, const PointFunction& f)
{
  u.interpolate(
      [&f](const xt::xtensor<double, 2>& x) -> xt::xarray<T>
      {
        xt::xarray<T> v = xt::empty<T>({x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
          v(i) = f(x(0, i), x(1, i), x(2, i));
        return v;
      });
}

void interpolate_vector(Function& u, const VectorPointFunction& f)
{
  // The value size, not the dofmap block size: a vector sub-function of a mixed space
  // has an unblocked dofmap.
  const std::size_t bs = u.function_space()->element()->value_size();
  u.interpolate(
      [&f, bs](const xt::xtensor<double, 2>& x) -> xt::xarray<T>
      {
        xt::xarray<T> v = xt::empty<T>({bs, x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
        {
          const auto fi = f(x(0, i), x(1, i), x(2, i));
          for (std::size_t c = 0; c < bs; ++c)
            v(c, i) = fi[c];
        }
        return v;
      });
}

namespace
{
/// A position test as the xtensor marker callback of 0.5.2 (x has 3 rows of N points).
std::function<xt::xtensor<bool, 1>(const xt::xtensor<double, 2>&)> xmarker(const PointMarker& m)
{
  return [m](const xt::xtensor<double, 2>& x)
  {
    xt::xtensor<bool, 1> on = xt::empty<bool>({x.shape(1)});
    for (std::size_t i = 0; i < x.shape(1); ++i)
      on(i) = m(x(0, i), x(1, i), x(2, i));
    return on;
  };
}
} // namespace

std::vector<std::int32_t> dofs_in_sub_space(const Space& V, const Space& sub)
{
  // Both sides unrolled by their block size: a vector V (bs = dim) and the vector
  // sub-element of a mixed space (bs 1, components interleaved per node) list a cell's
  // dofs in the same order.
  const auto& map = *V.dofmap()->index_map;
  const int bs = V.dofmap()->bs(), sub_bs = sub.dofmap()->bs();
  std::vector<std::int32_t> to(std::size_t(map.size_local() + map.num_ghosts()) * bs);
  const auto& topology = V.mesh()->topology();
  const auto& cells = *topology.index_map(topology.dim());
  const std::int32_t ncells = cells.size_local() + cells.num_ghosts();
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto vd = V.dofmap()->cell_dofs(c);
    auto wd = sub.dofmap()->cell_dofs(c);
    for (std::size_t k = 0; k < vd.size() * bs; ++k)
      to[vd[k / bs] * bs + k % bs] = wd[k / sub_bs] * sub_bs + std::int32_t(k % sub_bs);
  }
  return to;
}

CollapsedSpace collapse(const Space& W, const std::vector<int>& component)
{
  CollapsedSpace s;
  // One level at a time: 0.5.2 cannot extract a path such as {0, 2} from the root at once.
  std::shared_ptr<const Space> sub = W.sub({component[0]});
  for (std::size_t i = 1; i < component.size(); ++i)
    sub = sub->sub({component[i]});
  s.sub = sub;
  auto [V, map] = s.sub->collapse();
  s.space = std::make_shared<Space>(std::move(V));
  s.to_parent = std::move(map);
  return s;
}

std::vector<std::int32_t> boundary_facets(const Mesh& m, const PointMarker& on)
{
  const int tdim = m.topology().dim();
  auto& topology = const_cast<Mesh&>(m).topology_mutable();
  topology.create_connectivity(tdim - 1, tdim);
  return mesh::locate_entities_boundary(m, tdim - 1, xmarker(on));
}

std::array<std::vector<std::int32_t>, 2> facet_dofs(const CollapsedSpace& s,
                                                    const std::vector<std::int32_t>& facets)
{
  const int tdim = s.space->mesh()->topology().dim();
  return fem::locate_dofs_topological({*s.sub, *s.space}, tdim - 1,
                                      std::span<const std::int32_t>(facets));
}

std::array<std::vector<std::int32_t>, 2> dofs_at(const CollapsedSpace& s, const PointMarker& at)
{
  return fem::locate_dofs_geometrical({*s.sub, *s.space}, xmarker(at));
}

std::array<std::array<double, 3>, 2> bounding_box(const Mesh& m)
{
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::max());
  hi.fill(std::numeric_limits<double>::lowest());
  auto x = m.geometry().x();
  for (std::size_t i = 0; i < x.size(); i += 3)
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], x[i + d]);
      hi[d] = std::max(hi[d], x[i + d]);
    }
  MPI_Allreduce(MPI_IN_PLACE, lo.data(), 3, MPI_DOUBLE, MPI_MIN, m.comm());
  MPI_Allreduce(MPI_IN_PLACE, hi.data(), 3, MPI_DOUBLE, MPI_MAX, m.comm());
  return {lo, hi};
}


using detail::all_local_cells;
using detail::PointLocator;

PointEvaluator make_evaluator(std::shared_ptr<const Function> u)
{
  auto locator = std::make_shared<PointLocator>(u->function_space()->mesh());
  return [u, locator](std::span<const double> pts, std::span<double> values)
  {
    const std::size_t n = pts.size() / 3;
    auto cells = locator->locate(pts);
    u->eval(pts, {n, 3}, cells, values, {n, 1});
  };
}

void transfer(std::shared_ptr<const Function> from, Function& to)
{
  MeshTransfer(from->function_space()->mesh(), to.function_space()).apply(*from, to);
}

MeshTransfer::MeshTransfer(std::shared_ptr<const Mesh> from_mesh,
                           std::shared_ptr<const Space> to_space)
    : from_mesh_(from_mesh), to_space_(to_space), cells_(all_local_cells(*to_space->mesh()))
{
  // interpolation_coords returns 3 rows (x, y, z) of N points; eval wants N rows of 3.
  const std::vector<double> X
      = fem::interpolation_coords(*to_space->element(), *to_space->mesh(), cells_);
  const std::size_t n = X.size() / 3;
  points_.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      points_[3 * i + d] = X[d * n + i];
  from_cells_ = PointLocator(from_mesh).locate(points_);
}

void MeshTransfer::apply(const Function& from, Function& to) const
{
  if (from.function_space()->mesh() != from_mesh_ || to.function_space() != to_space_)
    throw std::invalid_argument("MeshTransfer: the fields are not on its mesh and space");
  // Scalar or vector (blocked) fields: vs values per point.
  const std::size_t vs = to_space_->element()->value_size();
  if (std::size_t(from.function_space()->element()->value_size()) != vs)
    throw std::invalid_argument("transfer: the fields differ in value size");
  const std::size_t n = points_.size() / 3;
  std::vector<double> values(n * vs); // N rows of vs
  from.eval(points_, {n, 3}, from_cells_, values, {n, vs});
  if (vs == 1)
  {
    fem::interpolate(to, std::span<const T>(values), {1, n}, std::span<const std::int32_t>(cells_));
    return;
  }
  std::vector<double> rows(n * vs); // vs rows of N, as interpolate wants
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < vs; ++c)
      rows[c * n + i] = values[i * vs + c];
  fem::interpolate(to, std::span<const T>(rows), {vs, n}, std::span<const std::int32_t>(cells_));
}

std::array<std::vector<std::int32_t>, 2> boundary_dofs(const Space& W, int sub, const Space& V)
{
  auto m = W.mesh();
  const int tdim = m->topology().dim();
  m->topology_mutable().create_connectivity(tdim - 1, tdim);
  auto facets = mesh::exterior_facet_indices(m->topology());
  auto Wsub = W.sub({sub});
  return fem::locate_dofs_topological({*Wsub, V}, tdim - 1,
                                      std::span<const std::int32_t>(facets));
}

std::vector<std::int32_t> boundary_dofs(const Space& V)
{
  auto m = V.mesh();
  const int tdim = m->topology().dim();
  m->topology_mutable().create_connectivity(tdim - 1, tdim);
  auto facets = mesh::exterior_facet_indices(m->topology());
  return fem::locate_dofs_topological(V, tdim - 1, std::span<const std::int32_t>(facets));
}

std::array<std::vector<std::int32_t>, 2> boundary_dofs(const Space& W, int sub, const Space& V,
                                                       const std::vector<std::int32_t>& facets)
{
  const int tdim = W.mesh()->topology().dim();
  auto Wsub = W.sub({sub});
  return fem::locate_dofs_topological({*Wsub, V}, tdim - 1,
                                      std::span<const std::int32_t>(facets));
}

std::vector<std::int32_t> boundary_dofs(const Space& V, const std::vector<std::int32_t>& facets)
{
  const int tdim = V.mesh()->topology().dim();
  return fem::locate_dofs_topological(V, tdim - 1, std::span<const std::int32_t>(facets));
}

std::vector<double> cell_vertex_coordinates(const Mesh& m, std::int32_t cell)
{
  const auto& dofmap = m.geometry().dofmap();
  auto x = m.geometry().x();
  std::vector<double> out;
  for (auto node : dofmap.links(cell))
    out.insert(out.end(), x.begin() + 3 * node, x.begin() + 3 * node + 3);
  return out;
}

std::array<double, 3> cell_centroid(const Mesh& m, std::int32_t cell)
{
  const auto v = cell_vertex_coordinates(m, cell);
  const std::size_t nv = v.size() / 3;
  std::array<double, 3> c{0, 0, 0};
  for (std::size_t i = 0; i < nv; ++i)
    for (int d = 0; d < 3; ++d)
      c[d] += v[3 * i + d] / double(nv);
  return c;
}

std::int32_t num_owned_cells(const Mesh& m)
{
  return m.topology().index_map(m.topology().dim())->size_local();
}

std::int64_t num_global_cells(const Mesh& m)
{
  return m.topology().index_map(m.topology().dim())->size_global();
}

std::int64_t num_global_dofs(const Space& V)
{
  return V.dofmap()->index_map->size_global() * V.dofmap()->index_map_bs();
}
} // namespace cellphase::compat
