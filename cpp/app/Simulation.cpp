#include "app/Simulation.h"
#include "io/Progress.h"
#include "mesh/FieldTransfer.h"
#include "scene/Shapes.h"
#include "util/Clock.h"
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>

namespace cellphase
{
namespace
{
int rank_of(MPI_Comm comm)
{
  int r;
  MPI_Comm_rank(comm, &r);
  return r;
}
} // namespace

Simulation::Simulation(const scene::Scene& scene, MPI_Comm comm)
    : scene_(scene), comm_(comm), adaptive_(scene, comm), module_(scene, comm)
{
}

void Simulation::log(const char* fmt, ...) const
{
  if (rank_of(comm_) != 0)
    return;
  va_list args;
  va_start(args, fmt);
  std::vprintf(fmt, args);
  va_end(args);
  std::fflush(stdout);
}

void Simulation::initialise()
{
  const auto& out = scene_.output;
  if (rank_of(comm_) == 0)
    std::filesystem::create_directories(out.directory);
  MPI_Barrier(comm_);

  // Initial phase field (2.12) from the cells' signed distances, sampled by the mesher
  // directly so that the first mesh is refined where the analytic interface lies.
  scene::InitialPhaseField initial(scene_);
  PointEvaluator analytic = [&initial](std::span<const double> pts, std::span<double> values)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = initial(pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
  };
  auto mesh = adaptive_.build(analytic);
  auto V = create_p2_space(mesh, scene_.domain.dim);
  auto phi = std::make_shared<Function>(V);
  compat::interpolate(*phi, [&initial](double x, double y, double z) { return initial(x, y, z); });
  module_.attach(V, {{"phi", phi}});
  observables_ = std::make_unique<Observables>(scene_, module_);
  auto v = observables_->evaluate();
  module_.set_targets({v.phi_integral, v.energy_ch});

  csv_ = std::make_unique<ObservablesCsv>(out.directory + "/observables.csv", scene_.domain.dim,
                                          comm_);
  if (out.every > 0)
    writer_ = std::make_unique<FieldWriter>(comm_, out.directory + "/fields.xdmf", out.fields);
  log("cellphase: %s, %dD, model %s (%s), %d refinement levels, %lld dofs\n",
      scene_.source.c_str(), scene_.domain.dim, scene::to_string(scene_.phase_field.model),
      scene::to_string(scene_.numerics.linearisation), adaptive_.levels(),
      (long long)module_.num_dofs());
}

double Simulation::remesh(double& volume_change)
{
  auto t0 = Clock::now();
  auto phi = module_.fields().at("phi");
  auto mesh = adaptive_.build(compat::make_evaluator(phi));
  auto V = create_p2_space(mesh, scene_.domain.dim);
  TransferReport report;
  auto fields = transfer_fields(module_.fields(), V, report);
  module_.attach(V, fields);
  observables_ = std::make_unique<Observables>(scene_, module_);
  volume_change = report.volume_change_corrected;
  return seconds_since(t0);
}

void Simulation::record(int step, double time, const StepTimings& timings, double remesh_time,
                        double volume_change)
{
  StepRecord r;
  r.step = step;
  r.time = time;
  r.values = observables_->evaluate();
  r.dofs = module_.num_dofs();
  r.lam_v = module_.multipliers()[0];
  r.lam_a = module_.multipliers()[1];
  r.timings = timings;
  r.remesh_time = remesh_time;
  r.remesh_volume_change = volume_change;
  if (!std::isfinite(r.values.phi_min) || !std::isfinite(r.values.total_energy))
  {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "numerical failure in the phase-field module (%s): phi is not finite at "
                  "step %d, t = %g; the last good fields are in %s",
                  scene::to_string(scene_.phase_field.model), step, time,
                  scene_.output.directory.c_str());
    throw NumericalFailure(msg);
  }
  auto t0 = Clock::now();
  if (writer_ && step % scene_.output.every == 0)
    writer_->write(module_.fields(), time);
  r.output_time = seconds_since(t0);
  csv_->write(r);
}

void Simulation::run()
{
  initialise();
  const auto& nu = scene_.numerics;
  const int steps = int(std::ceil(nu.end_time / nu.dt - 1e-9));
  Progress progress(comm_, nu.end_time, scene_.output.progress);
  record(0, 0.0, {}, 0, 0);
  double time = 0;
  for (int n = 1; n <= steps; ++n)
  {
    double remesh_time = 0, volume_change = 0;
    if (nu.mesh.remesh_every > 0 && (n - 1) > 0 && (n - 1) % nu.mesh.remesh_every == 0)
      remesh_time = remesh(volume_change);
    const double dt = std::min(nu.dt, nu.end_time - time);
    auto timings = module_.step(dt);
    time = n == steps ? nu.end_time : time + dt;
    record(n, time, timings, remesh_time, volume_change);
    progress.update(n, time);
  }
  progress.finish(steps, time);
  log("  %d factorisations; observables in %s/observables.csv%s\n", module_.factorisations(),
      scene_.output.directory.c_str(), writer_ ? ", fields in fields.xdmf" : "");
}
} // namespace cellphase
