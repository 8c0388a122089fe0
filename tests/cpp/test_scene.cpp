// Scene files: parsing, defaults, overrides, units, shapes, resolution, check report and
// every class of error.
#include "scene/Check.h"
#include "scene/Resolution.h"
#include "scene/SceneLoader.h"
#include "scene/Shapes.h"
#include "scene/Units.h"
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace cellphase::scene;

namespace
{

// The annotated example of docs/scenes.md, without the comments.
const char* full_scene = R"(
domain:
  lower: [-2, -2]
  upper: [2, 2]
  resolution: [16, 16]
boundary:
  phi: neumann
cells:
  - name: vesicle
    shape: ellipse
    center: [-0.8, 0]
    semi_axes: [0.6, 0.4]
    rotation: 30
  - name: rbc
    shape: cassini
    center: [0.9, 0.2]
    a: 0.5
    b: 0.55
phase_field:
  model: helfrich_penalty
  mobility: 2.0
  spontaneous_curvature: -0.5
  penalty_volume: 1.0e3
  penalty_area: 1.0e2
  constraint_relaxation: 0.25
units:
  length: 5.0e-6
  velocity: 0.14e-6
  density: 1.0e3
  viscosity: 10
  bending_rigidity: 1.0e-17
  surface_tension: 5.0e-6
numerics:
  epsilon: 0.03
  dt: 1.0e-3
  end_time: 0.5
  linearisation: stabilised
  stabilisation: 3.0
  mesh:
    remesh_every: 5
    points_across_interface: 6
    refine_threshold: 0.9
    max_levels: 8
  petsc:
    pc_factor_mat_solver_type: mumps
    ksp_rtol: 1.0e-10
output:
  directory: results
  every: 20
  fields: [phi, mu]
  progress: false
)";

// Smallest valid scene: everything not required takes its default.
const char* minimal_scene = R"(
domain:
  lower: [-2, -2]
  upper: [2, 2]
  resolution: [16, 16]
cells:
  - radius: 1
phase_field:
  model: cahn_hilliard
numerics:
  epsilon: 0.05
  dt: 1.0e-3
  end_time: 0.1
)";

std::string error_of(const std::string& yaml, const std::vector<std::string>& overrides = {})
{
  try
  {
    parse_scene(yaml, "test.yaml", overrides);
  }
  catch (const SceneError& e)
  {
    return e.what();
  }
  return "(no error)";
}

/// minimal_scene with one line replaced (by its exact text).
std::string minimal_with(const std::string& from, const std::string& to)
{
  std::string s = minimal_scene;
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return s.replace(pos, from.size(), to);
}

#define EXPECT_ERROR(yaml, text) EXPECT_PRED_FORMAT2(::testing::IsSubstring, text, error_of(yaml))

} // namespace

// ---------------- parsing ----------------

TEST(SceneParse, FullExample)
{
  const Scene s = parse_scene(full_scene, "full.yaml");
  EXPECT_EQ(s.source, "full.yaml");
  EXPECT_EQ(s.domain.dim, 2);
  EXPECT_DOUBLE_EQ(s.domain.lower[0], -2);
  EXPECT_DOUBLE_EQ(s.domain.upper[1], 2);
  EXPECT_EQ(s.domain.resolution[0], 16);
  EXPECT_DOUBLE_EQ(s.domain.volume(), 16);
  EXPECT_EQ(s.phi_boundary, PhiBoundary::neumann);

  ASSERT_EQ(s.cells.size(), 2u);
  EXPECT_EQ(s.cells[0].name, "vesicle");
  EXPECT_EQ(s.cells[0].shape, ShapeKind::ellipse);
  EXPECT_DOUBLE_EQ(s.cells[0].center[0], -0.8);
  EXPECT_DOUBLE_EQ(s.cells[0].semi_axes[1], 0.4);
  EXPECT_NEAR(s.cells[0].rotation, M_PI / 6, 1e-15);
  EXPECT_EQ(s.cells[1].shape, ShapeKind::cassini);
  EXPECT_DOUBLE_EQ(s.cells[1].cassini_a, 0.5);
  EXPECT_DOUBLE_EQ(s.cells[1].cassini_b, 0.55);

  EXPECT_EQ(s.phase_field.model, Model::helfrich_penalty);
  EXPECT_DOUBLE_EQ(s.phase_field.mobility, 2.0);
  EXPECT_DOUBLE_EQ(s.phase_field.spontaneous_curvature, -0.5);
  EXPECT_DOUBLE_EQ(s.phase_field.penalty_volume, 1e3);
  EXPECT_DOUBLE_EQ(s.phase_field.penalty_area, 1e2);
  EXPECT_DOUBLE_EQ(s.phase_field.constraint_relaxation, 0.25);

  EXPECT_DOUBLE_EQ(*s.units.length, 5e-6);
  EXPECT_NEAR(s.numbers.Ca, 0.264, 5e-5);
  ASSERT_TRUE(s.numbers.time_scale_s);

  EXPECT_DOUBLE_EQ(s.numerics.epsilon, 0.03);
  EXPECT_DOUBLE_EQ(s.numerics.end_time, 0.5);
  EXPECT_EQ(s.numerics.linearisation, Linearisation::stabilised);
  EXPECT_DOUBLE_EQ(s.numerics.stabilisation, 3.0);
  EXPECT_EQ(s.numerics.mesh.remesh_every, 5);
  EXPECT_DOUBLE_EQ(s.numerics.mesh.refine_threshold, 0.9);
  EXPECT_EQ(s.numerics.petsc.at("pc_factor_mat_solver_type"), "mumps");
  EXPECT_EQ(s.numerics.petsc.at("ksp_rtol"), "1.0e-10");

  EXPECT_EQ(s.output.directory, "results");
  EXPECT_EQ(s.output.every, 20);
  EXPECT_EQ(s.output.fields, (std::vector<std::string>{"phi", "mu"}));
  EXPECT_FALSE(s.output.progress);
}

