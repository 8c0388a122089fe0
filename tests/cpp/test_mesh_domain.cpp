// Domains from mesh files (domain.mesh):
// * the XDMF reader gives the cells, nodes and named tags of the file;
// * the base mesh built from it has the file's cells, and its tagged boundary facets add
//   up to the tag lengths;
// * Poiseuille flow with tagged walls: the parabola (in P2 x P1) to round-off, and the
//   same flow as the box with side walls when the box mesh is given as a mesh file;
// * after adaptive refinement the boundary facets still carry their tags (lengths kept);
// * a cell across a periodic face: both faces are refined alike.
#include "app/FlowSetup.h"
#include "compat/Dolfinx.h"
#include "mesh/AdaptiveMesh.h"
#include "mesh/BoundaryTags.h"
#include "mesh/PeriodicFaces.h"
#include "mpi_main.h"
#include "scene/MeshDomain.h"
#include "scene/SceneLoader.h"
#include <cmath>
#include <cstdio>

using namespace cellphase;
namespace
{
const std::string test_meshes = CELLPHASE_TEST_MESH_DIR;
const std::string meshes = CELLPHASE_MESH_DIR;

/// Global length of the given local facets of a 2D mesh.
double facets_length(const Mesh& mesh, const std::vector<std::int32_t>& facets)
{
  const auto nodes = dolfinx::mesh::entities_to_geometry(mesh, 1, facets, false);
  auto x = mesh.geometry().x();
  double length = 0;
  for (std::size_t i = 0; i < facets.size(); ++i)
  {
    const double* a = &x[3 * nodes[2 * i]];
    const double* b = &x[3 * nodes[2 * i + 1]];
    length += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  MPI_Allreduce(MPI_IN_PLACE, &length, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
  return length;
}

/// A scene on a mesh file with a circle at `centre`, and an optional flow section.
scene::Scene mesh_scene(const std::string& file, const std::string& centre,
                        const std::string& flow = "")
{
  const std::string yaml = "domain: {mesh: " + file + "}\n"
                           "cells: [{shape: circle, center: " + centre + ", radius: 0.2}]\n"
                           "phase_field: {model: helfrich_penalty}\n"
                           "numbers: {Re: 0, Ca: 1, Be: 1}\n"
                           "numerics: {epsilon: 0.04, dt: 1.0e-3, end_time: 1.0e-3}\n"
                           + flow;
  return scene::parse_scene(yaml, "test.yaml", {});
}

double max_difference(const Function& u, const VectorPointFunction& f)
{
  Function exact(u.function_space());
  compat::interpolate_vector(exact, f);
  auto a = u.x()->array(), b = exact.x()->array();
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    m = std::max(m, std::abs(a[i] - b[i]));
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return m;
}
} // namespace

TEST(MeshFile, ReadsCellsNodesAndTagNames)
{
  const auto m = scene::read_mesh_file(std::string(CELLPHASE_SOURCE_DIR) + "/tests/meshes/square.xdmf");
  EXPECT_EQ(m.num_cells(), 4u);
  EXPECT_EQ(m.num_nodes(), 5u);
  const scene::MeshDomain d(m, "square.xdmf");
  EXPECT_EQ(d.tag_names(), (std::vector<std::string>{"bottom", "left", "right"}));
  EXPECT_DOUBLE_EQ(d.area(), 1.0);
  EXPECT_DOUBLE_EQ(d.tag_length(d.tag("left")), 1.0);
  // The top side carries no tag.
  EXPECT_DOUBLE_EQ(d.tag_length(scene::MeshDomain::untagged), 1.0);
  EXPECT_EQ(d.normal_axis({d.tag("left")}), 0);
  EXPECT_EQ(d.normal_axis({d.tag("bottom")}), 1);
  EXPECT_EQ(d.normal_axis({d.tag("left"), d.tag("bottom")}), -1);
  const double in[2] = {0.3, 0.6}, out[2] = {1.2, 0.5}, on[2] = {0.5, 0};
  EXPECT_TRUE(d.contains(in));
  EXPECT_FALSE(d.contains(out));
  EXPECT_TRUE(d.on_tags(on, {d.tag("bottom")}));
  EXPECT_FALSE(d.on_tags(on, {d.tag("left")}));
}

TEST(MeshFile, GeneratedMeshesHaveTheirTags)
{
  const auto bif = scene::read_mesh_file(meshes + "/bifurcation.xdmf");
  const scene::MeshDomain b(bif, "bifurcation.xdmf");
  EXPECT_EQ(b.tag_names(),
            (std::vector<std::string>{"inflow", "outflow_lower", "outflow_upper", "wall"}));
  EXPECT_NEAR(b.area(), 8.01828240239903, 1e-12); // the polygon of meshes/bifurcation.geo
  EXPECT_NEAR(b.tag_length(b.tag("inflow")), 1.0, 1e-12);
  EXPECT_NEAR(b.tag_length(b.tag("outflow_upper")), 0.7, 1e-12);
  EXPECT_EQ(b.tag_length(scene::MeshDomain::untagged), 0.0);
  const auto mc = scene::read_mesh_file(meshes + "/microchannel.xdmf");
  const scene::MeshDomain c(mc, "microchannel.xdmf");
  EXPECT_EQ(c.tag_names(), (std::vector<std::string>{"chamber_end", "tube_end", "wall"}));
  EXPECT_NEAR(c.area(), 46.0, 1e-12); // the polygon of meshes/microchannel.geo
  EXPECT_NEAR(c.tag_length(c.tag("chamber_end")), 6.0, 1e-12);
  EXPECT_NEAR(c.tag_length(c.tag("tube_end")), 2.0, 1e-12);
}

TEST(MeshDomain, BaseMeshHasTheFileCellsAndTags)
{
  const auto s = mesh_scene(test_meshes + "/channel.xdmf", "[2, 0.5]");
  auto mesh = compat::create_base_mesh(MPI_COMM_WORLD, s.domain);
  const scene::MeshDomain& d = *s.domain.mesh;
  EXPECT_EQ(compat::num_global_cells(*mesh), std::int64_t(d.data().num_cells()));
  EXPECT_NEAR(facets_length(*mesh, tagged_facets(*mesh, d, {d.tag("inflow")})), 1.0, 1e-12);
  EXPECT_NEAR(facets_length(*mesh, tagged_facets(*mesh, d, {d.tag("wall")})), 8.0, 1e-12);
  EXPECT_NEAR(s.domain.volume(), 4.0, 1e-12);
}

TEST(MeshDomain, PoiseuilleWithTaggedWallsIsExact)
{
  // Parabola in at x = 0 and out at x = 4, no-slip walls: a closed boundary, so the
  // pressure is pinned at a vertex. u = 4 y (1 - y), p = -8 x + c lie in P2 x P1.
  const auto s = mesh_scene(test_meshes + "/channel.xdmf", "[2, 0.5]",
                            "flow:\n  equations: stokes\n  walls:\n"
                            "    inflow: {type: prescribed, velocity: [\"4*y*(1-y)\", 0]}\n"
                            "    outflow: {type: prescribed, velocity: [\"4*y*(1-y)\", 0]}\n");
  FlowParameters p = flow_parameters(s);
  ASSERT_TRUE(p.pressure_pin.has_value());
  FlowModule flow(p, MPI_COMM_WORLD);
  flow.attach(compat::create_base_mesh(MPI_COMM_WORLD, s.domain));
  flow.step(1.0);
  EXPECT_TRUE(flow.pressure_pinned());
  const double err = max_difference(*flow.velocity(), [](double, double y, double)
                                    { return std::array<double, 3>{4 * y * (1 - y), 0, 0}; });
  EXPECT_LT(err, 1e-10);
  std::printf("Poiseuille on channel.xdmf: max nodal velocity error %.2e\n", err);
}

TEST(MeshDomain, TaggedWallsOfTheBoxGiveTheBoxFlow)
{
  // The box mesh written as mesh data with a tag per side: inflow profile on the left,
  // open right side, no-slip bottom and top. Same mesh, same flow as with box sides.
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1)
    GTEST_SKIP() << "serial: the box's nodes are taken from rank 0";
  scene::Domain box;
  box.upper = {2, 1, 0};
  box.resolution = {8, 4, 0};
  auto box_mesh = compat::create_base_mesh(MPI_COMM_WORLD, box);
  scene::MeshData data;
  auto x = box_mesh->geometry().x();
  data.points.assign(x.begin(), x.end());
  const auto& dofmap = box_mesh->geometry().dofmap();
  for (std::int32_t c = 0; c < compat::num_owned_cells(*box_mesh); ++c)
    for (auto n : dofmap.links(c))
      data.cells.push_back(n);
  data.tags = {{"left", 1}, {"right", 2}, {"bottom", 3}, {"top", 4}};
  for (std::size_t c = 0; c < data.cells.size(); c += 3)
    for (int k = 0; k < 3; ++k)
    {
      const auto a = data.cells[c + k], b = data.cells[c + (k + 1) % 3];
      const double *pa = &x[3 * a], *pb = &x[3 * b];
      for (auto [axis, value, tag] : {std::tuple{0, 0.0, 1}, {0, 2.0, 2}, {1, 0.0, 3}, {1, 1.0, 4}})
        if (pa[axis] == value && pb[axis] == value)
          data.facets.insert(data.facets.end(), {a, b}), data.facet_tags.push_back(tag);
    }
  auto domain = std::make_shared<scene::MeshDomain>(data, "box");
  auto file_mesh = compat::create_triangle_mesh(MPI_COMM_WORLD, data.points, data.cells);

  const VectorPointFunction profile = [](double, double y, double)
  { return std::array<double, 3>{4 * y * (1 - y), 0, 0}; };
  FlowParameters sides;
  sides.walls = {{Side::left, WallKind::prescribed, {}, profile},
                 {Side::bottom, WallKind::no_slip},
                 {Side::top, WallKind::no_slip}};
  FlowParameters tagged = sides;
  tagged.tagged_walls = true;
  for (auto& w : tagged.walls)
  {
    const int tag = w.side == Side::left ? 1 : w.side == Side::bottom ? 3 : 4;
    w.facets = [domain, tag](const Mesh& m) { return tagged_facets(m, *domain, {tag}); };
    w.normal_axis = domain->normal_axis({tag});
  }
  FlowModule a(sides, MPI_COMM_WORLD), b(tagged, MPI_COMM_WORLD);
  a.attach(box_mesh);
  b.attach(file_mesh);
  a.step(1.0);
  b.step(1.0);
  EXPECT_FALSE(a.pressure_pinned());
  EXPECT_FALSE(b.pressure_pinned());
  Function moved(a.velocity()->function_space());
  compat::transfer(b.velocity(), moved);
  double diff = 0, size_v = 0;
  for (std::size_t i = 0; i < moved.x()->array().size(); ++i)
  {
    diff = std::max(diff, std::abs(moved.x()->array()[i] - a.velocity()->x()->array()[i]));
    size_v = std::max(size_v, std::abs(a.velocity()->x()->array()[i]));
  }
  EXPECT_GT(size_v, 0.9);
  EXPECT_LT(diff, 1e-10);
  std::printf("box sides vs tagged box: max velocity difference %.2e (max |v| %.3f)\n", diff,
              size_v);
}

TEST(MeshDomain, RefinedMeshKeepsItsTags)
{
  // Refine around a circle that crosses the inflow: the inflow facets are split, and
  // every tag keeps its length on the refined mesh.
  const auto s = mesh_scene(meshes + "/bifurcation.xdmf", "[1.5, 0]");
  AdaptiveMesh adaptive(s, MPI_COMM_WORLD);
  ASSERT_GT(adaptive.levels(), 1);
  const double eps = s.numerics.epsilon;
  auto phi = [eps](std::span<const double> pts, std::span<double> values)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = std::tanh((0.3 - std::hypot(pts[3 * i], pts[3 * i + 1])) / (std::sqrt(2.0) * eps));
  };
  auto base = adaptive.base();
  auto fine = adaptive.build(phi);
  const scene::MeshDomain& d = *s.domain.mesh;
  EXPECT_GT(compat::num_global_cells(*fine), 2 * compat::num_global_cells(*base));
  std::printf("bifurcation: %lld base cells, %lld after %d levels\n",
              (long long)compat::num_global_cells(*base), (long long)compat::num_global_cells(*fine),
              adaptive.levels());
  auto count = [](const Mesh& m, const std::vector<std::int32_t>& f)
  {
    std::int64_t n = f.size();
    MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_INT64_T, MPI_SUM, m.comm());
    return n;
  };
  const int inflow = d.tag("inflow");
  EXPECT_GT(count(*fine, tagged_facets(*fine, d, {inflow})),
            2 * count(*base, tagged_facets(*base, d, {inflow})));
  double total = 0;
  for (const auto& name : d.tag_names())
  {
    const double l = facets_length(*fine, tagged_facets(*fine, d, {d.tag(name)}));
    EXPECT_NEAR(l, d.tag_length(d.tag(name)), 1e-12) << name;
    total += l;
  }
  // Every boundary facet has a tag.
  auto all = compat::boundary_facets(*fine, [](double, double, double) { return true; });
  EXPECT_NEAR(facets_length(*fine, all), total, 1e-12);
  // A replay from the refined cells' centroids gives the same mesh and tags.
  // replay() wants every rank's centroids (a checkpoint gathers them); a copy, since
  // replay() rewrites the history.
  std::vector<std::vector<double>> history;
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  for (const auto& level : adaptive.history())
  {
    int n = int(level.size());
    std::vector<int> counts(ranks), offsets(ranks, 0);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 1; r < ranks; ++r)
      offsets[r] = offsets[r - 1] + counts[r - 1];
    std::vector<double> all(offsets.back() + counts.back());
    MPI_Allgatherv(level.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, MPI_COMM_WORLD);
    history.push_back(all);
  }
  auto again = adaptive.replay(history);
  EXPECT_EQ(compat::num_global_cells(*again), compat::num_global_cells(*fine));
  EXPECT_NEAR(facets_length(*again, tagged_facets(*again, d, {inflow})), 1.0, 1e-12);
}

