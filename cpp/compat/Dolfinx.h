// The DOLFINx 0.5.2 calls whose signatures changed in later versions (xtensor callbacks,
// create_form, refinement, point location) live behind these few functions, so that a
// port to a newer DOLFINx touches this folder only.
#pragma once
#include "scene/Scene.h"
#include <dolfinx.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/petsc.h>
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace cellphase
{
using T = PetscScalar;
using Mesh = dolfinx::mesh::Mesh;
using Space = dolfinx::fem::FunctionSpace;
using Function = dolfinx::fem::Function<T>;
using Form = dolfinx::fem::Form<T>;
using Constant = dolfinx::fem::Constant<T>;
using DirichletBC = dolfinx::fem::DirichletBC<T>;
using BCs = std::vector<std::shared_ptr<const DirichletBC>>;
using CoefficientMap = std::map<std::string, std::shared_ptr<const Function>>;
using ConstantMap = std::map<std::string, std::shared_ptr<const Constant>>;
using ufcx_space_fn = ufcx_function_space* (*)(const char*);

/// A scalar field given by a formula of the position.
using PointFunction = std::function<double(double x, double y, double z)>;
/// A vector field given by a formula of the position (components beyond the dimension unused).
using VectorPointFunction = std::function<std::array<double, 3>(double x, double y, double z)>;
/// A test of the position (markers of facets and dofs).
using PointMarker = std::function<bool(double x, double y, double z)>;
/// Evaluates a scalar field at N points (coordinates as N rows of 3) into N values.
using PointEvaluator = std::function<void(std::span<const double> points, std::span<double> values)>;
} // namespace cellphase

