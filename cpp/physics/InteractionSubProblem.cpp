#include "physics/InteractionSubProblem.h"
#include "physics/FormTable.h"
#include "util/Clock.h"
#include <algorithm>
#include <limits>

namespace cellphase
{
InteractionSubProblem::InteractionSubProblem(scene::PlanStep step, const scene::Scene& scene,
                                             MPI_Comm comm)
    : SubProblem(std::move(step)), comm_(comm), eps_(scene.numerics.epsilon),
      interaction_(scene.interaction), groups_(scene::cell_groups(scene))
{
  for (const auto& g : groups_)
    phis_.push_back(g.prefix + ".phi");
}

void InteractionSubProblem::declare(FieldRegistry& fields)
{
  fields_ = &fields;
  if (!interaction_)
    return; // overlap only
  for (const auto& g : groups_)
    for (const char* sum : {"w_sum", "B_sum"})
      fields.declare({"interaction." + g.name + "." + sum, std::string(sum) + "_" + g.name,
                      name(), FieldSpace::scalar_p2, Transfer::recompute, false});
}

void InteractionSubProblem::attach(FieldRegistry& fields)
{
  w_sum_.clear();
  B_sum_.clear();
  energy_.clear();
  if (!interaction_)
    return;
  auto V = fields.get(phis_.front())->function_space();
  const int dim = V->mesh()->topology().dim();
  for (std::size_t i = 0; i < groups_.size(); ++i)
  {
    const std::string base = "interaction." + groups_[i].name + ".";
    w_sum_.push_back(std::make_shared<Function>(V));
    B_sum_.push_back(std::make_shared<Function>(V));
    fields.set(base + "w_sum", w_sum_.back());
    fields.set(base + "B_sum", B_sum_.back());
    energy_.push_back(compat::create_form(
        *observable_forms(dim).interaction_energy, {},
        {{"phi", fields.get(phis_[i])}, {"w_sum", w_sum_.back()}},
        {{"eps", std::make_shared<const Constant>(eps_)}}, V->mesh()));
  }
  update_sums(); // for the observables of this state
}

std::array<double, 6> InteractionSubProblem::band_box(const Function& phi) const
{
  const double inf = std::numeric_limits<double>::infinity();
  std::array<double, 6> box{inf, inf, inf, -inf, -inf, -inf};
  auto x = phi.function_space()->tabulate_dof_coordinates(false);
  auto values = phi.x()->array();
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::abs(values[i]) < 1 - 1e-12)
      for (int a = 0; a < 3; ++a)
      {
        box[a] = std::min(box[a], x[3 * i + a]);
        box[3 + a] = std::max(box[3 + a], x[3 * i + a]);
      }
  for (int a = 0; a < 3; ++a)
    box[3 + a] = -box[3 + a]; // one MIN reduction for both ends
  MPI_Allreduce(MPI_IN_PLACE, box.data(), 6, MPI_DOUBLE, MPI_MIN, comm_);
  for (int a = 0; a < 3; ++a)
    box[3 + a] = -box[3 + a];
  return box;
}

void InteractionSubProblem::update_sums()
{
  const std::size_t n = groups_.size();
  std::vector<std::array<double, 6>> boxes;
  std::vector<std::span<const double>> phi;
  for (const auto& name : phis_)
  {
    auto f = fields_->get(name);
    boxes.push_back(band_box(*f));
    phi.push_back(f->x()->array());
  }
  auto overlap = [&](std::size_t i, std::size_t j)
  {
    for (int a = 0; a < 3; ++a)
      if (boxes[i][3 + a] < boxes[j][a] || boxes[j][3 + a] < boxes[i][a])
        return false;
    return true;
  };
  scene::Interaction in = *interaction_;
  const InteractionShape shape{in.r1, in.r2, in.a1, in.a2, in.a3};
  for (std::size_t i = 0; i < n; ++i)
  {
    auto w = w_sum_[i]->x()->mutable_array();
    auto B = B_sum_[i]->x()->mutable_array();
    std::fill(w.begin(), w.end(), 0.0);
    std::fill(B.begin(), B.end(), 0.0);
    for (std::size_t j = 0; j < n; ++j)
      if (j != i && overlap(i, j))
        for (std::size_t k = 0; k < w.size(); ++k)
        {
          w[k] += interaction_w(phi[j][k], eps_, shape);
          B[k] += interaction_B(phi[j][k], eps_);
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
  double worst = 0;
  std::vector<std::span<const double>> phi;
  for (const auto& name : phis_)
    phi.push_back(fields_->get(name)->x()->array());
  for (std::size_t i = 0; i < phi.size(); ++i)
    for (std::size_t j = i + 1; j < phi.size(); ++j)
      for (std::size_t k = 0; k < phi[i].size(); ++k)
        worst = std::max(worst, std::min(1 + phi[i][k], 1 + phi[j][k]) / 2);
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, comm_);
  row.values.total_energy += energy; // (7.4)
  row.values.total_with_kinetic += energy;
  row.extra.insert(row.extra.end(), {{"interaction_energy", energy}, {"overlap_max", worst}});
}
} // namespace cellphase