namespace
{
/// Mean area of the local cells whose centroid lies at a distance from (2, 2) in [lo, hi).
double mean_area(const Mesh& mesh, double lo, double hi)
{
  double sum = 0, count = 0;
  for (std::int32_t c = 0; c < compat::num_owned_cells(mesh); ++c)
  {
    const auto v = compat::cell_vertex_coordinates(mesh, c);
    const double r = std::hypot((v[0] + v[3] + v[6]) / 3 - 2, (v[1] + v[4] + v[7]) / 3 - 2);
    if (r < lo || r >= hi)
      continue;
    sum += 0.5 * std::abs((v[3] - v[0]) * (v[7] - v[1]) - (v[6] - v[0]) * (v[4] - v[1]));
    count += 1;
  }
  double both[2] = {sum, count};
  MPI_Allreduce(MPI_IN_PLACE, both, 2, MPI_DOUBLE, MPI_SUM, mesh.comm());
  return both[0] / both[1];
}
} // namespace

TEST(AdaptiveMesh, CoarserInteriorKeepsTheInterfaceBandFinest)
{
  // numerics.mesh.inside_coarser_by: the band around the zero level set keeps the finest
  // cells, the interior (phi > -threshold away from the band) is refined one level less,
  // so its cells have about 4 times the area (bisection mixes halves and quarters, hence
  // the ranges).
  auto scene_with = [](int coarser)
  {
    const std::string yaml =
        "domain: {lower: [0, 0], upper: [4, 4], resolution: [8, 8]}\n"
        "cells: [{shape: circle, center: [2, 2], radius: 1}]\n"
        "phase_field: {model: helfrich_penalty}\n"
        "numbers: {Re: 0, Ca: 1, Be: 1}\n"
        "numerics: {epsilon: 0.04, dt: 1.0e-3, end_time: 1.0e-3, mesh: "
        "{points_across_interface: 3, refine_inside: true, inside_coarser_by: "
        + std::to_string(coarser) + "}}\n";
    return scene::parse_scene(yaml, "test.yaml", {});
  };
  auto phi = [](std::span<const double> pts, std::span<double> values)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = std::tanh((1 - std::hypot(pts[3 * i] - 2, pts[3 * i + 1] - 2))
                            / (std::sqrt(2.0) * 0.04));
  };
  const auto fine_scene = scene_with(0), coarse_scene = scene_with(1);
  AdaptiveMesh fine_builder(fine_scene, MPI_COMM_WORLD), coarse_builder(coarse_scene, MPI_COMM_WORLD);
  auto fine = fine_builder.build(phi);
  auto coarse = coarse_builder.build(phi);
  const double band_fine = mean_area(*fine, 0.97, 1.03), band_coarse = mean_area(*coarse, 0.97, 1.03);
  const double inside_fine = mean_area(*fine, 0, 0.6), inside_coarse = mean_area(*coarse, 0, 0.6);
  std::printf("levels %d; mean area in the band %.3g / %.3g, inside %.3g / %.3g; cells %lld / %lld\n",
              fine_builder.levels(), band_fine, band_coarse, inside_fine, inside_coarse,
              (long long)compat::num_global_cells(*fine), (long long)compat::num_global_cells(*coarse));
  EXPECT_NEAR(band_coarse / band_fine, 1.0, 0.05); // the band keeps the finest level
  EXPECT_GT(inside_fine / band_fine, 0.5);            // fine interior: the band's size
  EXPECT_LT(inside_fine / band_fine, 2.0);
  EXPECT_GT(inside_coarse / inside_fine, 3.0);        // one level less: about 4 times
  EXPECT_LT(inside_coarse / inside_fine, 5.0);
  EXPECT_LT(compat::num_global_cells(*coarse), compat::num_global_cells(*fine));
}