namespace cellphase::compat
{
/// Structured base mesh of the scene's rectangle/box (crossed diagonals in 2D for isotropy),
/// or the mesh of domain.mesh. Not ghosted: all refinements stay on the rank of their base cell.
std::shared_ptr<Mesh> create_base_mesh(MPI_Comm comm, const scene::Domain& domain);

/// 2D mesh of first-order triangles from node coordinates (3 per node, z unused) and cells
/// (3 node numbers each) given on rank 0 (the other ranks pass empty lists), partitioned
/// over the ranks, not ghosted.
std::shared_ptr<Mesh> create_triangle_mesh(MPI_Comm comm, std::span<const double> points,
                                           std::span<const std::int64_t> cells);

/// Owned exterior facets whose midpoint satisfies `on`.
std::vector<std::int32_t> boundary_facets_by_midpoint(const Mesh& mesh, const PointMarker& on);

/// Refine the given local cells (and what conformity needs) without redistributing.
std::shared_ptr<Mesh> refine_cells(Mesh& mesh, const std::vector<std::int32_t>& cells);

/// Split every cell once (the P2 nodes of mesh become the vertices of the result).
std::shared_ptr<Mesh> refine_uniform(const Mesh& mesh);

/// Function space created from an FFCx form's function space table.
std::shared_ptr<Space> create_space(ufcx_space_fn fn, const std::string& name,
                                    std::shared_ptr<const Mesh> mesh);

/// Form bound to spaces, coefficients and constants by name (extra names are ignored).
std::shared_ptr<Form> create_form(const ufcx_form& form,
                                  const std::vector<std::shared_ptr<const Space>>& spaces,
                                  const CoefficientMap& coefficients, const ConstantMap& constants,
                                  std::shared_ptr<const Mesh> mesh = nullptr);

/// The same form (kernels, coefficients, constants) integrated over the given owned cells
/// only, in increasing order as the whole-mesh assembly visits them: where the form is
/// exactly zero outside them, the result is the whole-mesh one bit for bit. Cell integrals
/// only (throws std::invalid_argument otherwise).
std::shared_ptr<Form> restrict_to_cells(const Form& form, std::vector<std::int32_t> cells);

/// Global value of a rank-0 form.
double assemble_scalar(const Form& form);

/// u <- f at u's interpolation points.
void interpolate(Function& u, const PointFunction& f);

/// u <- f at u's interpolation points, for a vector-valued u (blocked space).
void interpolate_vector(Function& u, const VectorPointFunction& f);

/// Point evaluator of a function on its mesh. Points must lie in cells of the local part
/// of the mesh, which holds for meshes refined from the same base mesh without
/// redistribution; points just outside (round-off) use the closest cell.
PointEvaluator make_evaluator(std::shared_ptr<const Function> u);

/// to <- from, evaluating `from` at the interpolation points of `to` (meshes may differ);
/// scalar or vector fields (same value size).
void transfer(std::shared_ptr<const Function> from, Function& to);

/// The same for many fields from one mesh to one space (a remesh moves every field of a
/// space at once): the interpolation points are computed and located in the old mesh once.
class MeshTransfer
{
public:
  MeshTransfer(std::shared_ptr<const Mesh> from_mesh, std::shared_ptr<const Space> to_space);
  /// to <- from; from lives on from_mesh, to in to_space.
  void apply(const Function& from, Function& to) const;

private:
  std::shared_ptr<const Mesh> from_mesh_;
  std::shared_ptr<const Space> to_space_;
  std::vector<std::int32_t> cells_, from_cells_;
  std::vector<double> points_; ///< N rows of 3
};

/// Dofs of sub-space `sub` of the mixed space W on the domain boundary, as the pair
/// (dofs in W, dofs in the collapsed sub-space V).
std::array<std::vector<std::int32_t>, 2> boundary_dofs(const Space& W, int sub, const Space& V);

/// Dofs of a (non-mixed) space on the domain boundary.
std::vector<std::int32_t> boundary_dofs(const Space& V);

/// The same on the given boundary facets only (e.g. the non-periodic sides).
std::array<std::vector<std::int32_t>, 2> boundary_dofs(const Space& W, int sub, const Space& V,
                                                       const std::vector<std::int32_t>& facets);
std::vector<std::int32_t> boundary_dofs(const Space& V, const std::vector<std::int32_t>& facets);

/// Sub-space of a mixed space (component path such as {0} or {0, 1}), its collapsed copy
/// and the map from the collapsed space's local dofs (unrolled) to the mixed space's.
struct CollapsedSpace
{
  std::shared_ptr<const Space> sub;
  std::shared_ptr<Space> space;
  std::vector<std::int32_t> to_parent;
};
CollapsedSpace collapse(const Space& W, const std::vector<int>& component);

/// For a space V and a sub-space `sub` of a mixed space whose element is V's: the sub's dof
/// of every local dof of V (owned and ghost), matched through the cell-local dof order;
/// for a vector V, per component (the index of x()'s array, block * bs + component).
std::vector<std::int32_t> dofs_in_sub_space(const Space& V, const Space& sub);

/// Boundary facets all of whose vertices satisfy `on`.
std::vector<std::int32_t> boundary_facets(const Mesh& mesh, const PointMarker& on);

/// Dofs of a collapsed sub-space on the given facets, as (dofs in W, dofs in the copy).
std::array<std::vector<std::int32_t>, 2> facet_dofs(const CollapsedSpace& s,
                                                    const std::vector<std::int32_t>& facets);

/// Dofs of a collapsed sub-space whose nodes satisfy `at`, as (dofs in W, dofs in the copy).
std::array<std::vector<std::int32_t>, 2> dofs_at(const CollapsedSpace& s, const PointMarker& at);

/// Lower and upper corner of the axis-aligned bounding box of the whole (distributed) mesh.
std::array<std::array<double, 3>, 2> bounding_box(const Mesh& mesh);

/// Coordinates (N x 3) of the vertices of each local cell, cell after cell.
std::vector<double> cell_vertex_coordinates(const Mesh& mesh, std::int32_t cell);

/// Mean of a local cell's vertices (the same bits on any number of ranks).
std::array<double, 3> cell_centroid(const Mesh& mesh, std::int32_t cell);

/// Number of locally owned cells.
std::int32_t num_owned_cells(const Mesh& mesh);
/// Global number of cells / degrees of freedom.
std::int64_t num_global_cells(const Mesh& mesh);
std::int64_t num_global_dofs(const Space& V);
} // namespace cellphase::compat
