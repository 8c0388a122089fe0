// Cross-section checks: every cell (plus a margin) inside the domain, cells disjoint,
// and the requested interface resolution reachable within max_levels.
#include "scene/Geometry.h"
#include "scene/MeshDomain.h"
#include "scene/Resolution.h"
#include "scene/Sections.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{
using namespace yaml;

namespace
{

std::string domain_text(const Domain& d)
{
  std::string s;
  for (int a = 0; a < d.dim; ++a)
    s += (a ? " x [" : "[") + fmt(d.lower[a]) + ", " + fmt(d.upper[a]) + "]";
  if (d.mesh)
    return "of mesh " + d.mesh->path() + " (bounding box " + s + ")";
  return s;
}

/// Calls f(q) at points a distance `margin` inside the boundary of a mesh domain: along
/// each boundary edge with spacing about h, moved by margin along its inward normal.
template <typename F>
void for_each_mesh_margin_point(const MeshDomain& m, double margin, double h, F&& f)
{
  for (const auto& e : m.boundary())
  {
    const double len = std::hypot(e.b[0] - e.a[0], e.b[1] - e.a[1]);
    const int n = std::max(2, int(std::ceil(len / h)) + 1);
    for (int i = 0; i < n; ++i)
    {
      const double t = double(i) / (n - 1);
      Point q{e.a[0] + t * (e.b[0] - e.a[0]) + margin * e.n[0],
              e.a[1] + t * (e.b[1] - e.a[1]) + margin * e.n[1], 0};
      f(q);
    }
  }
}

/// Calls f(p) on the boundary of the box [lo, hi] with spacing about h (at least `min_n`
/// points per edge).
template <typename F>
void for_each_box_boundary_point(int dim, const Point& lo, const Point& hi, double h,
                                 int min_n, int max_n, F&& f)
{
  for (int a = 0; a < dim; ++a)
    for (double fixed : {lo[a], hi[a]})
    {
      // The other axes of this face (one in 2D, two in 3D).
      const int b = (a + 1) % dim, c = (a + 2) % dim;
      auto count = [&](int axis)
      { return std::clamp(int(std::ceil((hi[axis] - lo[axis]) / h)) + 1, min_n, max_n); };
      const int nb = count(b), nc = dim == 3 ? count(c) : 1;
      for (int j = 0; j < nc; ++j)
        for (int i = 0; i < nb; ++i)
        {
          Point p{0, 0, 0};
          p[a] = fixed;
          p[b] = lo[b] + (hi[b] - lo[b]) * i / (nb - 1);
          if (dim == 3)
            p[c] = nc > 1 ? lo[c] + (hi[c] - lo[c]) * j / (nc - 1) : lo[c];
          f(p);
        }
    }
}

} // namespace

