// The modular core: a sub-problem defined only in this file (a tracer q that decays,
// dq/dt = -q) joins a scene's split and is checkpointed, restarted, moved to new meshes,
// written and observed without a change to the time loop, the io or the registry.
#include "mpi_main.h"
#include "app/Simulation.h"
#include "io/CheckpointFile.h"
#include "mesh/FieldTransfer.h"
#include "scene/SceneLoader.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace cellphase;
namespace fs = std::filesystem;

namespace
{
/// q0 = 1 + x^2 (exact in P2, so interpolation at a remesh loses nothing), q = q0 e^{-t}.
class DecayingTracer : public SubProblem
{
public:
  DecayingTracer() : SubProblem({"tracer", "test tracer dq/dt = -q", {"cell.phi"}, {"tracer.q"}}) {}
  std::vector<std::string> attach_reads() const override { return {"cell.phi"}; }
  void declare(FieldRegistry& fields) override
  {
    fields.declare({"tracer.q", "q", name(), FieldSpace::scalar_p2, Transfer::interpolate, true});
  }
  void attach(FieldRegistry& fields) override
  {
    q_ = fields.find("tracer.q");
    if (!q_) // a new run: the initial value
    {
      q_ = std::make_shared<Function>(fields.get("cell.phi")->function_space());
      compat::interpolate(*q_, [](double x, double, double) { return 1 + x * x; });
    }
    fields.set("tracer.q", q_);
  }
  StepTimings step(double dt) override
  {
    for (auto& v : q_->x()->mutable_array())
      v *= std::exp(-dt); // exact in time
    return {};
  }
  void observe(Observation& row) override { row.extra.push_back({"tracer_integral", integral_of(q_)}); }

private:
  std::shared_ptr<Function> q_;
};

const char* scene_text = R"(
domain: {lower: [-1, -1], upper: [1, 1], resolution: [8, 8]}
cells: [{shape: circle, center: [0.1, 0], radius: 0.5}]
phase_field: {model: allen_cahn, mobility: 1}
numerics:
  epsilon: 0.08
  dt: 0.01
  end_time: 0.06
  mesh: {remesh_every: 2, points_across_interface: 3}
output: {every: 1, fields: [phi], progress: false, checkpoints: {every: 2, keep: 5}}
)";

scene::Scene make_scene(const std::string& dir, double end_time)
{
  std::ostringstream end;
  end << "numerics.end_time=" << end_time;
  auto s = scene::parse_scene(scene_text, "tracer.yaml", {"output.directory=" + dir, end.str()});
  s.output.fields.push_back("q"); // the scene reader knows only the built-in fields
  return s;
}

std::vector<std::unique_ptr<SubProblem>> tracer()
{
  std::vector<std::unique_ptr<SubProblem>> extra;
  extra.push_back(std::make_unique<DecayingTracer>());
  return extra;
}

std::string read(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The rows of observables.csv without the timing columns (wall_*), as text.
std::vector<std::string> physics_rows(const std::string& path)
{
  std::istringstream in(read(path));
  std::vector<std::string> rows, header;
  std::string line, cell;
  std::getline(in, line);
  for (std::istringstream h(line); std::getline(h, cell, ',');)
    header.push_back(cell);
  while (std::getline(in, line))
  {
    std::istringstream r(line);
    std::string kept;
    for (std::size_t i = 0; std::getline(r, cell, ','); ++i)
      if (header.at(i).rfind("wall_", 0) != 0)
        kept += cell + ",";
    rows.push_back(kept);
  }
  return rows;
}
} // namespace

TEST(Core, TestOnlySubProblemIsTransferredWrittenCheckpointedAndObserved)
{
  const std::string dir = (fs::temp_directory_path() / "cellphase_core_tracer").string();
  fs::remove_all(dir);
  auto scene = make_scene(dir, 0.06);
  Simulation sim(scene, MPI_COMM_WORLD, false, tracer());
  sim.run();

  // Stepped and moved over two remeshes (steps 3 and 5): q = (1 + x^2) e^{-t} at every node.
  auto q = sim.fields().get("tracer.q");
  auto x = q->function_space()->tabulate_dof_coordinates(false);
  auto values = q->x()->array();
  double worst = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
    worst = std::max(worst, std::abs(values[i] - (1 + x[3 * i] * x[3 * i]) * std::exp(-0.06)));
  EXPECT_LT(worst, 1e-12);
  EXPECT_NE(q->function_space()->mesh(), nullptr);

  // Observed: its own column, the exact integral int (1 + x^2) e^{-t} = (4 + 4/3) e^{-t}.
  const std::string csv = read(dir + "/observables.csv");
  EXPECT_NE(csv.find(",tracer_integral\n"), std::string::npos);
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  const double integral = std::stod(last.substr(last.rfind(',') + 1));
  EXPECT_NEAR(integral, (4 + 4.0 / 3) * std::exp(-0.06), 1e-12);
  // Written: the output index has a series of q.
  EXPECT_NE(read(dir + "/fields.xdmf").find("Name=\"q\""), std::string::npos);
  // Checkpointed under its qualified name.
  const auto data = decode(read_file(dir + "/checkpoints/checkpoint-00000006.cpk"));
  EXPECT_TRUE(data.arrays.count("field.tracer.q.values"));
}

TEST(Core, RestartContinuesTheTestSubProblemBitForBit)
{
  const std::string full = (fs::temp_directory_path() / "cellphase_core_full").string();
  const std::string cut = (fs::temp_directory_path() / "cellphase_core_cut").string();
  fs::remove_all(full);
  fs::remove_all(cut);
  auto whole = make_scene(full, 0.06);
  Simulation(whole, MPI_COMM_WORLD, false, tracer()).run();
  auto first = make_scene(cut, 0.04);
  Simulation(first, MPI_COMM_WORLD, false, tracer()).run();
  auto rest = make_scene(cut, 0.06);
  Simulation(rest, MPI_COMM_WORLD, true, tracer()).run();
  const auto a = physics_rows(full + "/observables.csv");
  const auto b = physics_rows(cut + "/observables.csv");
  ASSERT_EQ(a.size(), 7u);
  EXPECT_EQ(a, b);
}