TEST(SceneParse, Defaults)
{
  const Scene s = parse_scene(minimal_scene, "min.yaml");
  const Scene d; // defaults of Scene.h
  // H^-1 flows default to natural conditions on phi, L2 flows to phi = -1 (2.19)
  EXPECT_EQ(s.phi_boundary, PhiBoundary::neumann);
  EXPECT_EQ(parse_scene(minimal_scene, "min.yaml", {"phase_field.model=allen_cahn"}).phi_boundary,
            PhiBoundary::dirichlet);
  EXPECT_EQ(s.cells[0].name, "cells[0]");
  EXPECT_EQ(s.cells[0].shape, ShapeKind::circle);
  EXPECT_DOUBLE_EQ(s.cells[0].center[0], 0);
  EXPECT_DOUBLE_EQ(s.cells[0].rotation, 0);
  EXPECT_DOUBLE_EQ(s.phase_field.mobility, d.phase_field.mobility);
  EXPECT_DOUBLE_EQ(s.phase_field.constraint_relaxation, d.phase_field.constraint_relaxation);
  EXPECT_DOUBLE_EQ(s.numbers.Re, 0);
  EXPECT_DOUBLE_EQ(s.numbers.Ca, 1);
  EXPECT_DOUBLE_EQ(s.numbers.Be, 1);
  EXPECT_FALSE(s.numbers.time_scale_s);
  EXPECT_EQ(s.numerics.linearisation, Linearisation::taylor);
  EXPECT_DOUBLE_EQ(s.numerics.stabilisation, d.numerics.stabilisation);
  EXPECT_EQ(s.numerics.mesh.remesh_every, d.numerics.mesh.remesh_every);
  EXPECT_DOUBLE_EQ(s.numerics.mesh.points_across_interface, 6);
  EXPECT_DOUBLE_EQ(s.numerics.mesh.refine_threshold, 0.95);
  EXPECT_EQ(s.numerics.mesh.max_levels, 8);
  EXPECT_TRUE(s.numerics.petsc.empty());
  EXPECT_EQ(s.output.directory, "output");
  EXPECT_EQ(s.output.every, 10);
  EXPECT_EQ(s.output.fields, std::vector<std::string>{"phi"});
  EXPECT_TRUE(s.output.progress);
}

TEST(SceneParse, ThreeDimensional)
{
  const Scene s = parse_scene(R"(
domain: {lower: [-1, -1, -1], upper: [1, 1, 1], resolution: [8, 8, 8]}
cells:
  - {shape: ellipse, center: [0, 0, 0.1], semi_axes: [0.6, 0.4, 0.3], rotation: 45}
phase_field: {model: helfrich_hm1}
numerics: {epsilon: 0.06, dt: 0.01, end_time: 0.1}
output: {fields: [phi, mu, w]}
)",
                              "3d.yaml");
  EXPECT_EQ(s.domain.dim, 3);
  EXPECT_EQ(s.domain.resolution[2], 8);
  EXPECT_DOUBLE_EQ(s.domain.volume(), 8);
  EXPECT_DOUBLE_EQ(s.cells[0].center[2], 0.1);
  EXPECT_DOUBLE_EQ(s.cells[0].semi_axes[2], 0.3);
  EXPECT_EQ(s.output.fields.size(), 3u);
}

TEST(SceneParse, ModelHelpers)
{
  EXPECT_STREQ(to_string(Model::allen_cahn_volume), "allen_cahn_volume");
  EXPECT_STREQ(to_string(Model::helfrich_hm1), "helfrich_hm1");
  EXPECT_STREQ(to_string(Linearisation::stabilised), "stabilised");
  EXPECT_EQ(model_fields(Model::allen_cahn), std::vector<std::string>{"phi"});
  EXPECT_EQ(model_fields(Model::allen_cahn_volume), std::vector<std::string>{"phi"});
  EXPECT_EQ(model_fields(Model::cahn_hilliard), (std::vector<std::string>{"phi", "mu"}));
  EXPECT_EQ(model_fields(Model::helfrich_lagrange), (std::vector<std::string>{"phi", "mu"}));
  EXPECT_EQ(model_fields(Model::helfrich_penalty), (std::vector<std::string>{"phi", "mu"}));
  EXPECT_EQ(model_fields(Model::helfrich_hm1), (std::vector<std::string>{"phi", "mu", "w"}));
  EXPECT_TRUE(is_helfrich(Model::helfrich_lagrange));
  EXPECT_FALSE(is_helfrich(Model::cahn_hilliard));
}

// ---------------- overrides ----------------

TEST(SceneOverrides, ValuesParsedAsYaml)
{
  const Scene s = parse_scene(minimal_scene, "min.yaml",
                              {"numerics.epsilon=0.04", "cells.0.radius=0.8",
                               "output.fields=[phi,mu]", "numerics.mesh.max_levels=5",
                               "boundary.phi=neumann", "numerics.petsc.ksp_type=cg"});
  EXPECT_DOUBLE_EQ(s.numerics.epsilon, 0.04);
  EXPECT_DOUBLE_EQ(s.cells[0].radius, 0.8);
  EXPECT_EQ(s.output.fields, (std::vector<std::string>{"phi", "mu"}));
  EXPECT_EQ(s.numerics.mesh.max_levels, 5);
  EXPECT_EQ(s.phi_boundary, PhiBoundary::neumann);
  EXPECT_EQ(s.numerics.petsc.at("ksp_type"), "cg");
}

