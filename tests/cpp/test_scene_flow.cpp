// The flow section of a scene: values, defaults, the derived Re and interface-force
// prefactor, the check report, and every kind of error naming its key.
#include "scene/Check.h"
#include "scene/SceneLoader.h"
#include <cmath>
#include <gtest/gtest.h>

using namespace cellphase::scene;

namespace
{
const char* base_scene = R"(
domain:
  lower: [0, 0]
  upper: [1, 2]
  resolution: [8, 16]
cells:
  - center: [0.5, 0.5]
    radius: 0.25
phase_field:
  model: cahn_hilliard
numbers:
  Re: 100
  Ca: 0.5
numerics:
  epsilon: 0.04
  dt: 1.0e-2
  end_time: 0.1
)";

const char* flow_section = R"(flow:
  equations: navier_stokes
  density: {inside: 0.1, outside: 1}
  viscosity: {inside: 0.2, outside: 1}
  gravity: [0, -98]
  force: [0.5, 0]
  surface_tension: 2.45
  walls:
    left: free_slip
    right: open
    bottom: no_slip
    top: {type: moving, velocity: [1, 0]}
  petsc:
    mat_mumps_icntl_7: 2
)";

std::string with_flow(const std::string& flow) { return std::string(base_scene) + flow; }

std::string error_of(const std::string& yaml, const std::vector<std::string>& overrides = {})
{
  try
  {
    parse_scene(yaml, "flow.yaml", overrides);
  }
  catch (const SceneError& e)
  {
    return e.what();
  }
  return "(no error)";
}

#define EXPECT_ERROR(yaml, text) EXPECT_PRED_FORMAT2(::testing::IsSubstring, text, error_of(yaml))
} // namespace

TEST(SceneFlow, AbsentMeansNoFlow)
{
  const Scene s = parse_scene(base_scene, "flow.yaml");
  EXPECT_FALSE(s.flow.has_value());
  EXPECT_EQ(flow_reynolds(s), 0.0);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "none (phase field only)", check_report(s));
}

TEST(SceneFlow, AllKeys)
{
  const Scene s = parse_scene(with_flow(flow_section), "flow.yaml");
  ASSERT_TRUE(s.flow.has_value());
  const Flow& f = *s.flow;
  EXPECT_EQ(f.equations, FlowEquations::navier_stokes);
  EXPECT_EQ(f.density[0], 1.0);   // outside first
  EXPECT_EQ(f.density[1], 0.1);
  EXPECT_EQ(f.viscosity[1], 0.2);
  EXPECT_EQ(f.gravity[1], -98.0);
  EXPECT_EQ(f.force[0], 0.5);
  EXPECT_EQ(f.walls[0].type, WallType::free_slip);
  EXPECT_EQ(f.walls[1].type, WallType::open);
  EXPECT_EQ(f.walls[2].type, WallType::no_slip);
  EXPECT_EQ(f.walls[3].type, WallType::moving);
  EXPECT_EQ(f.walls[3].velocity[0], 1.0);
  EXPECT_EQ(f.petsc.at("mat_mumps_icntl_7"), "2");
  EXPECT_EQ(flow_reynolds(s), 100.0);
  // sigma given: 3 sigma / (2 sqrt2), not 1/Ca
  EXPECT_NEAR(flow_capillary(s), 3 * 2.45 / (2 * std::sqrt(2.0)), 1e-14);
}

TEST(SceneFlow, DefaultsAndDerivedNumbers)
{
  const Scene s = parse_scene(with_flow("flow: {}\n"), "flow.yaml");
  ASSERT_TRUE(s.flow.has_value());
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(s.flow->walls[i].type, WallType::no_slip); // closed box (3.59)-(3.64) BCs
  EXPECT_EQ(s.flow->density[0], 1.0);
  EXPECT_EQ(flow_capillary(s), 2.0); // 1/Ca
  // Stokes explicitly, or automatically when Re = 0
  EXPECT_EQ(flow_reynolds(parse_scene(with_flow("flow: {equations: stokes}\n"), "f.yaml")), 0.0);
  const Scene re0 = parse_scene(with_flow("flow: {}\n"), "f.yaml", {"numbers.Re=0"});
  EXPECT_EQ(flow_reynolds(re0), 0.0);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "Stokes (Re = 0, as numbers.Re is 0",
                      check_report(re0));
  // The flow's solver: numerics.solver unless flow.solver says otherwise.
  EXPECT_EQ(flow_solver(s), Numerics::Solver::direct);
  EXPECT_EQ(flow_solver(parse_scene(with_flow("flow: {}\n"), "f.yaml", {"numerics.solver=reuse"})),
            Numerics::Solver::reuse);
  EXPECT_EQ(flow_solver(parse_scene(with_flow("flow: {solver: reuse}\n"), "f.yaml")),
            Numerics::Solver::reuse);
  EXPECT_EQ(flow_solver(parse_scene(with_flow("flow: {solver: direct}\n"), "f.yaml",
                                    {"numerics.solver=reuse"})),
            Numerics::Solver::direct);
  // velocity and pressure may be written
  const Scene out = parse_scene(with_flow("flow: {}\noutput: {fields: [phi, v, p]}\n"), "f.yaml");
  EXPECT_EQ(out.output.fields.size(), 3u);
}

