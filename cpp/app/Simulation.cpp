#include "app/Simulation.h"
#include "app/FlowSetup.h"
#include "app/StopSignal.h"
#include "io/FieldSnapshot.h"
#include "io/Progress.h"
#include "mesh/FieldTransfer.h"
#include "physics/UnionPhaseField.h"
#include "scene/Check.h"
#include "scene/Shapes.h"
#include "util/Clock.h"
#include "util/Mpi.h"
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace cellphase
{
namespace
{
std::string format(const char* fmt, ...)
{
  char buf[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

std::vector<std::string> split_names(const std::string& text)
{
  std::vector<std::string> names;
  std::istringstream in(text);
  for (std::string name; std::getline(in, name, ',');)
    names.push_back(name);
  return names;
}
} // namespace

Simulation::Simulation(const scene::Scene& scene, MPI_Comm comm, bool restart)
    : scene_(scene), comm_(comm), restart_(restart), adaptive_(scene, comm),
      module_(scene, comm),
      checkpoints_(comm, scene.output.directory, scene.output.checkpoints.keep)
{
  if (scene.flow)
    flow_ = std::make_unique<FlowModule>(flow_parameters(scene), comm);
  if (scene.flow && scene.flow->inextensibility && scene.flow->inextensibility->concentration)
    concentration_ = std::make_unique<ConcentrationModule>(
        scene.flow->inextensibility->concentration->diffusion, scene.domain.periodic, comm);
}

void Simulation::attach_flow(std::shared_ptr<const Function> velocity,
                             std::shared_ptr<const Function> concentration)
{
  if (!flow_)
    return;
  const auto& fields = module_.fields();
  MembraneFields membrane;
  if (scene_.flow->inextensibility)
  {
    membrane.phi_cells = union_phase_field({fields.at("phi")}); // (7.14); one field today
    if (concentration_)
    {
      concentration_->attach(membrane.phi_cells, concentration);
      membrane.concentration = concentration_->concentration();
    }
  }
  flow_->attach(module_.space()->mesh(), fields.at("phi"), module_.interface_potential(),
                velocity, membrane);
  module_.set_velocity(flow_->velocity());
  if (concentration_)
    concentration_->set_velocity(flow_->velocity());
}

FieldMap Simulation::all_fields() const
{
  FieldMap all = module_.fields();
  if (flow_)
  {
    all["v"] = flow_->velocity();
    all["p"] = flow_->pressure();
    if (flow_->multiplier())
      all["lambda"] = flow_->multiplier();
  }
  if (concentration_)
    all["c"] = concentration_->concentration();
  return all;
}

StepTimings Simulation::step(double dt)
{
  StepTimings t;
  if (flow_)
  {
    solving_ = "v"; // names the module if its solver fails
    flow_->set_area_target(module_.targets().area); // (3.69), fixed at the start
    const FlowTimings f = flow_->step(dt);
    t.assemble += f.assemble;
    t.factorise += f.factorise;
    t.solve += f.solve;
    t.flow = f.assemble + f.factorise + f.solve;
  }
  solving_ = "phi";
  const StepTimings p = module_.step(dt);
  t.assemble += p.assemble;
  t.factorise += p.factorise;
  t.solve += p.solve;
  if (concentration_)
  {
    solving_ = "c"; // (3.70) with v^{n+1} and phi^{n+1}
    const double seconds = concentration_->step(dt);
    t.solve += seconds;
    t.flow += seconds;
  }
  return t;
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

Simulation::LoopState Simulation::initialise()
{
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
  attach_flow(nullptr); // fluid at rest
  observables_ = std::make_unique<Observables>(scene_, module_);
  auto v = observables_->evaluate();
  module_.set_targets({v.phi_integral, v.energy_ch});
  initial_volume_ = v.volume;
  return {};
}

// Everything a checkpoint holds is what the loop needs to take the next step exactly as
// an uninterrupted run would: the mesh (as the cells refined at each level, so that it is
// rebuilt from the base mesh on any number of ranks), all fields, time, step and the
// constraint targets. The models have no random numbers and no other history.
std::string Simulation::save_checkpoint(const LoopState& at)
{
  CheckpointData data;
  data.set("format_version", 1);
  data.set("step", at.step);
  data.set("time", at.time);
  data.set("dt", scene_.numerics.dt);
  data.set("targets.volume", module_.targets().volume);
  for (int a = 0; a < 3; ++a)
  {
    data.set("centre.shift." + std::to_string(a), centre_shift_[a]);
    data.set("centre.last." + std::to_string(a), last_centre_[a]);
  }
  data.set("centre.have_last", have_last_centre_ ? 1 : 0);
  data.set("targets.area", module_.targets().area);
  data.set("initial_volume", initial_volume_);
  data.set("mesh.levels", adaptive_.levels());
  for (int level = 0; level < adaptive_.levels(); ++level)
  {
    auto all = gather_to_root(comm_, adaptive_.history()[level]);
    data.arrays["mesh.refined_centroids." + std::to_string(level)] = std::move(all);
  }
  std::string names;
  for (const auto& [name, f] : module_.fields())
  {
    save_field(*f, "field." + name, data);
    names += (names.empty() ? "" : ",") + name;
  }
  data.texts["fields"] = names;
  if (flow_)
  {
    // v^n is the flow's only history (p is recomputed each step; kept for the output).
    save_field(*flow_->velocity(), "flow.v", data);
    save_field(*flow_->pressure(), "flow.p", data);
    if (concentration_)
      save_field(*concentration_->concentration(), "concentration.c", data);
    // dE/dphi of the L2 Helfrich flows (the next flow step's force) uses them
    data.set("multipliers.volume", module_.multipliers()[0]);
    data.set("multipliers.area", module_.multipliers()[1]);
  }
  data.texts["model"] = scene::to_string(scene_.phase_field.model);
  data.texts["scene"] = scene_.resolved_yaml;
  data.texts["scene.source"] = scene_.source;
  return checkpoints_.save(data, at.step);
}

Simulation::LoopState Simulation::restore()
{
  std::string path;
  CheckpointData data;
  try
  {
    data = checkpoints_.load_newest(path);
  }
  catch (const CheckpointError& e)
  {
    throw RestartError("cannot restart from " + scene_.output.directory + ": " + e.what());
  }
  try
  {
    if (data.text("model") != scene::to_string(scene_.phase_field.model))
      throw CheckpointError("it was written by model " + data.text("model") + ", the scene gives "
                            + scene::to_string(scene_.phase_field.model));
    if (data.text("scene") != scene_.resolved_yaml)
      log("cellphase: note: the scene differs from the one %s was written with; the run "
          "continues with the scene given now\n", path.c_str());
    std::vector<std::vector<double>> history;
    for (int level = 0; level < int(data.scalar("mesh.levels")); ++level)
      history.push_back(data.array("mesh.refined_centroids." + std::to_string(level)));
    std::shared_ptr<Mesh> mesh;
    try
    {
      mesh = adaptive_.replay(history);
    }
    catch (const std::runtime_error& e)
    {
      throw CheckpointError(e.what());
    }
    auto V = create_p2_space(mesh, scene_.domain.dim);
    FieldMap fields;
    for (const auto& name : split_names(data.text("fields")))
    {
      auto f = std::make_shared<Function>(V);
      f->name = name;
      restore_field(data, "field." + name, *f);
      fields[name] = f;
    }
    module_.attach(V, fields);
    if (flow_)
    {
      if (!data.arrays.count("flow.v.block_size"))
        throw CheckpointError("it was written without flow, the scene has a flow section");
      auto v = std::make_shared<Function>(create_vector_p2_space(mesh, scene_.domain.dim));
      restore_field(data, "flow.v", *v);
      module_.set_multipliers({data.scalar("multipliers.volume"), data.scalar("multipliers.area")});
      std::shared_ptr<Function> c;
      if (concentration_)
      {
        if (!data.arrays.count("concentration.c.block_size"))
          throw CheckpointError("it was written without the membrane concentration, the scene "
                                "has flow.inextensibility.concentration");
        c = std::make_shared<Function>(V);
        restore_field(data, "concentration.c", *c);
      }
      attach_flow(v, c);
      restore_field(data, "flow.p", *flow_->pressure());
    }
    module_.set_targets({data.scalar("targets.volume"), data.scalar("targets.area")});
    initial_volume_ = data.scalar("initial_volume");
    if (data.arrays.count("centre.have_last")) // written since the centre is unwrapped
    {
      for (int a = 0; a < 3; ++a)
      {
        centre_shift_[a] = data.scalar("centre.shift." + std::to_string(a));
        last_centre_[a] = data.scalar("centre.last." + std::to_string(a));
      }
      have_last_centre_ = data.scalar("centre.have_last") != 0;
    }
    observables_ = std::make_unique<Observables>(scene_, module_);
    LoopState at{int(data.scalar("step")), data.scalar("time")};
    log("cellphase: restarting from %s (step %d, t = %g)\n", path.c_str(), at.step, at.time);
    return at;
  }
  catch (const CheckpointError& e)
  {
    throw RestartError("cannot restart from " + path + ": " + e.what());
  }
}

void Simulation::open_output(const LoopState& start)
{
  const auto& out = scene_.output;
  csv_ = std::make_unique<ObservablesCsv>(out.directory + "/observables.csv", scene_.domain.dim,
                                          comm_, restart_ ? start.step : -1);
  if (out.every > 0)
    writer_ = make_writer(start);
  int ranks;
  MPI_Comm_size(comm_, &ranks);
  log("cellphase: %s, %dD, model %s (%s), %d refinement levels, %lld dofs, %d MPI rank%s, "
      "%d assembly thread%s per rank\n",
      scene_.source.c_str(), scene_.domain.dim, scene::to_string(scene_.phase_field.model),
      scene::to_string(scene_.numerics.linearisation), adaptive_.levels(),
      (long long)(module_.num_dofs() + (flow_ ? flow_->num_dofs() : 0)), ranks,
      ranks > 1 ? "s" : "", module_.threads(), module_.threads() > 1 ? "s" : "");
}

std::unique_ptr<FieldWriter> Simulation::make_writer(const LoopState& start) const
{
  // A restart continues the index of the interrupted run, cut back to the checkpoint.
  return std::make_unique<FieldWriter>(
      comm_, scene_.output.directory, scene_.output.fields,
      restart_ ? std::optional<double>(start.time) : std::nullopt);
}

double Simulation::remesh(double& volume_change)
{
  auto t0 = Clock::now();
  auto phi = module_.fields().at("phi");
  auto mesh = adaptive_.build(compat::make_evaluator(phi));
  auto V = create_p2_space(mesh, scene_.domain.dim);
  TransferReport report;
  auto fields = transfer_fields(module_.fields(), V, report);
  std::shared_ptr<Function> velocity;
  if (flow_)
  {
    // v^n moves with the fields (interpolated; div v = 0 again after the next flow step).
    velocity = std::make_shared<Function>(create_vector_p2_space(mesh, scene_.domain.dim));
    compat::transfer(flow_->velocity(), *velocity);
  }
  std::shared_ptr<Function> concentration;
  if (concentration_)
  {
    concentration = std::make_shared<Function>(V);
    compat::transfer(concentration_->concentration(), *concentration);
  }
  module_.attach(V, fields);
  attach_flow(velocity, concentration);
  observables_ = std::make_unique<Observables>(scene_, module_);
  volume_change = report.volume_change_corrected;
  return seconds_since(t0);
}

void Simulation::keep_good_state(const LoopState& at)
{
  good_.at = at;
  for (const auto& [name, f] : all_fields())
  {
    auto x = f->x()->array();
    good_.values[name].assign(x.begin(), x.end());
  }
}

std::string Simulation::module_name(const std::string& field) const
{
  if (field == "v" || field == "p" || field == "lambda")
    return "flow module";
  if (field == "c")
    return "membrane concentration module (3.70)";
  return std::string("phase-field module (") + scene::to_string(scene_.phase_field.model) + ")";
}

void Simulation::fail(const LoopState& at, const std::string& module, const std::string& what)
{
  // Back to the fields at the start of the failed step (same mesh: remeshing happens
  // before a step), then save them as a checkpoint and as output.
  for (const auto& [name, f] : all_fields())
  {
    auto x = f->x()->mutable_array();
    const auto& good = good_.values.at(name);
    std::copy(good.begin(), good.end(), x.begin());
  }
  std::string saved;
  try
  {
    saved = save_checkpoint(good_.at);
    if (!writer_)
      writer_ = make_writer(good_.at);
    writer_->write(all_fields(), good_.at.time, good_.at.step);
    saved += " and " + writer_->index_path();
  }
  catch (const std::exception& e)
  {
    saved = std::string("nowhere (") + e.what() + ")";
  }
  throw NumericalFailure(format(
      "numerical failure in the %s at step %d, t = %g: %s; the last good "
      "state (step %d, t = %g) is in %s",
      module.c_str(), at.step, at.time, what.c_str(),
      good_.at.step, good_.at.time, saved.c_str()));
}

void Simulation::check_health(const LoopState& at, const ObservableValues& v)
{
  for (const auto& [name, f] : all_fields())
  {
    int bad = 0;
    for (double x : f->x()->array())
      bad |= !std::isfinite(x);
    MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm_);
    if (bad)
      fail(at, module_name(name), "field " + name + " is not finite (NaN or Inf)");
  }
  const auto& limits = scene_.numerics.limits;
  const double phi_abs = std::max(-v.phi_min, v.phi_max);
  if (phi_abs > limits.phi_bound)
    fail(at, module_name("phi"), format("field phi reaches %.4g, beyond the bound +-%g (numerics.limits.phi_bound); "
                    "the time step may be too large",
                    v.phi_max > -v.phi_min ? v.phi_max : v.phi_min, limits.phi_bound));
  if (limits.volume_drift && initial_volume_ != 0)
  {
    const double drift = std::abs(v.volume - initial_volume_) / std::abs(initial_volume_);
    if (drift > *limits.volume_drift)
      fail(at, module_name("phi"), format("the cell volume drifted by %.3g (relative) from %.6g to %.6g, beyond "
                      "numerics.limits.volume_drift = %g",
                      drift, initial_volume_, v.volume, *limits.volume_drift));
  }
}

void Simulation::unwrap_centre(std::array<double, 3>& centre)
{
  const auto& d = scene_.domain;
  for (int a : d.periodic)
  {
    // The centre moves less than half a period per step; a larger jump is a crossing.
    const double period = d.upper[a] - d.lower[a];
    double c = centre[a] + centre_shift_[a];
    if (have_last_centre_)
    {
      const double periods = std::round((last_centre_[a] - c) / period);
      centre_shift_[a] += periods * period;
      c += periods * period;
    }
    centre[a] = c;
  }
  last_centre_ = centre;
  have_last_centre_ = true;
}

void Simulation::record(const LoopState& at, const StepTimings& timings, double remesh_time,
                        double volume_change)
{
  StepRecord r;
  r.step = at.step;
  r.time = at.time;
  r.values = observables_->evaluate();
  unwrap_centre(r.values.center);
  if (flow_)
  {
    const FlowObservables f = flow_->observables();
    auto& v = r.values;
    v.kinetic_energy = scene::flow_reynolds(scene_) * f.kinetic_energy; // (3.12)
    v.cell_velocity = f.cell_velocity;
    v.tension_mean = f.tension_mean;
    // Cahn-Hilliard: the interface energy is (1/Ca) E_CH (3.13); Helfrich: the model's own.
    const double interface = scene_.phase_field.model == scene::Model::cahn_hilliard
                                 ? scene::flow_capillary(scene_) * v.energy_ch
                                 : v.total_energy;
    v.total_with_kinetic = v.kinetic_energy + interface;
  }
  else
    r.values.total_with_kinetic = r.values.total_energy;
  check_health(at, r.values);
  r.dofs = module_.num_dofs() + (flow_ ? flow_->num_dofs() : 0);
  r.lam_v = module_.multipliers()[0];
  r.lam_a = module_.multipliers()[1];
  r.timings = timings;
  r.remesh_time = remesh_time;
  r.remesh_volume_change = volume_change;
  auto t0 = Clock::now();
  if (writer_ && (at.step % scene_.output.every == 0 || at.step == last_step_))
    writer_->write(all_fields(), at.time, at.step);
  r.output_time = seconds_since(t0);
  csv_->write(r);
}

void Simulation::run()
{
  if (rank_of(comm_) == 0)
    std::filesystem::create_directories(scene_.output.directory);
  MPI_Barrier(comm_);
  stop_signal::install();
  last_step_ = int(scene::number_of_steps(scene_));
  LoopState at = restart_ ? restore() : initialise();
  open_output(at);
  keep_good_state(at);
  if (!restart_)
  {
    record(at, {}, 0, 0);
    save_checkpoint(at); // so that a run killed at any later moment can be restarted
  }

  const auto& nu = scene_.numerics;
  const int steps = last_step_;
  const int every = scene_.output.checkpoints.every;
  Progress progress(comm_, at.time, nu.end_time, scene_.output.progress);
  while (at.step < steps)
  {
    const int n = at.step + 1;
    double remesh_time = 0, volume_change = 0;
    if (nu.mesh.remesh_every > 0 && (n - 1) > 0 && (n - 1) % nu.mesh.remesh_every == 0)
      remesh_time = remesh(volume_change);
    keep_good_state(at);
    const double dt = std::min(nu.dt, nu.end_time - at.time);
    StepTimings timings;
    try
    {
      timings = step(dt);
    }
    catch (const SolverError& e)
    {
      fail({n, at.time + dt}, module_name(solving_), e.what());
    }
    at = {n, n == steps ? nu.end_time : at.time + dt};
    record(at, timings, remesh_time, volume_change);
    progress.update(n, at.time);
    std::string checkpoint;
    if (n == steps || (every > 0 && n % every == 0))
      checkpoint = save_checkpoint(at);
    if (n < steps && stop_signal::requested(comm_))
    {
      if (checkpoint.empty())
        checkpoint = save_checkpoint(at);
      std::string command = "cellphase run " + scene_.source;
      for (const auto& o : scene_.overrides)
        if (o.rfind("output.directory=", 0) != 0)
          command += " --set " + o;
      command += " --restart " + scene_.output.directory;
      throw Interrupted(format(
          "stopped by %s after step %d (t = %g); checkpoint written to %s. Continue with:\n  %s",
          *stop_signal::name() ? stop_signal::name() : "a signal on another rank", n, at.time,
          checkpoint.c_str(), command.c_str()));
    }
  }
  progress.finish(steps, at.time);
  log("  %d factorisations; observables in %s/observables.csv%s\n",
      module_.factorisations() + (flow_ ? flow_->factorisations() : 0),
      scene_.output.directory.c_str(),
      writer_ ? ", fields in fields.xdmf" : "");
}
} // namespace cellphase