TEST(SceneOverrides, Errors)
{
  auto err = [](const std::string& o) { return error_of(minimal_scene, {o}); };
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "--set numerics.epsilonn=0.1: numerics.epsilonn: unknown key",
                      err("numerics.epsilonn=0.1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "--set numerics.epsilon=-1: numerics.epsilon: found -1",
                      err("numerics.epsilon=-1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "expected key.path=value", err("numerics.epsilon"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "is not a dotted key path", err("numerics..dt=1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "cells is a list of 1 entry", err("cells.3.radius=1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "numerics.epsilon is a value, not a section",
                      err("numerics.epsilon.x=1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "unknown key; allowed keys at the top level",
                      err("solver.tol=1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "the value is not valid YAML", err("output.fields=[phi"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "numerics.dt: no value given", err("numerics.dt="));
}

// ---------------- units ----------------

TEST(SceneUnits, Table51)
{
  PhysicalUnits u;
  u.length = 5.0e-6;
  u.velocity = 0.14e-6;
  u.density = 1.0e3;
  u.viscosity = 10;
  u.bending_rigidity = 1.0e-17;
  u.surface_tension = 5.0e-6;
  const Numbers n = derive_numbers(u);
  EXPECT_NEAR(n.Re, 7e-11, 1e-22);
  EXPECT_NEAR(n.Ca, 0.264, 5e-5); // 0.26399
  EXPECT_NEAR(n.Ca, 2 * std::sqrt(2.0) * 10 * 0.14e-6 / (3 * 5.0e-6), 1e-15);
  EXPECT_NEAR(n.Be, 6.6, 0.005); // 6.5997...
  EXPECT_NEAR(n.Be, 4 * std::sqrt(2.0) * 10 * 0.14e-6 * 25e-12 / 3e-17, 1e-12);
  ASSERT_TRUE(n.time_scale_s);
  EXPECT_NEAR(*n.time_scale_s, 5.0e-6 / 0.14e-6, 1e-12);
}

TEST(SceneUnits, PartialUnitsKeepDefaults)
{
  PhysicalUnits u;
  u.velocity = 1e-6;
  u.viscosity = 1;
  u.surface_tension = 1e-5;
  const Numbers n = derive_numbers(u);
  EXPECT_NEAR(n.Ca, 2 * std::sqrt(2.0) * 1e-6 / 3e-5, 1e-15);
  EXPECT_DOUBLE_EQ(n.Re, 0);
  EXPECT_DOUBLE_EQ(n.Be, 1);
  EXPECT_FALSE(n.time_scale_s);
}

TEST(SceneUnits, FromSceneFile)
{
  const Scene s = parse_scene(full_scene, "full.yaml");
  EXPECT_NEAR(s.numbers.Re, 7e-11, 1e-22);
  EXPECT_NEAR(s.numbers.Ca, 0.264, 5e-5);
  EXPECT_NEAR(s.numbers.Be, 6.6, 0.005);
  const Scene m = parse_scene(minimal_scene, "min.yaml", {"numbers={Re: 0.5, Be: 6.6}"});
  EXPECT_DOUBLE_EQ(m.numbers.Re, 0.5);
  EXPECT_DOUBLE_EQ(m.numbers.Ca, 1);
  EXPECT_DOUBLE_EQ(m.numbers.Be, 6.6);
}

// ---------------- shapes ----------------

TEST(SceneShapes, CircleAndSphereExact)
{
  Cell c;
  c.shape = ShapeKind::circle;
  c.center = {0.5, -0.25, 1};
  c.radius = 0.75;
  const SignedDistance r2(c, 2), r3(c, 3);
  EXPECT_NEAR(r2(0.5, -0.25), -0.75, 1e-15);
  EXPECT_NEAR(r2(0.5 + 3, -0.25 + 4), 5 - 0.75, 1e-14);
  EXPECT_NEAR(r2(0.5, -0.25, 123), -0.75, 1e-15); // z ignored in 2D
  EXPECT_NEAR(r3(0.5, -0.25, 1 + 2), 2 - 0.75, 1e-14);
}

/// Central-difference gradient norm of r at (x, y, z).
double grad_norm(const SignedDistance& r, double x, double y, double z, int dim)
{
  const double h = 1e-6;
  double g2 = 0;
  for (int a = 0; a < dim; ++a)
  {
    double p[3] = {x, y, z}, m[3] = {x, y, z};
    p[a] += h;
    m[a] -= h;
    const double d = (r(p[0], p[1], p[2]) - r(m[0], m[1], m[2])) / (2 * h);
    g2 += d * d;
  }
  return std::sqrt(g2);
}

TEST(SceneShapes, EllipseIsADistance)
{
  Cell c;
  c.shape = ShapeKind::ellipse;
  c.center = {0.1, 0.2, 0};
  c.semi_axes = {1.2, 0.6, 0};
  c.rotation = M_PI / 6;
  const SignedDistance r(c, 2);
  const double cs = std::cos(c.rotation), sn = std::sin(c.rotation);
  for (int k = 0; k < 64; ++k)
  {
    const double t = 2 * M_PI * k / 64;
    // A boundary point, and points just inside and outside along the normal.
    const double lx = 1.2 * std::cos(t), ly = 0.6 * std::sin(t);
    double nx = std::cos(t) / 1.2, ny = std::sin(t) / 0.6;
    const double nn = std::hypot(nx, ny);
    nx /= nn;
    ny /= nn;
    for (double off : {-0.05, 0.0, 0.05})
    {
      const double px = lx + off * nx, py = ly + off * ny;
      const double x = 0.1 + cs * px - sn * py, y = 0.2 + sn * px + cs * py;
      EXPECT_NEAR(r(x, y), off, 1e-9) << "t=" << t << " off=" << off;
      EXPECT_NEAR(grad_norm(r, x, y, 0, 2), 1.0, 1e-4);
    }
  }
  // On the axes the distance is known exactly.
  Cell a = c;
  a.center = {0, 0, 0};
  a.rotation = 0;
  const SignedDistance ra(a, 2);
  EXPECT_NEAR(ra(2, 0), 0.8, 1e-12);
  EXPECT_NEAR(ra(0, 0), -0.6, 1e-12);
  EXPECT_NEAR(ra(0, -0.5), -0.1, 1e-12);
  // Inside on the major axis the closest point leaves the axis: (0.4, 0.5657).
  EXPECT_NEAR(ra(0.3, 0), -std::sqrt(0.33), 1e-12);
}

TEST(SceneShapes, EllipsoidIsADistance)
{
  Cell c;
  c.shape = ShapeKind::ellipse;
  c.semi_axes = {1.0, 0.7, 0.4};
  const SignedDistance r(c, 3);
  EXPECT_NEAR(r(0, 0, 0), -0.4, 1e-12);
  EXPECT_NEAR(r(1.5, 0, 0), 0.5, 1e-12);
  EXPECT_NEAR(r(0, 0, -1), 0.6, 1e-12);
  for (int k = 0; k < 50; ++k)
  {
    const double th = M_PI * (k + 0.5) / 50, ph = 2.4 * k;
    const double x = std::sin(th) * std::cos(ph), y = std::sin(th) * std::sin(ph),
                 z = std::cos(th);
    EXPECT_NEAR(r(1.0 * x, 0.7 * y, 0.4 * z), 0, 1e-9);
    EXPECT_NEAR(grad_norm(r, 1.0 * x, 0.7 * y, 0.4 * z, 3), 1.0, 1e-3);
  }
}

TEST(SceneShapes, CassiniZeroSet)
{
  Cell c;
  c.shape = ShapeKind::cassini;
  c.center = {0.3, -0.2, 0};
  c.cassini_a = 0.9;
  c.cassini_b = 1.0;
  c.rotation = M_PI / 4;
  const SignedDistance r(c, 2);
  const double cs = std::cos(c.rotation), sn = std::sin(c.rotation);
  auto world = [&](double px, double py)
  { return std::array<double, 2>{0.3 + cs * px - sn * py, -0.2 + sn * px + cs * py}; };
  // Points of the oval: on the x axis (x^2 - a^2)^2 = b^4, x = sqrt(a^2 + b^2).
  const double xa = std::sqrt(0.81 + 1.0);
  for (double sx : {-1.0, 1.0})
  {
    const auto p = world(sx * xa, 0);
    EXPECT_NEAR(r(p[0], p[1]), 0, 1e-12);
    const auto in = world(sx * (xa - 0.02), 0), out = world(sx * (xa + 0.02), 0);
    EXPECT_NEAR(r(in[0], in[1]), -0.02, 2e-3);
    EXPECT_NEAR(r(out[0], out[1]), 0.02, 2e-3);
  }
  // Points along rays: the product of distances to the foci is b^2 where r = 0.
  for (int k = 0; k < 36; ++k)
  {
    const double t = 2 * M_PI * k / 36;
    double lo = 0, hi = 3; // bisection on the ray for |q-f1||q-f2| = b^2
    for (int it = 0; it < 100; ++it)
    {
      const double m = 0.5 * (lo + hi), x = m * std::cos(t), y = m * std::sin(t);
      const double prod = std::hypot(x - 0.9, y) * std::hypot(x + 0.9, y);
      (prod < 1.0 ? lo : hi) = m;
    }
    const auto p = world(lo * std::cos(t), lo * std::sin(t));
    EXPECT_NEAR(r(p[0], p[1]), 0, 1e-9);
    EXPECT_NEAR(grad_norm(r, p[0], p[1], 0, 2), 1.0, 0.02);
  }
  // The midpoint (where grad f = 0) is inside and finite.
  EXPECT_LT(r(0.3, -0.2), 0);
  EXPECT_TRUE(std::isfinite(r(0.3, -0.2)));
}

/// Distance from (x, y) to the Cassini oval |q - f1| |q - f2| = b^2 by brute force: the
/// nearest of 400000 points from the polar form r^2(theta) on each branch and of 400000
/// from y^2 = sqrt(4 a^2 x^2 + b^4) - x^2 - a^2 (each is dense where the other is sparse).
double cassini_brute_force(double x, double y, double a, double b)
{
  double best = 1e300;
  const int n = 400000;
  const double reach = std::sqrt(a * a + b * b);
  for (int i = 0; i <= n; ++i)
  {
    const double px = -reach + 2 * reach * i / n;
    const double py2 = std::sqrt(4 * a * a * px * px + b * b * b * b) - px * px - a * a;
    if (py2 >= 0)
      for (double sign : {1.0, -1.0})
        best = std::min(best, std::hypot(x - px, y - sign * std::sqrt(py2)));
  }
  for (int i = 0; i < n; ++i)
  {
    const double t = 2 * M_PI * (i + 0.5) / n, s2 = std::sin(2 * t);
    const double disc = b * b * b * b - a * a * a * a * s2 * s2;
    if (disc < 0)
      continue;
    for (double sign : {1.0, -1.0})
    {
      const double r2 = a * a * std::cos(2 * t) + sign * std::sqrt(disc);
      if (r2 < 0)
        continue;
      const double r = std::sqrt(r2);
      best = std::min(best, std::hypot(x - r * std::cos(t), y - r * std::sin(t)));
    }
  }
  const double f = (std::pow(x - a, 2) + y * y) * (std::pow(x + a, 2) + y * y) - std::pow(b, 4);
  return f < 0 ? -best : best;
}

TEST(SceneShapes, CassiniIsADistance)
{
  // One loop pinched in the middle (the red blood cell of demos/rbc-bifurcation), and two
  // loops (b < a): the signed distance equals the brute-force one away from the curve too,
  // where the first-order estimate f / |grad f| is off by 25 % at one epsilon (0.04).
  for (const auto [a, b] : {std::pair{0.15, 0.18}, std::pair{0.5, 0.4}})
  {
    Cell c;
    c.shape = ShapeKind::cassini;
    c.cassini_a = a;
    c.cassini_b = b;
    const SignedDistance r2(c, 2), r3(c, 3);
    for (int k = 0; k < 40; ++k)
    {
      const double x = -0.6 + 1.2 * ((k * 37) % 40) / 39.0, y = -0.4 + 0.8 * ((k * 11) % 40) / 39.0;
      const double expected = cassini_brute_force(x, y, a, b);
      EXPECT_NEAR(r2(x, y), expected, 2e-6) << "a " << a << ", b " << b << " at " << x << ", " << y;
      // In 3D the surface of revolution about x: the distance of (x, rho) in any plane.
      EXPECT_NEAR(r3(x, 0.6 * y, 0.8 * y), expected, 2e-6);
    }
  }
}

TEST(SceneShapes, Expression)
{
  Cell c;
  c.shape = ShapeKind::expression;
  c.expression = "sqrt(x^2 + y^2) - 1";
  c.center = {1, 1, 0};
  const SignedDistance r(c, 2);
  EXPECT_NEAR(r(1, 1), -1, 1e-14);
  EXPECT_NEAR(r(4, 5), 4, 1e-14);
  SignedDistance copy = r; // copies share the compiled expression
  EXPECT_NEAR(copy(1, 3), 1, 1e-14);

  Cell z = c;
  z.expression = "abs(z) - 0.5";
  z.center = {0, 0, 0};
  EXPECT_NEAR(SignedDistance(z, 3)(0, 0, 2), 1.5, 1e-14);

  EXPECT_EQ(check_expression("sqrt(x^2+y^2+z^2)-1"), "");
  EXPECT_NE(check_expression("sqrt(x^2+t^2)-1"), "");
  EXPECT_NE(check_expression("x+"), "");
  EXPECT_NE(check_expression("x, y"), "");
  Cell bad = c;
  bad.expression = "x +* 2";
  EXPECT_THROW(SignedDistance(bad, 2), std::invalid_argument);
}

TEST(SceneShapes, InitialPhaseField)
{
  const Scene s = parse_scene(minimal_scene, "min.yaml");
  const InitialPhaseField phi(s);
  const double eps = s.numerics.epsilon;
  EXPECT_NEAR(phi(0, 0), 1, 1e-9);
  EXPECT_NEAR(phi(1.9, 1.9), -1, 1e-9);
  EXPECT_NEAR(phi(1, 0), 0, 1e-15);
  EXPECT_NEAR(phi(1 + eps, 0), std::tanh(-1 / std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(phi.distance(0, 0.5), -0.5, 1e-15);

  const Scene two = parse_scene(full_scene, "full.yaml");
  const InitialPhaseField phi2(two);
  EXPECT_NEAR(phi2(-0.8, 0), 1, 1e-6);  // inside the vesicle
  // The Cassini cell's centre (a 0.5, b 0.55) lies sqrt(b^2 - a^2) from its pinched sides.
  const double pinch = std::sqrt(0.55 * 0.55 - 0.5 * 0.5);
  EXPECT_NEAR(phi2(0.9, 0.2), std::tanh(pinch / (std::sqrt(2.0) * two.numerics.epsilon)), 1e-9);
  EXPECT_NEAR(phi2(-1.9, 1.9), -1, 1e-6);
}

TEST(SceneShapes, InitialPhaseFieldReachesAcrossAPeriodicSide)
{
  // A circle of radius 1 at x = 1.5 in [-2, 2] periodic in x: its image at x = -2.5 reaches
  // 0.5 across the side x = -2, and a point beyond x = 2 (a wrapped patch's node) takes
  // the value of its image a period down.
  Scene s = parse_scene(minimal_scene, "min.yaml");
  s.domain.periodic = {0};
  s.cells[0].center = {1.5, 0, 0};
  const InitialPhaseField phi(s);
  const double eps = s.numerics.epsilon;
  EXPECT_NEAR(phi(-1.9, 0), std::tanh(0.4 / (std::sqrt(2.0) * eps)), 1e-12); // 0.6 from -2.5
  EXPECT_NEAR(phi(-1.9, 0), phi(2.1, 0), 1e-12);
  EXPECT_NEAR(phi(2.3, 0.4), phi(-1.7, 0.4), 1e-12);
  EXPECT_NEAR(phi.distance(-1.9, 0), -0.4, 1e-12);
  // Not across the walls in y.
  s.cells[0].center = {0, 1.5, 0};
  EXPECT_NEAR(InitialPhaseField(s)(0, -1.9), -1, 1e-9);
}

// ---------------- resolution ----------------

TEST(SceneResolution, LevelsAndSizes)
{
  EXPECT_NEAR(interface_width(1), 2 * std::sqrt(2.0) * std::atanh(0.9), 1e-15);
  EXPECT_NEAR(interface_width(0.03), 0.124922, 1e-6);

  Scene s = parse_scene(minimal_scene, "min.yaml");
  EXPECT_DOUBLE_EQ(base_cell_size(s.domain), 0.25);
  // eps 0.05: width 0.208; 6 points need h <= 0.0347, i.e. 0.25 / 8: 3 levels.
  EXPECT_EQ(required_levels(s), 3);
  EXPECT_DOUBLE_EQ(finest_cell_size(s), 0.25 / 8);
  s.numerics.mesh.points_across_interface = 0.5;
  EXPECT_EQ(required_levels(s), 0);
  EXPECT_DOUBLE_EQ(finest_cell_size(s), 0.25);

  Domain d;
  d.dim = 3;
  d.lower = {0, 0, 0};
  d.upper = {1, 2, 3};
  d.resolution = {10, 10, 10};
  EXPECT_DOUBLE_EQ(base_cell_size(d), 0.3);
  EXPECT_DOUBLE_EQ(d.volume(), 6);
}

TEST(SceneResolution, TooFewLevelsRejected)
{
  const std::string msg = error_of(minimal_scene, {"numerics.mesh.max_levels=2"});
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "numerics.mesh.max_levels", msg);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "needs 3 refinement levels", msg);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "domain.resolution to [32, 32]", msg);
}

// ---------------- check report ----------------

TEST(SceneCheck, Report)
{
  const Scene s = parse_scene(full_scene, "full.yaml");
  const std::string r = check_report(s);
  for (const char* text : {"full.yaml", "2D (triangles)", "vesicle", "rbc", "Cassini",
                           "helfrich_penalty", "stabilised", "Re = 7e-11", "Ca = 0.26398",
                           "Be = 6.59966", "time scale", "35.7143 s", "interface width",
                           "0.124922", "refinement levels", "finest cell size", "steps",
                           "500", "outputs", "26 (initial state", "degrees of freedom", "estimate"})
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, text, r);
  EXPECT_EQ(number_of_steps(s), 500);
  EXPECT_EQ(number_of_outputs(s), 26);
}

TEST(SceneCheck, SizeEstimate)
{
  // One circle of radius 1: length 2 pi.
  const Scene s = parse_scene(minimal_scene, "min.yaml");
  const SizeEstimate e = estimate_size(s);
  EXPECT_NEAR(e.interface_measure, 2 * M_PI, 0.01 * 2 * M_PI);
  EXPECT_DOUBLE_EQ(e.base_cells, 4 * 16 * 16); // crossed diagonals: four triangles per square
  // Band 2 atanh(0.95) sqrt2 eps + 2 h_base, finest triangles h^2/2 with h = 0.25/8.
  const double band = 2 * std::atanh(0.95) * std::sqrt(2.0) * 0.05 + 0.5;
  const double h = 0.25 / 8;
  EXPECT_NEAR(e.refined_cells, 2 * M_PI * band / (h * h / 2), 0.05 * e.refined_cells);
  EXPECT_NEAR(e.dofs, 2 * 2 * (e.base_cells + e.refined_cells), 1e-6 * e.dofs);

  // A sphere of radius 0.5: area pi.
  const Scene b = parse_scene(R"(
domain: {lower: [-1, -1, -1], upper: [1, 1, 1], resolution: [8, 8, 8]}
cells: [{radius: 0.5}]
phase_field: {model: allen_cahn}
numerics: {epsilon: 0.06, dt: 0.01, end_time: 0.1}
)",
                              "ball.yaml");
  const SizeEstimate eb = estimate_size(b);
  EXPECT_NEAR(eb.interface_measure, M_PI, 0.03 * M_PI);
  EXPECT_DOUBLE_EQ(eb.base_cells, 6 * 8 * 8 * 8);
}

TEST(SceneCheck, StepsRoundUp)
{
  Scene s = parse_scene(minimal_scene, "min.yaml");
  s.numerics.dt = 0.03;
  s.numerics.end_time = 0.1;
  EXPECT_EQ(number_of_steps(s), 4);
  // dt written with 9 digits: 0.2 / 0.00114285714 = 175.0000004; the remainder of 5e-10
  // joins the last step instead of being a singular step of its own.
  s.numerics.dt = 0.00114285714;
  s.numerics.end_time = 0.2;
  EXPECT_EQ(number_of_steps(s), 175);
  s.numerics.dt = 0.2 / 175 * (1 - 1e-5); // a real remainder of 1.75e-3 dt: one more step
  EXPECT_EQ(number_of_steps(s), 176);
  s.output.every = 0; // the final state only
  EXPECT_EQ(number_of_outputs(s), 1);
}

// ---------------- errors, one per class ----------------

TEST(SceneErrors, FileAndDocument)
{
  try
  {
    load_scene("/nonexistent/scene.yaml");
    FAIL() << "no error";
  }
  catch (const SceneError& e)
  {
    EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                        "cannot read scene file '/nonexistent/scene.yaml'", e.what());
  }
  EXPECT_THROW(load_scene(CELLPHASE_SOURCE_DIR "/tests"), SceneError);
  EXPECT_ERROR("", "test.yaml: the scene file is empty");
  EXPECT_ERROR("# just a comment\n", "the scene file is empty");
  EXPECT_ERROR("42", "must be a mapping of sections");
  EXPECT_ERROR("[1, 2]", "found a list");
  EXPECT_ERROR("domain: {lower: [0, 0]\n", "test.yaml:2:1: YAML syntax error");
  EXPECT_ERROR("a: b: c", "YAML syntax error");
}

TEST(SceneErrors, UnknownKeys)
{
  EXPECT_ERROR(minimal_with("cells:", "cell:"),
               "test.yaml:6:1: cell: unknown key; allowed keys at the top level: domain, "
               "boundary, cells");
  EXPECT_ERROR(minimal_with("cells:", "cell:"), "(did you mean 'cells'?)");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - radius: 1\n    colour: red"),
               "cells[0].colour: unknown key; allowed keys in cells[0]: name, shape, center, "
               "rotation, group, Be, spontaneous_curvature, mobility, penalty_area, viscosity, "
               "radius");
  EXPECT_ERROR(minimal_with("  model: cahn_hilliard", "  model: cahn_hilliard\n  gamma: 1"),
               "phase_field.gamma: unknown key");
  EXPECT_ERROR(minimal_with("  end_time: 0.1", "  end_time: 0.1\n  mesh: {levels: 3}"),
               "numerics.mesh.levels: unknown key; allowed keys in numerics.mesh: adaptive, "
               "remesh_every");
  EXPECT_ERROR(std::string(minimal_scene) + "units: {lenght: 1}\n",
               "units.lenght: unknown key; allowed keys in units: length");
  EXPECT_ERROR(std::string(minimal_scene) + "numbers: {Pe: 1}\n", "numbers.Pe: unknown key");
  EXPECT_ERROR(std::string(minimal_scene) + "output: {formats: vtk}\n",
               "output.formats: unknown key; allowed keys in output: directory, format, every");
  EXPECT_ERROR(std::string(minimal_scene) + "boundary: {mu: neumann}\n",
               "boundary.mu: unknown key; allowed keys in boundary: phi");
  EXPECT_ERROR(minimal_with("  resolution: [16, 16]", "  resolution: [16, 16]\n  periodicity: [x]"),
               "domain.periodicity: unknown key");
}

TEST(SceneErrors, WrongTypes)
{
  EXPECT_ERROR(minimal_with("epsilon: 0.05", "epsilon: small"),
               "test.yaml:11:12: numerics.epsilon: found \"small\", expected a number > 0");
  EXPECT_ERROR(minimal_with("epsilon: 0.05", "epsilon: [0.05]"),
               "numerics.epsilon: found a list of 1 item, expected a number > 0");
  EXPECT_ERROR(minimal_with("epsilon: 0.05", "epsilon: {value: 0.05}"),
               "numerics.epsilon: found a mapping");
  EXPECT_ERROR(minimal_with("epsilon: 0.05", "epsilon:"), "numerics.epsilon: no value given");
  EXPECT_ERROR(minimal_with("lower: [-2, -2]", "lower: [-2, two]"),
               "domain.lower[1]: found \"two\", expected a number");
  EXPECT_ERROR(minimal_with("resolution: [16, 16]", "resolution: [16, 16.5]"),
               "domain.resolution[1]: found 16.5, expected an integer in [1, 1e+06]");
  EXPECT_ERROR(minimal_with("resolution: [16, 16]", "resolution: 16"),
               "domain.resolution: found 16, expected a list of 2 values");
  EXPECT_ERROR(minimal_with("lower: [-2, -2]", "lower: [-2, -2, -2, -2]"),
               "domain.lower: found a list of 4 items, expected a list of 2 numbers (2D) or 3");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - radius: 1\n    center: [0, 0, 0]"),
               "cells[0].center: found a list of 3 items, expected a list of 2 numbers");
  EXPECT_ERROR(std::string(minimal_scene) + "output: {every: ten}\n",
               "output.every: found \"ten\", expected an integer >= 0");
  EXPECT_ERROR(std::string(minimal_scene) + "output: {progress: 1.5}\n",
               "output.progress: found 1.5, expected true or false");
  EXPECT_ERROR(std::string(minimal_scene) + "output: {fields: phi}\n",
               "output.fields: found \"phi\", expected a list of names");
  EXPECT_ERROR(std::string(minimal_scene) + "output: {directory: [a, b]}\n",
               "output.directory: found a list of 2 items, expected a text value");
  EXPECT_ERROR(std::string(minimal_scene) + "output: 3\n",
               "output: found 3, expected a section of keys");
  EXPECT_ERROR(minimal_with("cells:\n  - radius: 1", "cells: {radius: 1}"),
               "cells: found a mapping, expected a list");
  EXPECT_ERROR(minimal_with("cells:\n  - radius: 1", "cells: [circle]"),
               "cells[0]: found \"circle\", expected a mapping of keys");
  EXPECT_ERROR(minimal_with("end_time: 0.1", "end_time: 0.1\n  petsc: {ksp_type: [cg]}"),
               "numerics.petsc.ksp_type: found a list of 1 item, expected a single value");
  // MUMPS controls are read by cellphase itself (solve/MumpsSolver): their shape is checked.
  EXPECT_ERROR(minimal_with("end_time: 0.1", "end_time: 0.1\n  petsc: {mat_mumps_icntl_7: amf}"),
               "numerics.petsc.mat_mumps_icntl_7: found \"amf\", expected an integer");
  EXPECT_ERROR(minimal_with("end_time: 0.1", "end_time: 0.1\n  petsc: {mat_mumps_cntl_1: x}"),
               "numerics.petsc.mat_mumps_cntl_1: found \"x\", expected a number");
  EXPECT_ERROR(minimal_with("end_time: 0.1", "end_time: 0.1\n  petsc: {mat_mumps_icntl_61: 1}"),
               "numerics.petsc.mat_mumps_icntl_61: MUMPS has ICNTL(1) to (60)");
}

