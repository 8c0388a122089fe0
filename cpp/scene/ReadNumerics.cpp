#include "scene/Resolution.h"
#include "scene/Sections.h"
#include <cmath>

namespace cellphase::scene
{
using namespace yaml;

namespace
{
void read_mesh(const Section& m, Mesh& mesh)
{
  m.allow_only({"adaptive", "remesh_every", "points_across_interface", "refine_threshold",
                "refine_inside", "inside_coarser_by", "max_levels", "cell_meshes", "own_margin",
                "partition", "stripe_width"});
  mesh.adaptive = m.boolean("adaptive", mesh.adaptive);
  if (!mesh.adaptive)
  {
    // The uniform base mesh: the refinement keys would have no effect.
    for (const char* key : {"remesh_every", "points_across_interface", "refine_threshold",
                            "refine_inside", "inside_coarser_by", "max_levels"})
      if (m.has(key))
        m.fail(key, "has no effect with numerics.mesh.adaptive: false (the base mesh of "
                    "domain.resolution is used as it is); remove it");
    mesh.remesh_every = 0;
    mesh.max_levels = 0;
  }
  mesh.remesh_every = m.integer("remesh_every", mesh.remesh_every, non_negative());
  mesh.points_across_interface =
      m.number("points_across_interface", mesh.points_across_interface, positive());
  mesh.refine_threshold = m.number("refine_threshold", mesh.refine_threshold, open(0, 1));
  if (m.has("refine_inside"))
    mesh.refine_inside = m.boolean("refine_inside", false);
  mesh.inside_coarser_by = m.integer("inside_coarser_by", 0, closed(0, 20));
  mesh.max_levels = m.integer("max_levels", mesh.max_levels, closed(0, 20));
  mesh.cell_meshes = m.choice<Mesh::CellMeshes>(
      "cell_meshes", mesh.cell_meshes,
      {{"shared", Mesh::CellMeshes::shared}, {"own", Mesh::CellMeshes::own}});
  if (m.has("own_margin"))
    mesh.own_margin = m.number("own_margin", positive());
  if (m.has("partition"))
    mesh.partition = m.choice<Mesh::Partition>(
        "partition", Mesh::Partition::graph,
        {{"graph", Mesh::Partition::graph}, {"stripes", Mesh::Partition::stripes}});
  if (m.has("stripe_width"))
  {
    mesh.stripe_width = m.number("stripe_width", positive());
    if (mesh.partition_or_default() != Mesh::Partition::stripes)
      m.fail("stripe_width", "is only used with partition: stripes (the partition here is "
                             "graph); remove it or set partition: stripes");
  }
}

/// numerics.stop_when_settled; the observable is checked against the run's columns when
/// the first row is made (they depend on the sub-problems).
std::optional<SettledStop> read_settled_stop(const Section& n, double end_time)
{
  if (!n.has("stop_when_settled"))
    return std::nullopt;
  const Section w = n.section("stop_when_settled");
  w.allow_only({"observable", "over", "relative", "absolute", "after"});
  for (const char* key : {"observable", "over"})
    if (!w.has(key))
      w.fail(key, "missing; e.g. stop_when_settled: {observable: cell_velocity_x, over: 5, "
                  "relative: 0.01}");
  SettledStop stop;
  stop.observable = w.string("observable", "");
  stop.over = w.number("over", positive());
  if (stop.over >= end_time)
    w.fail("over", "found " + fmt(stop.over) + ", expected less than numerics.end_time ("
                       + fmt(end_time) + "): the window must fit into the run");
  stop.relative = w.number("relative", stop.relative, non_negative());
  stop.absolute = w.number("absolute", stop.absolute, non_negative());
  if (stop.relative == 0 && stop.absolute == 0)
    w.fail("relative", "and absolute are both 0: nothing would ever count as settled");
  stop.after = w.number("after", 0.0, non_negative());
  return stop;
}

std::optional<AdaptiveDt> read_adaptive_dt(const Section& n, const Numerics& num)
{
  if (!n.has("adaptive_dt"))
    return std::nullopt;
  const Section a = n.section("adaptive_dt");
  a.allow_only({"tolerance", "dt_min", "dt_max", "growth", "safety", "cfl"});
  AdaptiveDt ad;
  ad.tolerance = a.number("tolerance", positive());
  ad.dt_min = a.number("dt_min", num.dt * 1e-3, positive());
  ad.dt_max = a.number("dt_max", num.end_time, positive());
  if (ad.dt_min > num.dt)
    a.fail("dt_min", "found " + fmt(ad.dt_min) + ", expected at most numerics.dt = "
                         + fmt(num.dt) + " (the first step)");
  if (ad.dt_max < num.dt)
    a.fail("dt_max", "found " + fmt(ad.dt_max) + ", expected at least numerics.dt = "
                         + fmt(num.dt) + " (the first step)");
  if (num.end_time / ad.dt_min > 1e9)
    a.fail("dt_min", "end_time / dt_min = " + fmt(num.end_time / ad.dt_min)
                         + " steps; at most 1e9 steps are allowed");
  // Variable-step BDF2 is zero-stable for step ratios below 1 + sqrt 2.
  ad.growth = a.number("growth", ad.growth, open(1, 1 + std::sqrt(2.0)));
  ad.safety = a.number("safety", ad.safety, Range{0, 1, true, false}); // (0, 1]
  ad.cfl = a.number("cfl", ad.cfl, positive());
  return ad;
}

void read_limits(const Section& l, Model model, Limits& limits)
{
  l.allow_only({"phi_bound", "volume_drift"});
  // phi stays in [-1, 1] up to small overshoots; 1 itself would stop sound runs.
  limits.phi_bound = l.number("phi_bound", limits.phi_bound, open(1, 1e300));
  if (l.has("volume_drift"))
    limits.volume_drift = l.number("volume_drift", positive());
  else if (model != Model::allen_cahn) // every other model conserves the volume
    limits.volume_drift = 0.01;
}
} // namespace

void check_coupling(const Section& top, const Scene& s)
{
  const Section n = top.section("numerics");
  if (n.has("coupling") && (!s.flow || s.numerics.time_scheme != Numerics::TimeScheme::bdf2))
    n.fail("coupling", "chooses what drives a BDF2 flow step: it needs a flow and "
                       "numerics.time_scheme: bdf2 (backward Euler drives the flow by phi^n)");
}

void read_numerics(const Section& top, Scene& s)
{
  if (!top.has("numerics"))
    top.fail("numerics", "missing; every scene needs numerics.epsilon, numerics.dt and "
                         "numerics.end_time");
  const Section n = top.section("numerics");
  n.allow_only({"epsilon", "dt", "end_time", "linearisation", "stabilisation", "mesh", "limits",
                "petsc", "split", "solver", "stop_when_settled", "time_scheme", "adaptive_dt",
                "coupling"});
  Numerics& num = s.numerics;
  num.epsilon = n.number("epsilon", positive());
  num.dt = n.number("dt", positive());
  num.end_time = n.number("end_time", positive());
  if (num.end_time < num.dt)
    n.fail("end_time", "found " + fmt(num.end_time) + ", expected a number >= numerics.dt ("
                           + fmt(num.dt) + "), so that at least one step is taken");
  // Step counts are stored as int downstream; far beyond that no run would finish anyway.
  if (num.end_time / num.dt > 1e9)
    n.fail("dt", "end_time / dt = " + fmt(num.end_time / num.dt)
                     + " steps; at most 1e9 steps are allowed, so dt must be >= end_time / 1e9 = "
                     + fmt(num.end_time / 1e9));
  num.linearisation = n.choice<Linearisation>(
      "linearisation", num.linearisation,
      {{"taylor", Linearisation::taylor}, {"stabilised", Linearisation::stabilised}});
  num.stabilisation = n.number("stabilisation", num.stabilisation, non_negative());
  if (num.linearisation == Linearisation::stabilised && s.phase_field.degenerate_mobility)
    n.fail("linearisation", "stabilised keeps the matrix constant, but the degenerate mobility "
                            "gamma W(phi^n) (phase_field.mobility_law) changes it every step; "
                            "use taylor");
  read_mesh(n.section("mesh"), num.mesh);
  if (num.mesh.stripe_width && *num.mesh.stripe_width < base_cell_size(s.domain))
    n.section("mesh").fail("stripe_width",
                           "found " + fmt(*num.mesh.stripe_width) + ", expected at least the base "
                           "cell size " + fmt(base_cell_size(s.domain))
                           + " (narrower stripes scatter single cells among the ranks)");
  if (num.mesh.cell_meshes == Mesh::CellMeshes::own)
  {
    const Section m = n.section("mesh");
    if (s.phase_field.model == Model::allen_cahn_volume)
      m.fail("cell_meshes", "own meshes do not suit allen_cahn_volume, whose multiplier (2.27) "
                            "acts on the whole domain; use cell_meshes: shared");
    // The edge then lies >= 8 epsilon from the zero level set, where |phi + 1| < 2e-5.
    if (num.mesh.own_margin && *num.mesh.own_margin < 6 * num.epsilon)
      m.fail("own_margin", "found " + fmt(*num.mesh.own_margin) + ", expected at least "
                               "6 epsilon = " + fmt(6 * num.epsilon)
                               + " (phi must be -1 to 2e-5 at the edge of a cell's mesh)");
  }
  read_limits(n.section("limits"), s.phase_field.model, num.limits);
  num.stop_when_settled = read_settled_stop(n, num.end_time);
  read_petsc_options(n.section("petsc"), num.petsc);
  if (n.has("split"))
    num.split = n.strings("split"); // checked against the plan in check_split
  num.solver = read_solver(n, num.solver);
  num.time_scheme = n.choice("time_scheme", num.time_scheme,
                             {{"euler", Numerics::TimeScheme::euler},
                              {"bdf2", Numerics::TimeScheme::bdf2}});
  num.adaptive_dt = read_adaptive_dt(n, num);
  num.coupling = n.choice("coupling", num.coupling,
                          {{"extrapolated", Numerics::Coupling::extrapolated},
                           {"lagged", Numerics::Coupling::lagged}});
  if (num.time_scheme == Numerics::TimeScheme::bdf2)
  {
    // BDF2 needs the Taylor linearisation about its extrapolation; the stabilised scheme's
    // S (phi - phi^n) is a first-order perturbation, and (2.27)'s multiplier is explicit.
    if (num.linearisation == Linearisation::stabilised)
      n.fail("time_scheme", "bdf2 needs numerics.linearisation: taylor (the stabilised "
                            "scheme's S (phi - phi^n) term is first order in dt)");
    if (s.phase_field.model == Model::allen_cahn_volume)
      n.fail("time_scheme", "bdf2 does not suit allen_cahn_volume, whose multiplier (2.27) is "
                            "explicit (first order); use euler");
  }
}

} // namespace cellphase::scene
