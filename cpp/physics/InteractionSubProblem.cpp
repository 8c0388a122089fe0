#include "physics/InteractionSubProblem.h"
#include "mesh/OwnMesh.h"
#include "physics/FormTable.h"
#include "scene/InteractionPairs.h"
#include "util/Clock.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace cellphase
{
InteractionSubProblem::InteractionSubProblem(scene::PlanStep step, const scene::Scene& scene,
                                             MPI_Comm comm)
    : SubProblem(std::move(step)), comm_(comm), domain_(scene.domain), eps_(scene.numerics.epsilon),
      interaction_(scene.interaction), groups_(scene::cell_groups(scene)),
      own_(scene::own_meshes(scene))
{
  // Beyond `reach` from a cell's zero level set its w_j is below 1e-12 of its scale
  // (Gaussians of widths r2, a3 around 0 and a2 eps) and B(phi_j) below 1e-10 / eps.
  double reach = 10;
  if (interaction_)
  {
    potentials_ = scene::interaction_potentials(*interaction_);
    for (const auto& p : potentials_)
    {
      reach = std::max(reach, std::sqrt(27.7 * p.r2));
      if (p.a1 != 0)
        reach = std::max(reach, std::abs(p.a2) + std::sqrt(27.7 * p.a3));
    }
    for (const auto& a : groups_)
    {
      pairs_.emplace_back();
      for (const auto& b : groups_)
        pairs_.back().push_back(scene::pair_interaction(*interaction_, a.name, b.name));
    }
  }
  reach_level_ = std::max(-std::tanh(reach / std::sqrt(2.0)), -1 + 1e-12); // (7.3), d in eps
  for (const auto& g : groups_)
    phis_.push_back(scene::state_field(scene, g, "phi"));
}

void InteractionSubProblem::declare(FieldRegistry& fields)
{
  fields_ = &fields;
  if (!interaction_)
    return; // overlap only
  for (const auto& g : groups_)
    for (std::size_t k = 0; k < potentials_.size(); ++k)
      for (const std::string sum : {"w_sum", "B_sum"})
        fields.declare({scene::interaction_sum_field(g.name, sum, k),
                        sum + (k == 0 ? "" : std::to_string(k)) + "_" + g.name, name(),
                        FieldSpace::scalar_p2, Transfer::recompute, false});
}

void InteractionSubProblem::attach(FieldRegistry& fields)
{
  w_sum_.clear();
  B_sum_.clear();
  energy_.clear();
  evaluate_.clear();
  nodes_.clear();
  if (own_)
    for (const auto& name : phis_)
    {
      auto phi = fields.get(name);
      evaluate_.push_back(compat::make_evaluator(phi, -1.0));
      nodes_.push_back(phi->function_space()->tabulate_dof_coordinates(false));
    }
  if (!interaction_)
    return;
  for (std::size_t i = 0; i < groups_.size(); ++i)
  {
    auto V = fields.get(phis_[i])->function_space(); // its own mesh, or the shared one
    const int dim = V->mesh()->topology().dim();
    w_sum_.emplace_back();
    B_sum_.emplace_back();
    for (std::size_t k = 0; k < potentials_.size(); ++k)
    {
      w_sum_[i].push_back(std::make_shared<Function>(V));
      B_sum_[i].push_back(std::make_shared<Function>(V));
      fields.set(scene::interaction_sum_field(groups_[i].name, "w_sum", k), w_sum_[i][k]);
      fields.set(scene::interaction_sum_field(groups_[i].name, "B_sum", k), B_sum_[i][k]);
      energy_.push_back(compat::create_form(
          *observable_forms(dim).interaction_energy, {},
          {{"phi", fields.get(phis_[i])}, {"w_sum", w_sum_[i][k]}},
          {{"eps", std::make_shared<const Constant>(eps_)}}, V->mesh()));
    }
  }
  update_sums(); // for the observables of this state
}

namespace
{
/// The faces of a band box pass through nodes, whose coordinates differ in the last bits
/// with the cell that tabulates them (and so with the number of ranks): a tolerance of
/// round-off relative to the box's coordinates. An empty box (ends at -+infinity) gets
/// none, so that it meets no other box.
double round_off(const std::array<double, 6>& box)
{
  double scale = 1;
  for (double c : box)
    if (std::isfinite(c))
      scale = std::max(scale, std::abs(c));
  return 1e-9 * scale;
}
} // namespace

bool InteractionSubProblem::boxes_meet(const std::array<double, 6>& a,
                                       const std::array<double, 6>& b)
{
  // Boxes that touch within round-off meet (on any number of ranks: the faces of two
  // patches' boxes often pass through the same column of base-mesh nodes).
  const double pad = std::max(round_off(a), round_off(b));
  for (int d = 0; d < 3; ++d)
    if (a[3 + d] + pad < b[d] || b[3 + d] + pad < a[d])
      return false;
  return true;
}

InteractionSubProblem::Samples InteractionSubProblem::sample(std::size_t i, std::size_t j,
                                                             const std::array<double, 6>& box_j) const
{
  Samples s;
  if (!own_)
  {
    auto phi = fields_->get(phis_[j])->x()->array();
    s.nodes.resize(phi.size());
    std::iota(s.nodes.begin(), s.nodes.end(), 0);
    s.values.assign(phi.begin(), phi.end());
    return s;
  }
  const auto& x = nodes_[i];
  std::vector<double> pts;
  const double pad = round_off(box_j); // nodes on the box's faces, tabulated anywhere
  for (std::size_t k = 0; k < x.size() / 3; ++k)
  {
    bool inside = true;
    for (int d = 0; d < 3 && inside; ++d)
      inside = x[3 * k + d] >= box_j[d] - pad && x[3 * k + d] <= box_j[3 + d] + pad;
    if (inside)
    {
      s.nodes.push_back(std::int32_t(k));
      pts.insert(pts.end(), x.begin() + 3 * k, x.begin() + 3 * k + 3);
    }
  }
  s.values.resize(s.nodes.size());
  evaluate_[j](pts, s.values);
  return s;
}

std::array<double, 6> InteractionSubProblem::band_box(const Function& phi) const
{
  return box_above(phi, reach_level_);
}

std::array<double, 6> InteractionSubProblem::common_box(const std::array<double, 6>& a,
                                                        const std::array<double, 6>& b)
{
  std::array<double, 6> c;
  for (int d = 0; d < 3; ++d)
    c[d] = std::max(a[d], b[d]), c[3 + d] = std::min(a[3 + d], b[3 + d]);
  return c;
}

std::vector<std::array<double, 6>> InteractionSubProblem::band_boxes() const
{
  std::vector<std::array<double, 6>> boxes;
  for (const auto& name : phis_)
    boxes.push_back(band_box(*fields_->get(name)));
  return boxes;
}

void InteractionSubProblem::update_sums()
{
  const std::size_t n = groups_.size();
  boxes_ = band_boxes();
  const auto& boxes = boxes_;
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t k = 0; k < potentials_.size(); ++k)
    {
      w_sum_[i][k]->x()->set(0.0);
      B_sum_[i][k]->x()->set(0.0);
    }
    for (std::size_t j = 0; j < n; ++j)
      if (const auto box_j = image_near(boxes[j], boxes[i], domain_);
          j != i && boxes_meet(boxes[i], box_j))
      {
        // The pair's potential k takes its sums; In_ij enters them as In / In_ij, so that
        // the forms' 1/In makes 1/In_ij of (7.5) and (7.11) (exactly 1 for the scene's In).
        const auto [k, In_ij] = pairs_[i][j];
        const double scale = interaction_->In / In_ij;
        auto w = w_sum_[i][k]->x()->mutable_array();
        auto B = B_sum_[i][k]->x()->mutable_array();
        // Own meshes: only where both bands reach; the source (7.11) has a factor of cell i.
        const Samples s = sample(i, j, own_ ? common_box(boxes[i], box_j) : boxes[j]);
        for (std::size_t m = 0; m < s.nodes.size(); ++m)
        {
          w[s.nodes[m]] += scale * interaction_w(s.values[m], eps_, potentials_[k]);
          B[s.nodes[m]] += scale * interaction_B(s.values[m], eps_);
        }
      }
  }
}