TEST(SceneErrors, NonFiniteValues)
{
  EXPECT_ERROR(minimal_with("dt: 1.0e-3", "dt: .nan"), "numerics.dt: found .nan, which is not a finite number");
  EXPECT_ERROR(minimal_with("dt: 1.0e-3", "dt: -.inf"), "found -.inf, which is not a finite number");
  EXPECT_ERROR(minimal_with("dt: 1.0e-3", "dt: nan"), "which is not a finite number");
  EXPECT_ERROR(minimal_with("dt: 1.0e-3", "dt: inf"), "which is not a finite number");
  EXPECT_ERROR(minimal_with("radius: 1", "radius: .inf"), "cells[0].radius: found .inf");
}

TEST(SceneErrors, OutOfRange)
{
  EXPECT_ERROR(minimal_with("epsilon: 0.05", "epsilon: 0"), "numerics.epsilon: found 0, expected a number > 0");
  EXPECT_ERROR(minimal_with("end_time: 0.1", "end_time: 1e-4"), "expected a number >= numerics.dt");
  EXPECT_ERROR(minimal_with("dt: 1.0e-3", "dt: 1.0e-300"), "at most 1e9 steps are allowed");
  EXPECT_ERROR(minimal_with("radius: 1", "radius: -1"), "cells[0].radius: found -1, expected a number > 0");
  EXPECT_ERROR(minimal_with("upper: [2, 2]", "upper: [2, -3]"), "domain.upper: on axis 1");
  EXPECT_ERROR(minimal_with("resolution: [16, 16]", "resolution: [0, 16]"),
               "domain.resolution[0]: found 0, expected an integer in [1, 1e+06]");
  auto with = [](const std::string& o) { return error_of(minimal_scene, {o}); };
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "phase_field.mobility: found 0, expected a number > 0",
                      with("phase_field.mobility=0"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "phase_field.penalty_area: found -1, expected a number >= 0",
                      with("phase_field.penalty_area=-1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "expected a number in [0, 1]",
                      with("phase_field.constraint_relaxation=1.5"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "numbers.Re: found -1, expected a number >= 0",
                      with("numbers.Re=-1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "numbers.Ca: found 0, expected a number > 0",
                      with("numbers.Ca=0"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "units.viscosity: found -10", with("units.viscosity=-10"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "numerics.stabilisation: found -2",
                      with("numerics.stabilisation=-2"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "expected an integer in [0, 20]",
                      with("numerics.mesh.max_levels=21"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "expected a number in (0, 1)",
                      with("numerics.mesh.refine_threshold=0"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "numerics.mesh.points_across_interface: found 0",
                      with("numerics.mesh.points_across_interface=0"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "output.every: found -1, expected an integer >= 0",
                      with("output.every=-1"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "output.directory: is empty", with("output.directory=''"));
}

TEST(SceneErrors, EnumsAndMissingKeys)
{
  EXPECT_ERROR(minimal_with("model: cahn_hilliard", "model: navier_stokes"),
               "phase_field.model: unknown value \"navier_stokes\"; allowed: allen_cahn, "
               "allen_cahn_volume, cahn_hilliard, helfrich_lagrange, helfrich_penalty, helfrich_hm1");
  EXPECT_ERROR(std::string(minimal_scene) + "boundary: {phi: periodic}\n",
               "boundary.phi: unknown value \"periodic\"; allowed: dirichlet, neumann");
  EXPECT_ERROR(minimal_with("end_time: 0.1", "end_time: 0.1\n  linearisation: taylr"),
               "allowed: taylor, stabilised (did you mean 'taylor'?)");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - shape: blob"), "cells[0].shape: unknown value \"blob\"");
  EXPECT_ERROR(minimal_with("phase_field:\n  model: cahn_hilliard\n", ""), "phase_field: missing");
  EXPECT_ERROR(minimal_with("  model: cahn_hilliard", "  mobility: 1"), "phase_field.model: missing");
  EXPECT_ERROR(minimal_with("  epsilon: 0.05\n", ""), "numerics.epsilon: missing");
  EXPECT_ERROR(minimal_with("  end_time: 0.1\n", ""), "numerics.end_time: missing");
  EXPECT_ERROR(minimal_with("cells:\n  - radius: 1\n", ""), "cells: missing");
  EXPECT_ERROR(minimal_with("cells:\n  - radius: 1\n", "cells: []\n"), "cells: is an empty list");
  EXPECT_ERROR(minimal_with("numerics:", "numerix:"), "numerix: unknown key");
}

TEST(SceneErrors, CellShapes)
{
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - name: rbc\n    shape: ellipse\n    radius: 1"),
               "cells[0] (\"rbc\").radius: is a key of shape circle, but this cell's shape is "
               "ellipse, which takes semi_axes");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - shape: ellipse"),
               "cells[0].semi_axes: missing; shape ellipse needs semi_axes");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - shape: cassini\n    a: 0.5"),
               "cells[0].b: missing; shape cassini needs b");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - shape: expression"),
               "cells[0].distance: missing");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - shape: circle\n    distance: x"),
               "cells[0].distance: is a key of shape expression");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - shape: ellipse\n    semi_axes: [1, 0]"),
               "cells[0].semi_axes[1]: found 0, expected a number > 0");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - radius: 1\n    name: ''"), "cells[0].name: is empty");
  EXPECT_ERROR(minimal_with("  - radius: 1",
                            "  - {name: a, radius: 0.5, center: [-1, 0]}\n"
                            "  - {name: a, radius: 0.5, center: [1, 0]}"),
               "cells[1].name: \"a\" is already the name of cells[0]");
}

TEST(SceneErrors, Expressions)
{
  auto scene = [](const std::string& expr)
  { return minimal_with("  - radius: 1", "  - name: blob\n    shape: expression\n    distance: \"" + expr + "\""); };
  EXPECT_NO_THROW(parse_scene(scene("sqrt(x^2 + y^2) - 1"), "t.yaml"));
  EXPECT_NO_THROW(parse_scene(scene("max(abs(x), abs(y)) - 1"), "t.yaml"));
  EXPECT_ERROR(scene("sqrt(x^2 + t^2) - 1"),
               "cells[0] (\"blob\").distance: cannot parse the expression \"sqrt(x^2 + t^2) - 1\": "
               "Unexpected token \"t\"");
  EXPECT_ERROR(scene("sqrt(x^2 + y^2 - 1"), "cannot parse the expression");
  EXPECT_ERROR(scene(""), "cannot parse the expression");
  EXPECT_ERROR(scene("x, y"), "gives 2 values");
  EXPECT_ERROR(scene("sqrt(x) - 1"), "cells[0] (\"blob\"): the signed distance is nan");
}

TEST(SceneErrors, Placement)
{
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - {name: big, radius: 1.9}"),
               "cells[0] (\"big\"): extends outside the domain");
  // Inside, but within the 3 epsilon = 0.15 margin.
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - {radius: 1, center: [0.9, 0]}"),
               "extends outside the domain");
  EXPECT_NO_THROW(parse_scene(minimal_with("  - radius: 1", "  - {radius: 1, center: [0.8, 0]}"), "t"));
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - {radius: 1, center: [5, 0]}"),
               "no point of the domain [-2, 2] x [-2, 2] lies inside this cell");
  EXPECT_ERROR(minimal_with("  - radius: 1", "  - {radius: 1e-4, center: [0.001, 0.001]}"),
               "too small");
  EXPECT_ERROR(minimal_with("  - radius: 1",
                            "  - {name: a, radius: 0.6, center: [-0.5, 0]}\n"
                            "  - {name: b, shape: cassini, a: 0.5, b: 0.55, center: [0.6, 0]}"),
               "cells[1] (\"b\"): overlaps cells[0] (\"a\")");
  EXPECT_NO_THROW(parse_scene(minimal_with("  - radius: 1",
                                           "  - {name: a, radius: 0.5, center: [-1, 0]}\n"
                                           "  - {name: b, radius: 0.5, center: [1, 0]}"),
                              "t"));
  // 3D: a sphere poking out through the top face.
  EXPECT_ERROR(R"(
domain: {lower: [-1, -1, -1], upper: [1, 1, 1], resolution: [8, 8, 8]}
cells: [{radius: 0.5, center: [0, 0, 0.6]}]
phase_field: {model: allen_cahn}
numerics: {epsilon: 0.06, dt: 0.01, end_time: 0.1}
)",
               "cells[0]: extends outside the domain");
}