TEST(SceneFlow, HelfrichHm1UsesW)
{
  std::string yaml = with_flow("flow: {}\n");
  yaml.replace(yaml.find("cahn_hilliard"), 13, "helfrich_hm1");
  const Scene s = parse_scene(yaml, "flow.yaml");
  EXPECT_EQ(flow_capillary(s), 1.0);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "w grad phi", check_report(s));
}

TEST(SceneFlow, HelfrichL2UsesProjectedVariation)
{
  std::string yaml = with_flow("flow: {}\n");
  yaml.replace(yaml.find("cahn_hilliard"), 13, "helfrich_penalty");
  const Scene s = parse_scene(yaml, "flow.yaml");
  EXPECT_EQ(flow_capillary(s), 1.0);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "dE/dphi of (3.84)", check_report(s));
}

TEST(SceneFlow, CheckReport)
{
  const std::string r = check_report(parse_scene(with_flow(flow_section), "flow.yaml"));
  for (const char* text : {"Navier-Stokes (Re = 100)", "inside 0.1, outside 1",
                           "inside 0.2, outside 1", "rho(phi) (0, -98) + (0.5, 0)",
                           "2.59862 mu grad phi", "sigma 2.45", "left free_slip",
                           "right open", "bottom no_slip", "top moving (1, 0)",
                           "-flow_mat_mumps_icntl_7 2"})
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, text, r);
}

TEST(SceneFlow, Errors)
{
  EXPECT_ERROR(with_flow("flow: {viscousity: {inside: 1}}\n"),
               "flow.viscousity: unknown key; allowed keys in flow: equations, density");
  EXPECT_ERROR(with_flow("flow: {equations: euler}\n"),
               "flow.equations: unknown value \"euler\"; allowed: stokes, navier_stokes");
  EXPECT_ERROR(with_flow("flow: {solver: lu}\n"),
               "flow.solver: unknown value \"lu\"; allowed: direct, reuse");
  EXPECT_ERROR(with_flow("flow: {density: {inside: 0}}\n"),
               "flow.density.inside: found 0, expected a number > 0");
  EXPECT_ERROR(with_flow("flow: {density: {middle: 1}}\n"), "flow.density.middle: unknown key");
  EXPECT_ERROR(with_flow("flow: {gravity: [0, -1, 0]}\n"),
               "flow.gravity: found a list of 3 items, expected a list of 2");
  EXPECT_ERROR(with_flow("flow: {surface_tension: -1}\n"), "flow.surface_tension: found -1");
  EXPECT_ERROR(with_flow("flow: {walls: {front: no_slip}}\n"),
               "flow.walls.front: unknown key; allowed keys in flow.walls: left, right, bottom, top");
  EXPECT_ERROR(with_flow("flow: {walls: {top: sticky}}\n"),
               "flow.walls.top: unknown value \"sticky\"; allowed: no_slip, free_slip, moving, open");
  EXPECT_ERROR(with_flow("flow: {walls: {top: moving}}\n"),
               "flow.walls.top: a moving wall needs its velocity");
  EXPECT_ERROR(with_flow("flow: {walls: {top: {type: moving}}}\n"),
               "flow.walls.top.velocity: missing");
  EXPECT_ERROR(with_flow("flow: {walls: {top: {type: no_slip, velocity: [1, 0]}}}\n"),
               "flow.walls.top.velocity: only a moving wall has a velocity");
  EXPECT_ERROR(with_flow("flow: {petsc: {-ksp_type: preonly}}\n"), "without the leading '-'");
  EXPECT_ERROR(base_scene + std::string("output: {fields: [phi, v]}\n"),
               "field \"v\" is not solved for by model cahn_hilliard; allowed: phi, mu");
  std::string ac = with_flow("flow: {}\n");
  ac.replace(ac.find("cahn_hilliard"), 13, "allen_cahn");
  EXPECT_ERROR(ac, "flow: phase_field.model allen_cahn cannot be coupled to the flow");
  std::string hm1 = with_flow("flow: {surface_tension: 1}\n");
  hm1.replace(hm1.find("cahn_hilliard"), 13, "helfrich_hm1");
  EXPECT_ERROR(hm1, "flow.surface_tension: model helfrich_hm1 takes its interface force from its energy");
  // --set reaches the flow keys
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "flow.density.inside",
                      error_of(with_flow(flow_section), {"flow.density.inside=-2"}));
}
