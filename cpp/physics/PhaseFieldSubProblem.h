// The phase field of the scene's cells as a sub-problem of the split: PhaseFieldModule
// (the solver) plus what the time loop needs around it: its fields in the registry,
// its observables (section 5.3), the constraint targets fixed at t = 0 and the centre of
// mass continued across periodic faces, both checkpointed.
#pragma once
#include "core/SubProblem.h"
#include "physics/Observables.h"
#include "physics/PhaseFieldModule.h"
#include <array>
#include <memory>

namespace cellphase
{
class PhaseFieldSubProblem : public SubProblem
{
public:
  /// `group`: the prefix of its fields ("cell": cell.phi, cell.mu, ...).
  PhaseFieldSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm,
                       std::string group = "cell");

  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  void connect(FieldRegistry& fields) override;
  void start() override;
  StepTimings step(double dt) override;
  void observe(Observation& row) override;
  std::string health(const Observation& row) const override;
  void save(CheckpointData& data) const override;
  void restore(const CheckpointData& data) override;
  std::int64_t num_dofs() const override { return module_.num_dofs(); }
  int factorisations() const override { return module_.factorisations(); }
  int threads() const { return module_.threads(); }

private:
  std::string field(const std::string& f) const { return group_ + "." + f; }
  std::string key(const std::string& k) const { return name() + "." + k; }
  void publish_targets();
  void unwrap_centre(std::array<double, 3>& centre);

  const scene::Scene& scene_;
  std::string group_;
  PhaseFieldModule module_;
  std::unique_ptr<Observables> observables_;
  FieldRegistry* fields_ = nullptr;
  double initial_volume_ = 0;
  /// Along periodic axes: the whole periods added so far, and the centre of the last row.
  std::array<double, 3> centre_shift_{0, 0, 0}, last_centre_{0, 0, 0};
  bool have_last_centre_ = false;
};
} // namespace cellphase