TEST(SceneErrors, FieldsAndSections)
{
  EXPECT_ERROR(std::string(minimal_scene) + "output: {fields: [phi, w]}\n",
               "output.fields[1]: field \"w\" is not solved for by model cahn_hilliard; allowed: phi, mu");
  EXPECT_ERROR(std::string(minimal_scene) + "output: {fields: [phi, phi]}\n", "is listed twice");
  EXPECT_ERROR(std::string(minimal_scene) + "output: {format: vtu}\n",
               "output.format: unknown value \"vtu\"");
  EXPECT_ERROR(std::string(minimal_scene) + "numbers: {Ca: 1}\nunits: {length: 1}\n",
               "units: give either numbers");
  EXPECT_ERROR(minimal_with("numerics:\n  epsilon: 0.05", "numerics:\n  epsilon: 0.05\n  dt: 0.1"),
               "numerics.dt: duplicate key");
}

// ---------------- the malformed scene files ----------------

TEST(SceneErrors, BadSceneFiles)
{
  const std::string dir = CELLPHASE_SOURCE_DIR "/tests/scenes/bad/";
  std::ifstream list(dir + "expected.txt");
  ASSERT_TRUE(list) << "cannot open " << dir << "expected.txt";
  std::string line;
  int checked = 0;
  while (std::getline(list, line))
  {
    if (line.empty() || line[0] == '#')
      continue;
    const auto colon = line.find(": ");
    ASSERT_NE(colon, std::string::npos) << line;
    const std::string file = line.substr(0, colon), expected = line.substr(colon + 2);
    SCOPED_TRACE(file);
    try
    {
      load_scene(dir + file);
      ADD_FAILURE() << file << " loaded without error";
    }
    catch (const SceneError& e)
    {
      EXPECT_PRED_FORMAT2(::testing::IsSubstring, expected, e.what());
      EXPECT_PRED_FORMAT2(::testing::IsSubstring, file, e.what()); // names the file
    }
    ++checked;
  }
  EXPECT_GE(checked, 12);
}