void check_geometry(const Section& top, const Scene& s)
{
  const Domain& d = s.domain;
  const int dim = d.dim;
  const double margin = 3 * s.numerics.epsilon;
  // With a contact angle, drops sit on the walls: cells may touch and cross them (the
  // part outside the box is cut off). The natural condition of the phase-separation models
  // is the contact angle of 90 degrees (2.8), which the message names.
  const Model m = s.phase_field.model;
  const bool separating = m == Model::cahn_hilliard || m == Model::allen_cahn
                          || m == Model::allen_cahn_volume;
  const bool wetting = s.contact_angle_deg.has_value();
  const std::vector<Section> cell_sections = top.list_of_sections("cells");
  auto cell_fail = [&](std::size_t i, const std::string& problem)
  { cell_sections[i].relabel(cell_label(i, s.cells[i])).fail(problem); };
  auto outside = [&](std::size_t i, const Point& p)
  {
    cell_fail(i, "extends outside the domain: its interior reaches " + point_text(p, dim)
                     + ", closer than 3 epsilon = " + fmt(margin)
                     + " to the domain boundary; the cell and a margin of 3 epsilon around "
                       "it must lie inside the domain "
                     + domain_text(d)
                     + (d.periodic.empty() ? ""
                                           : " (also on periodic axes: a cell may not start "
                                             "across a periodic face)")
                     + (separating ? "; a phase may touch and cross the boundary with "
                                     "boundary.phi: neumann and boundary.contact_angle "
                                     "(90 is the natural condition, grad phi . n = 0)"
                                   : ""));
  };

  std::vector<SignedDistance> r;
  for (const Cell& c : s.cells)
    r.emplace_back(c, dim);

  // Interior points must keep the margin to the boundary.
  Point lo{0, 0, 0}, hi{0, 0, 0};
  bool room = true;
  for (int a = 0; a < dim; ++a)
  {
    lo[a] = d.lower[a] + margin;
    hi[a] = d.upper[a] - margin;
    room = room && lo[a] < hi[a];
  }
  auto in_inner_box = [&](const Point& p)
  {
    // A mesh domain: inside the mesh and at least the margin away from its boundary.
    if (d.mesh)
      return d.mesh->contains(p.data()) && !d.mesh->near_boundary(p.data(), margin);
    for (int a = 0; a < dim; ++a)
      if (p[a] < lo[a] || p[a] > hi[a])
        return false;
    return true;
  };

  // Grid pass: finite values, margin, overlaps, and that each cell is seen at all.
  std::vector<long> inside(s.cells.size(), 0);
  for_each_grid_point(d, check_grid_points(dim),
                      [&](const Point& p)
                      {
                        std::size_t first_inside = s.cells.size();
                        for (std::size_t i = 0; i < r.size(); ++i)
                        {
                          const double v = r[i](p[0], p[1], p[2]);
                          if (!std::isfinite(v))
                            cell_fail(i, "the signed distance is " + fmt(v) + " at "
                                             + point_text(p, dim)
                                             + "; it must be finite everywhere in the domain");
                          if (v >= 0)
                            continue;
                          ++inside[i];
                          if (!in_inner_box(p) && !wetting)
                            outside(i, p);
                          if (first_inside < s.cells.size())
                            cell_fail(i, "overlaps " + cell_label(first_inside, s.cells[first_inside])
                                             + ", e.g. at " + point_text(p, dim)
                                             + "; cells must not overlap");
                          first_inside = i;
                        }
                      });

  // Dense pass along the margin: catches cells that cross it between grid points.
  if (d.mesh && !wetting)
    for (std::size_t i = 0; i < r.size(); ++i)
      for_each_mesh_margin_point(*d.mesh, margin, s.numerics.epsilon / 4,
                                 [&](const Point& p)
                                 {
                                   if (r[i](p[0], p[1], p[2]) <= 0)
                                     outside(i, p);
                                 });
  if (room && !wetting && !d.mesh)
  {
    const double h = s.numerics.epsilon / (dim == 2 ? 4 : 1);
    for (std::size_t i = 0; i < r.size(); ++i)
      for_each_box_boundary_point(dim, lo, hi, h, dim == 2 ? 401 : 61, dim == 2 ? 20001 : 301,
                                  [&](const Point& p)
                                  {
                                    if (r[i](p[0], p[1], p[2]) <= 0)
                                      outside(i, p);
                                  });
  }

  for (std::size_t i = 0; i < r.size(); ++i)
    if (inside[i] == 0)
      cell_fail(i, "no point of the domain " + domain_text(d)
                       + " lies inside this cell: it is outside the domain or too small "
                         "(smaller than the sampling grid of "
                       + std::to_string(check_grid_points(dim)) + " points per axis)");

  const int levels = required_levels(s);
  const int max_levels = s.numerics.mesh.max_levels;
  if (levels > max_levels)
  {
    std::string finer;
    for (int a = 0; a < dim; ++a)
      finer += (a ? ", " : "[")
               + std::to_string(std::lround(std::ldexp(d.resolution[a], levels - max_levels)));
    if (d.mesh)
      finer = "a mesh file whose longest edge is at most "
              + fmt(std::ldexp(base_cell_size(d), max_levels - levels)) + " (now "
              + fmt(base_cell_size(d)) + ")";
    else
      finer = "domain.resolution to " + finer + "]";
    top.section("numerics").section("mesh").fail(
        "max_levels",
        "the interface (width " + fmt(interface_width(s.numerics.epsilon))
            + " = 4.16 epsilon) needs " + std::to_string(levels)
            + " refinement levels of the base cells (size " + fmt(base_cell_size(d)) + ") for "
            + fmt(s.numerics.mesh.points_across_interface)
            + " mesh points across it, but max_levels is " + std::to_string(max_levels)
            + "; set numerics.mesh.max_levels to " + std::to_string(levels)
            + ", or " + finer + ", or lower numerics.mesh.points_across_interface, or raise numerics.epsilon");
  }
  const int coarser = s.numerics.mesh.inside_coarser_by;
  if (coarser > 0 && !s.numerics.mesh.refine_inside.value_or(false))
    top.section("numerics").section("mesh").fail(
        "inside_coarser_by", "needs the interior refined (refine_inside: true, the default "
                             "with polar_gel); here only the interfaces are refined");
  if (coarser > 0 && coarser >= levels)
    top.section("numerics").section("mesh").fail(
        "inside_coarser_by", "found " + std::to_string(coarser) + ", expected less than the "
                             + std::to_string(levels) + " refinement levels (with "
                             + std::to_string(levels) + " or more the interior is the base "
                             "mesh: set refine_inside: false instead)");
}

} // namespace cellphase::scene
