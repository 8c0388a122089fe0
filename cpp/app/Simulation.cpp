#include "app/Simulation.h"
#include "app/TestHooks.h"
#include "app/StopSignal.h"
#include "app/SubProblems.h"
#include "io/FieldSnapshot.h"
#include "io/Progress.h"
#include "compat/Resample.h"
#include "mesh/BaseMesh.h"
#include "mesh/FieldTransfer.h"
#include "physics/PhaseFieldSubProblem.h"
#include "scene/Check.h"
#include "scene/Resolution.h"
#include "scene/Shapes.h"
#include "util/Clock.h"
#include "util/Mpi.h"
#include "util/Split.h"
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <set>

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

/// Checkpoints since the field registry: fields under their qualified names, scalars under
/// their sub-problem's name.
constexpr int checkpoint_format = 2;

} // namespace

Simulation::Simulation(const scene::Scene& scene, MPI_Comm comm, bool restart,
                       std::vector<std::unique_ptr<SubProblem>> extra)
    : scene_(scene), comm_(comm), restart_(restart), adaptive_(scene, comm),
      split_(build_sub_problems(scene, comm)), initial_(scene::make_plan(scene).initial),
      checkpoints_(comm, scene.output.directory, scene.output.checkpoints.keep)
{
  for (auto& e : extra)
    split_.push_back(std::move(e));
  if (scene.numerics.adaptive_dt)
    step_control_.emplace(*scene.numerics.adaptive_dt, scene.numerics.dt);
  for (auto& sub : split_)
    sub->declare(fields_);
  for (const auto& key : fields_.mesh_keys())
    if (!key.empty())
      own_meshes_.emplace(key, OwnMesh(scene_, adaptive_.base()));
  check_plan();
  order_attach();
}

void Simulation::check_plan() const
{
  // The declarations must be the plan's lists (each field declared by the one that writes
  // it), and the split with any extra sub-problems must close as the scene's plan does.
  scene::Plan plan;
  plan.initial = initial_;
  for (const auto& sub : split_)
  {
    for (const auto& f : sub->writes())
      if (!fields_.declared(f) || fields_.info(f).owner != sub->name())
        throw std::logic_error(sub->name() + " writes " + f + " but does not declare it");
    plan.steps.push_back({sub->name(), sub->description(), sub->reads(), sub->writes(),
                          sub->active_from()});
  }
  for (const auto& name : fields_.names())
  {
    const auto owner = std::find_if(split_.begin(), split_.end(), [&](const auto& s)
                                    { return s->name() == fields_.info(name).owner; });
    if (owner == split_.end()
        || !std::count((*owner)->writes().begin(), (*owner)->writes().end(), name))
      throw std::logic_error("field " + name + " is declared but not in its owner's writes");
  }
  const std::string problem = scene::plan_problem(plan);
  if (!problem.empty())
    throw std::invalid_argument(problem);
}

void Simulation::order_attach()
{
  // Topological order of attach_reads -> owners (a cycle is a programming error).
  std::set<std::string> ready(initial_.begin(), initial_.end());
  std::vector<SubProblem*> pending;
  for (auto& s : split_)
    pending.push_back(s.get());
  while (!pending.empty())
  {
    auto it = std::find_if(pending.begin(), pending.end(), [&](SubProblem* s)
                           {
                             for (const auto& f : s->attach_reads())
                               if (fields_.declared(f) && !ready.count(f))
                                 return false;
                             return true;
                           });
    if (it == pending.end())
      throw std::logic_error("the sub-problems' attach_reads form a cycle");
    for (const auto& f : (*it)->writes())
      ready.insert(f);
    attach_order_.push_back(*it);
    pending.erase(it);
  }
}

void Simulation::attach_all()
{
  for (auto* sub : attach_order_)
    sub->attach(fields_);
  for (auto* sub : attach_order_)
    sub->connect(fields_);
}