StepTimings InteractionSubProblem::step(double)
{
  StepTimings t;
  if (!interaction_)
    return t;
  auto t0 = Clock::now();
  update_sums(); // from phi^n of every cell, explicit in (7.11)
  t.assemble = seconds_since(t0);
  return t;
}

StepTimings InteractionSubProblem::finish_step()
{
  StepTimings t;
  if (!interaction_ || !interaction_->refresh)
    return t;
  auto t0 = Clock::now();
  update_sums();
  t.assemble = seconds_since(t0);
  return t;
}

void InteractionSubProblem::observe(Observation& row)
{
  double energy = 0;
  if (interaction_)
  {
    update_sums(); // of the state observed (the phase fields have stepped since)
    for (auto& form : energy_)
      energy += compat::assemble_scalar(*form) / interaction_->In; // (7.5)
  }
  // Largest overlap of two cells at the nodes: max_x min(phi~_i, phi~_j), phi~ = (1+phi)/2.
  // With own meshes only pairs whose band boxes meet (elsewhere one phi~ is below 1e-6).
  double worst = 0;
  // The boxes of update_sums above (the same phase fields), else computed for the overlap.
  std::vector<std::array<double, 6>> boxes(phis_.size(), std::array<double, 6>{});
  if (own_)
    boxes = interaction_ ? boxes_ : band_boxes();
  for (std::size_t i = 0; i < phis_.size(); ++i)
  {
    auto phi_i = fields_->get(phis_[i])->x()->array();
    for (std::size_t j = i + 1; j < phis_.size(); ++j)
    {
      const auto box_j = image_near(boxes[j], boxes[i], domain_); // i's side of a periodic side
      if (own_ && !boxes_meet(boxes[i], box_j))
        continue;
      const Samples s = sample(i, j, own_ ? common_box(boxes[i], box_j) : boxes[j]);
      for (std::size_t m = 0; m < s.nodes.size(); ++m)
        worst = std::max(worst, std::min(1 + phi_i[s.nodes[m]], 1 + s.values[m]) / 2);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, comm_);
  row.values.total_energy += energy; // (7.4)
  row.values.total_with_kinetic += energy;
  row.extra.insert(row.extra.end(), {{"interaction_energy", energy}, {"overlap_max", worst}});
}
} // namespace cellphase