TEST(AdaptiveMesh, PeriodicFacesAreRefinedAlike)
{
  // A circle across the face x = 0 of a box periodic in x: the refinement around its band
  // reaches the face from both sides, and each side's cells are marked on their own. The
  // faces must end up with the same vertices (else the periodic constraint ties the fine
  // side to the coarse side's trace, which cannot resolve the interface).
  const std::string yaml = "domain: {lower: [0, 0], upper: [4, 4], resolution: [8, 8], "
                           "periodic: [x]}\n"
                           "cells: [{shape: circle, center: [2, 2], radius: 1}]\n"
                           "phase_field: {model: helfrich_penalty}\n"
                           "numbers: {Re: 0, Ca: 1, Be: 1}\n"
                           "numerics: {epsilon: 0.04, dt: 1.0e-3, end_time: 1.0e-3, mesh: "
                           "{points_across_interface: 3, refine_inside: true, inside_coarser_by: 1}}\n";
  const auto s = scene::parse_scene(yaml, "test.yaml", {});
  for (double cx : {0.3, 3.85, 0.0})
  {
    auto phi = [cx](std::span<const double> pts, std::span<double> values)
    {
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        double dx = std::abs(pts[3 * i] - cx);
        dx = std::min(dx, 4 - dx); // the periodic distance
        values[i] = std::tanh((1 - std::hypot(dx, pts[3 * i + 1] - 2)) / (std::sqrt(2.0) * 0.04));
      }
    };
    AdaptiveMesh builder(s, MPI_COMM_WORLD);
    auto mesh = builder.build(phi);
    std::int64_t on_face = 0; // vertices on x = 0 (owned and ghost: an upper bound)
    auto x = mesh->geometry().x();
    for (std::size_t i = 0; i < x.size() / 3; ++i)
      on_face += std::abs(x[3 * i]) < 1e-12;
    MPI_Allreduce(MPI_IN_PLACE, &on_face, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
    const auto unmatched = unmatched_periodic_points(*mesh, s.domain);
    std::printf("circle at x = %.2f: %lld vertex entries on x = 0 (9 unrefined), %zu unmatched\n",
                cx, (long long)on_face, unmatched.size() / 3);
    EXPECT_GT(on_face, 3 * 9); // refined well below the base spacing there
    EXPECT_EQ(unmatched.size(), 0u);
  }
}