StepTimings Simulation::step(double dt, double time)
{
  StepTimings t;
  for (auto& sub : split_)
  {
    if (time + 0.5 * dt < sub->active_from())
      continue; // frozen until then (reaction_diffusion.frozen_until)
    solving_ = sub.get(); // names the module if its solver fails
    t += sub->step(dt);
  }
  for (auto& sub : split_)
    if (time + 0.5 * dt >= sub->active_from())
    {
      solving_ = sub.get();
      t += sub->finish_step();
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
  fields_.set_mesh("", adaptive_.build(analytic));
  for (const auto& group : scene::cell_groups(scene_))
  {
    // Each phase field from its own cells, (7.3), on the mesh its state lives on.
    scene::InitialPhaseField own(scene::group_scene(scene_, group));
    auto formula = [&own](double x, double y, double z) { return own(x, y, z); };
    const std::string name = scene::state_field(scene_, group, "phi");
    const std::string& key = fields_.info(name).mesh;
    if (!key.empty())
    {
      // Its own mesh around its band, found at the nodes of the shared mesh (refined there).
      auto probe = std::make_shared<Function>(fields_.space("", FieldSpace::scalar_p2));
      compat::interpolate(*probe, formula);
      PointEvaluator cell = [&own](std::span<const double> pts, std::span<double> values)
      {
        for (std::size_t i = 0; i < values.size(); ++i)
          values[i] = own(pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
      };
      auto& own_mesh = own_meshes_.at(key);
      auto patch = own_mesh.build(cell, box_above(*probe, own_band_level));
      fields_.set_mesh(key, patch, own_mesh.patch_box());
    }
    auto phi = std::make_shared<Function>(fields_.space(key, FieldSpace::scalar_p2));
    compat::interpolate(*phi, formula);
    fields_.set(name, phi);
  }
  attach_all(); // the other fields start from their owners' defaults (fluid at rest)
  for (auto* sub : attach_order_)
    sub->start();
  return {};
}

// Everything a checkpoint holds is what the loop needs to take the next step exactly as
// an uninterrupted run would: the mesh (as the cells refined at each level, so that it is
// rebuilt from the base mesh on any number of ranks), the checkpointed fields of the
// registry, time, step and the sub-problems' scalars (targets, multipliers, ...).
std::string Simulation::save_checkpoint(const LoopState& at)
{
  CheckpointData data;
  data.set("format_version", checkpoint_format);
  data.set("step", at.step);
  data.set("time", at.time);
  data.set("remeshed_for_next_step", at.remeshed ? 1 : 0);
  data.set("dt", scene_.numerics.dt);
  data.set("mesh.levels", adaptive_.levels());
  for (int level = 0; level < adaptive_.levels(); ++level)
  {
    auto all = gather_to_root(comm_, adaptive_.history()[level]);
    data.arrays["mesh.refined_centroids." + std::to_string(level)] = std::move(all);
  }
  for (const auto& [key, own] : own_meshes_)
  {
    const std::string m = "mesh." + key + ".";
    data.arrays[m + "box"].assign(own.patch_box().begin(), own.patch_box().end());
    data.set(m + "levels", own.levels());
    for (int level = 0; level < own.levels(); ++level)
      data.arrays[m + "refined_centroids." + std::to_string(level)] =
          gather_to_root(comm_, own.history()[level]);
  }
  std::string names;
  for (const auto& name : fields_.names())
    if (fields_.info(name).checkpointed)
    {
      save_field(*fields_.get(name), "field." + name, data);
      names += (names.empty() ? "" : ",") + name;
    }
  data.texts["fields"] = names;
  for (const auto& sub : split_)
    sub->save(data);
  if (step_control_)
    step_control_->save(data);
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
    if (data.scalar("format_version") != checkpoint_format)
      throw CheckpointError(format("it has checkpoint format %g, this cellphase reads format %d "
                                   "(start the run again)",
                                   data.scalar("format_version"), checkpoint_format));
    if (data.text("model") != scene::to_string(scene_.phase_field.model))
      throw CheckpointError("it was written by model " + data.text("model") + ", the scene gives "
                            + scene::to_string(scene_.phase_field.model));
    if (data.text("scene") != scene_.resolved_yaml)
      log("cellphase: note: the scene differs from the one %s was written with; the run "
          "continues with the scene given now\n", path.c_str());
    std::vector<std::vector<double>> history;
    for (int level = 0; level < int(data.scalar("mesh.levels")); ++level)
      history.push_back(data.array("mesh.refined_centroids." + std::to_string(level)));
    try
    {
      fields_.set_mesh("", adaptive_.replay(history));
      for (auto& [key, own] : own_meshes_)
      {
        const std::string m = "mesh." + key + ".";
        if (!data.arrays.count(m + "box"))
          throw CheckpointError("it holds no own mesh of " + key
                                + " (it was written with numerics.mesh.cell_meshes: shared)");
        compat::Box box;
        const auto& stored_box = data.array(m + "box");
        std::copy(stored_box.begin(), stored_box.end(), box.begin());
        std::vector<std::vector<double>> own_history;
        for (int level = 0; level < int(data.scalar(m + "levels")); ++level)
          own_history.push_back(data.array(m + "refined_centroids." + std::to_string(level)));
        fields_.set_mesh(key, own.replay(box, own_history), box);
      }
    }
    catch (const std::runtime_error& e)
    {
      throw CheckpointError(e.what());
    }
    const auto stored = split(data.text("fields"));
    fields_.clear_functions();
    for (const auto& name : fields_.names())
    {
      const FieldInfo& info = fields_.info(name);
      if (!info.checkpointed)
        continue;
      if (std::find(stored.begin(), stored.end(), name) == stored.end())
        throw CheckpointError("it holds no field " + name + " of the " + owner_of(name)
                              + " (it was written by a scene without it)");
      if (info.space == FieldSpace::other)
        continue; // restored below, into the function its owner builds
      auto f = std::make_shared<Function>(fields_.space(info.mesh, info.space));
      f->name = info.label;
      restore_field(data, "field." + name, *f);
      fields_.set(name, f);
    }
    for (const auto& sub : split_)
      sub->restore(data);
    if (step_control_)
      step_control_->restore(data);
    attach_all();
    for (const auto& name : fields_.names())
      if (fields_.info(name).checkpointed && fields_.info(name).space == FieldSpace::other)
        restore_field(data, "field." + name, *fields_.get(name));
    // (Absent from checkpoints written before it was recorded: those were never remeshed.)
    LoopState at{int(data.scalar("step")), data.scalar("time"),
                 data.arrays.count("remeshed_for_next_step")
                     && data.scalar("remeshed_for_next_step") != 0};
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
  if (scene_.numerics.stop_when_settled)
  {
    settled_watch_ = std::make_unique<SettledWatch>(*scene_.numerics.stop_when_settled,
                                                    scene_.source);
    MPI_Barrier(comm_); // rank 0 has cut observables.csv back to the checkpoint
    if (restart_)
      settled_watch_->restore(read_observable(out.directory + "/observables.csv",
                                              scene_.numerics.stop_when_settled->observable));
  }
  make_writers(start); // output.every = 0 still writes the final state
  int ranks;
  MPI_Comm_size(comm_, &ranks);
  std::int64_t dofs = 0;
  int threads = 1;
  for (const auto& sub : split_)
  {
    dofs += sub->num_dofs();
    if (auto* pf = dynamic_cast<const PhaseFieldSubProblem*>(sub.get()))
      threads = std::max(threads, pf->threads());
  }
  char partition[96] = ""; // how the ranks split the meshes (mesh/BaseMesh)
  if (ranks > 1)
  {
    if (scene_.numerics.mesh.partition_or_default() == scene::Mesh::Partition::stripes)
      std::snprintf(partition, sizeof partition, " (stripes %g wide across %c)",
                    stripe_width(scene_), "xyz"[stripe_axis(scene_.domain)]);
    else
      std::snprintf(partition, sizeof partition, " (graph partition)");
  }
  log("cellphase: %s, %dD, model %s (%s), %d refinement levels, %lld dofs, %d MPI rank%s%s, "
      "%d assembly thread%s per rank\n",
      scene_.source.c_str(), scene_.domain.dim, scene::to_string(scene_.phase_field.model),
      scene::to_string(scene_.numerics.linearisation), adaptive_.levels(), (long long)dofs,
      ranks, ranks > 1 ? "s" : "", partition, threads, threads > 1 ? "s" : "");
}

void Simulation::make_writers(const LoopState& start)
{
  // A restart continues each index of the interrupted run, cut back to the checkpoint.
  const auto resume = restart_ ? std::optional<double>(start.time) : std::nullopt;
  for (const auto& key : fields_.mesh_keys())
    writers_[key] = make_field_output(scene_.output.format, comm_, scene_.output.directory,
                                      resume, key.empty() ? "fields" : key);
}

void Simulation::write_fields(double time, int step)
{
  for (const auto& [key, writer] : writers_)
    writer->write(output_fields(key), time, step);
}

FieldMap Simulation::output_fields(const std::string& key) const
{
  // "phi" is the field labelled phi, or with several cells every phi_<group>. On a cell's
  // own mesh the state own_phi_<group> is written as phi_<group>, and a field that lives
  // there only (the polar gel's P) under its own label.
  std::vector<std::string> labels;
  for (const auto& label : scene_.output.fields)
  {
    if (!fields_.by_label(label).empty())
      labels.push_back(label);
    else
      for (const auto& g : scene::cell_groups(scene_))
        labels.push_back(label + g.label_suffix);
  }
  FieldMap out;
  for (const auto& label : labels)
  {
    std::string name = fields_.by_label(key.empty() ? label : "own_" + label);
    if (name.empty() && !key.empty())
      name = fields_.by_label(label);
    if (name.empty() || fields_.info(name).mesh != key)
      continue;
    if (auto f = fields_.find(name))
      out[label] = f;
  }
  return out;
}

std::map<std::string, std::shared_ptr<Mesh>> Simulation::rebuild_meshes()
{
  std::map<std::string, std::shared_ptr<Mesh>> meshes;
  for (const auto& key : fields_.mesh_keys())
  {
    // Refine around the zero level set of every phase field on this mesh: max_i phi_i.
    // Own meshes: phi = -1 beyond the old patch.
    std::vector<PointEvaluator> phases;
    std::shared_ptr<const Function> cell_phi;
    std::shared_ptr<Function> copies; // own meshes: max_i of the copies, node by node
    for (const auto& name : fields_.names())
      if (fields_.info(name).mesh == key && fields_.shapes_mesh(name))
      {
        auto f = fields_.get(name);
        if (fields_.info(name).level_set && key.empty())
        {
          // Copies of the cells' phase fields share one space: one evaluation of their
          // maximum instead of one per cell (the marking then costs the same for any N).
          if (!copies)
          {
            copies = std::make_shared<Function>(f->function_space());
            copies->x()->set(-1.0);
            phases.push_back(compat::make_evaluator(copies));
          }
          auto m = copies->x()->mutable_array();
          auto x = f->x()->array();
          for (std::size_t i = 0; i < m.size(); ++i)
            m[i] = std::max(m[i], x[i]);
          continue;
        }
        phases.push_back(key.empty() ? compat::make_evaluator(f)
                                     : compat::make_evaluator(f, fields_.info(name).outside));
        if (fields_.info(name).transfer == Transfer::keep_integral)
          cell_phi = f;
      }
    PointEvaluator all = phases.front();
    if (phases.size() > 1)
      all = [&phases](std::span<const double> pts, std::span<double> values)
      {
        phases[0](pts, values);
        std::vector<double> other(values.size());
        for (std::size_t k = 1; k < phases.size(); ++k)
        {
          phases[k](pts, other);
          for (std::size_t i = 0; i < values.size(); ++i)
            values[i] = std::max(values[i], other[i]);
        }
      };
    meshes[key] = key.empty() ? adaptive_.build(all)
                              : own_meshes_.at(key).build(all, box_above(*cell_phi, own_band_level));
  }
  return meshes;
}

double Simulation::remesh(double& volume_change)
{
  auto t0 = Clock::now();
  std::map<std::string, std::shared_ptr<Function>> old;
  for (const auto& name : fields_.names())
    if (auto f = fields_.find(name))
      old[name] = f;
  for (auto& [key, mesh] : rebuild_meshes())
    fields_.set_mesh(key, mesh, key.empty() ? std::nullopt
                                            : std::optional(own_meshes_.at(key).patch_box()));

  std::map<std::string, std::shared_ptr<Function>> moved;
  // The fields of one space share their interpolation points, located in the old mesh once.
  std::map<std::pair<const Mesh*, const Space*>, compat::MeshTransfer> shared_transfers;
  std::map<std::pair<const Mesh*, const Space*>, compat::Resampler> patch_transfers;
  volume_change = 0;
  for (const auto& name : fields_.names())
  {
    const FieldInfo& info = fields_.info(name);
    if (info.transfer == Transfer::recompute)
      continue;
    auto f = std::make_shared<Function>(fields_.space(info.mesh, info.space));
    f->name = info.label;
    if (info.mesh.empty())
    {
      auto from_mesh = old.at(name)->function_space()->mesh();
      auto key = std::pair(from_mesh.get(), f->function_space().get());
      auto it = shared_transfers.find(key);
      if (it == shared_transfers.end())
        it = shared_transfers.emplace(key, compat::MeshTransfer(from_mesh, f->function_space())).first;
      it->second.apply(*old.at(name), *f);
    }
    else // a cell's own patch: info.outside beyond the old patch
    {
      auto key = std::pair(old.at(name)->function_space()->mesh().get(), f->function_space().get());
      auto it = patch_transfers.find(key);
      if (it == patch_transfers.end())
      {
        const auto cells = compat::local_cells(*f->function_space()->mesh());
        it = patch_transfers.emplace(key, compat::Resampler(old.at(name), f, cells, info.outside)).first;
      }
      it->second.apply(*old.at(name), *f, info.outside);
    }
    if (info.transfer == Transfer::keep_integral)
    {
      TransferReport report;
      // (3.10): the cell volume int (1 + phi) is kept, so int phi changes by
      // |old mesh| - |new mesh| (zero on the shared mesh, which covers the domain)
      const double shift = info.mesh.empty() ? 0.0
                                             : mesh_volume(old.at(name)->function_space())
                                                   - mesh_volume(f->function_space());
      restore_integral(old.at(name), f, report, shift);
      volume_change = std::max(volume_change, report.volume_change_corrected);
    }
    moved[name] = f;
  }
  old.clear();
  fields_.clear_functions();
  for (auto& [name, f] : moved)
    fields_.set(name, f);
  attach_all();
  return seconds_since(t0);
}

void Simulation::keep_good_state(const LoopState& at)
{
  good_.at = at;
  for (const auto& name : fields_.names())
    if (auto f = fields_.find(name))
    {
      auto x = f->x()->array();
      good_.values[name].assign(x.begin(), x.end());
    }
  if (step_control_) // a rejected step is repeated from here
  {
    good_.scalars = {};
    for (const auto& sub : split_)
      sub->save(good_.scalars);
  }
}

void Simulation::restore_good_state()
{
  for (const auto& name : fields_.names())
    if (auto f = fields_.find(name))
    {
      auto x = f->x()->mutable_array();
      const auto& good = good_.values.at(name);
      std::copy(good.begin(), good.end(), x.begin());
    }
  if (step_control_)
    for (const auto& sub : split_)
    {
      sub->restore(good_.scalars);
      sub->rewind();
    }
}

double Simulation::max_flow_speed() const
{
  auto v = fields_.find("flow.v");
  if (!v)
    return 0;
  const int bs = v->function_space()->dofmap()->index_map_bs();
  auto x = v->x()->array();
  double largest = 0;
  for (std::size_t i = 0; i + bs <= x.size(); i += bs)
  {
    double s = 0;
    for (int k = 0; k < bs; ++k)
      s += x[i + k] * x[i + k];
    largest = std::max(largest, s);
  }
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return std::sqrt(largest);
}

double Simulation::take_step(const LoopState& at, double dt, StepTimings& timings)
{
  for (;;)
  {
    try
    {
      timings = step(dt, at.time);
    }
    catch (const SolverError& e)
    {
      // With adaptive steps a solver that fails is a step too large: a quarter of it.
      const auto& a = scene_.numerics.adaptive_dt;
      if (!step_control_ || dt <= a->dt_min * (1 + 1e-12))
        fail({at.step + 1, at.time + dt}, solving_ ? solving_->description() : "time loop",
             e.what());
      restore_good_state();
      dt = step_control_->reject(dt, 0.25);
      continue;
    }
    if (!step_control_)
      return dt;
    double estimate = -1;
    for (const auto& sub : split_)
      estimate = std::max(estimate, sub->time_error());
    const auto verdict = step_control_->judge(dt, estimate);
    last_estimate_ = estimate;
    if (verdict.accept)
      return dt;
    restore_good_state(); // and again from t^n with the smaller step
    dt = std::min(verdict.next, scene_.numerics.end_time - at.time);
  }
}

std::string Simulation::owner_of(const std::string& field) const
{
  const std::string& owner = fields_.info(field).owner;
  for (const auto& sub : split_)
    if (sub->name() == owner)
      return sub->description();
  return owner;
}

void Simulation::fail(const LoopState& at, const std::string& module, const std::string& what)
{
  // Back to the fields at the start of the failed step (same mesh: remeshing happens
  // before a step), then save them as a checkpoint and as output.
  restore_good_state();
  std::string saved;
  try
  {
    saved = save_checkpoint(good_.at);
    if (writers_.empty())
      make_writers(good_.at);
    write_fields(good_.at.time, good_.at.step);
    saved += " and " + writers_.at("")->index_path();
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

void Simulation::check_health(const LoopState& at, const Observation& row)
{
  for (const auto& name : fields_.names())
  {
    auto f = fields_.find(name);
    int bad = 0;
    if (f)
      for (double x : f->x()->array())
        bad |= !std::isfinite(x);
    MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm_);
    if (bad)
      fail(at, owner_of(name), "field " + fields_.info(name).label + " is not finite (NaN or Inf)");
  }
  for (const auto* sub : attach_order_)
  {
    const std::string problem = sub->health(row);
    if (!problem.empty())
      fail(at, sub->description(), problem);
  }
}

void Simulation::record(const LoopState& at, const StepTimings& timings, double remesh_time,
                        double volume_change, bool last)
{
  Observation row;
  for (auto* sub : attach_order_)
    sub->observe(row);
  check_health(at, row);
  StepRecord r;
  r.step = at.step;
  r.time = at.time;
  r.values = row.values;
  r.extra = row.extra;
  for (const auto& sub : split_)
    r.dofs += sub->num_dofs();
  r.lam_v = row.lam_v;
  r.lam_a = row.lam_a;
  r.timings = timings;
  r.remesh_time = remesh_time;
  r.remesh_volume_change = volume_change;
  if (step_control_) // the step that led to this row and the rejections so far
    r.extra.insert(r.extra.end(), {{"dt", last_dt_},
                                   {"time_error", last_estimate_},
                                   {"rejected_steps", double(step_control_->rejected())}});
  auto t0 = Clock::now();
  const int every = scene_.output.every;
  if ((every > 0 && at.step % every == 0) || last)
    write_fields(at.time, at.step);
  r.output_time = seconds_since(t0);
  if (settled_watch_)
    settled_watch_->add(observable_columns(r, scene_.domain.dim));
  csv_->write(r);
}

std::optional<std::string> Simulation::settled_now() const
{
  if (!settled_watch_)
    return std::nullopt;
  std::string why = rank_of(comm_) == 0 ? settled_watch_->settled().value_or("") : "";
  int length = int(why.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm_);
  why.resize(std::size_t(length));
  MPI_Bcast(why.data(), length, MPI_CHAR, 0, comm_);
  if (why.empty())
    return std::nullopt;
  return why;
}

void Simulation::run()
{
  if (rank_of(comm_) == 0)
    std::filesystem::create_directories(scene_.output.directory);
  MPI_Barrier(comm_);
  stop_signal::install();
  LoopState at = restart_ ? restore() : initialise();
  // The steps left to end_time at the scene's dt: a restart may change numerics.dt (or
  // end_time), so they are counted from the restored time, not from t = 0.
  last_step_ = at.step + int(scene::steps_between(scene_, at.time));
  open_output(at);
  keep_good_state(at);
  const int every = scene_.output.checkpoints.every; // 0: no checkpoints
  if (!restart_)
  {
    record(at, {}, 0, 0);
    if (every > 0)
      save_checkpoint(at); // so that a run killed at any later moment can be restarted
  }

  const auto& nu = scene_.numerics;
  const int steps = last_step_;
  Progress progress(comm_, at.time, nu.end_time, scene_.output.progress);
  // A fixed step: `steps` steps, the last one shortened to end at end_time. Adaptive: until
  // end_time, each step as the error estimate of the one before says.
  auto finished = [&](const LoopState& s)
  { return step_control_ ? s.time >= nu.end_time : s.step >= steps; };
  const double finest_cell = scene::finest_cell_size(scene_);
  while (!finished(at))
  {
    const int n = at.step + 1;
    double remesh_time = 0, volume_change = 0;
    const bool remesh_due =
        nu.mesh.remesh_every > 0 && (n - 1) > 0 && (n - 1) % nu.mesh.remesh_every == 0;
    if (remesh_due && !at.remeshed)
      remesh_time = remesh(volume_change);
    at.remeshed = remesh_due;
    keep_good_state(at);
    const double time_left = nu.end_time - at.time;
    StepTimings timings;
    last_dt_ = take_step(at, step_control_ ? step_control_->next(max_flow_speed(), finest_cell,
                                                                  time_left)
                                           : std::min(nu.dt, time_left),
                         timings);
    const bool last = step_control_ ? last_dt_ >= time_left : n == steps;
    at = {n, last ? nu.end_time : at.time + last_dt_};
    test_hooks::inject_nan_after_step(fields_, n);
    test_hooks::throw_on_one_rank_after_step(n, rank_of(comm_));
    record(at, timings, remesh_time, volume_change, last);
    progress.update(n, at.time);
    std::string checkpoint;
    if (every > 0 && (last || n % every == 0))
      checkpoint = save_checkpoint(at);
    if (const auto why = !last ? settled_now() : std::nullopt)
    {
      // Settled before end_time: the final state is written and checkpointed as at the end.
      const int out_every = scene_.output.every;
      if (!(out_every > 0 && n % out_every == 0))
        write_fields(at.time, n);
      if (every > 0 && checkpoint.empty())
        save_checkpoint(at);
      progress.finish(n, at.time);
      log("  settled at step %d (t = %g), before end_time %g: %s\n", n, at.time, nu.end_time,
          why->c_str());
      log_summary();
      return;
    }
    if (!last && stop_signal::requested(comm_))
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
  progress.finish(at.step, at.time);
  if (step_control_)
    log("  adaptive time step: %d steps, %d rejected and repeated%s\n", at.step,
        step_control_->rejected(),
        step_control_->rejected_at_dt_min()
            ? format(", %d accepted at dt_min beyond the tolerance",
                     step_control_->rejected_at_dt_min()).c_str()
            : "");
  log_summary();
}

void Simulation::log_summary() const
{
  int factorisations = 0, iterations = 0;
  for (const auto& sub : split_)
  {
    factorisations += sub->factorisations();
    iterations += sub->krylov_iterations();
  }
  std::string fields_at;
  for (const auto& [key, writer] : writers_)
    fields_at += (fields_at.empty() ? ", fields in " : ", ")
                 + std::filesystem::path(writer->index_path()).filename().string();
  const std::string krylov =
      iterations > 0 ? ", " + std::to_string(iterations) + " Krylov iterations" : "";
  log("  %d factorisations%s; observables in %s/observables.csv%s\n", factorisations,
      krylov.c_str(), scene_.output.directory.c_str(), fields_at.c_str());
}
} // namespace cellphase
