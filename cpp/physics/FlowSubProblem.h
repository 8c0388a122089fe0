// The flow (section 5.3, step 1) as a sub-problem: FlowModule on the mesh of the phase
// field, reading phi, the interface potential dE/dphi and, with inextensibility, the
// membrane union and concentration from the registry.
#pragma once
#include "core/SolverColumns.h"
#include "core/SubProblem.h"
#include "physics/FlowModule.h"
#include "scene/Plan.h"
#include "scene/Scene.h"
#include "solve/L2Projection.h"
#include "solve/LinearSolver.h"
#include <memory>

namespace cellphase
{
class FlowSubProblem : public SubProblem
{
public:
  FlowSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm);

  /// Forces of other sub-problems (fields <name>.force) are built after the flow, on its
  /// velocity space, and read only when stepping.
  std::vector<std::string> attach_reads() const override;
  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  StepTimings step(double dt) override;
  void observe(Observation& row) override;
  /// Second order: whether the previous state is held and its step (flow.history.*).
  void save(CheckpointData& data) const override;
  void restore(const CheckpointData& data) override;
  std::int64_t num_dofs() const override { return flow_.num_dofs(); }
  int factorisations() const override { return flow_.factorisations(); }
  int krylov_iterations() const override { return flow_.krylov_iterations(); }

private:
  SolverColumns solver_columns_{"flow"}; ///< numerics.solver: reuse
  /// Several cells: f_membrane <- L2 projection of sum_i capillary mu_i grad phi_i (7.12).
  double project_interface_force();
  /// flow.cell_force: F(x) at the velocity nodes and the phase-field dof at each node.
  void prepare_cell_force(std::shared_ptr<const Function> phi_cells);
  /// f_membrane += F(x) (1 + phi_cells)/2 at the nodes (section 7.3.1).
  void add_cell_force();
  /// f_membrane += each <name>.force the flow reads (the protrusion force rd.force, 5.7).
  void add_sub_problem_forces();
  /// cells[i].viscosity: eta <- eta_0 (1 - phi_cells)/2 + sum_i eta_i (1 + phi_i)/2 (7.12).
  void update_viscosity();

  const scene::Scene& scene_;
  MPI_Comm comm_;
  std::vector<scene::CellGroup> groups_;
  FlowModule flow_;
  FieldRegistry* fields_ = nullptr;
  // The projection of the summed force (several cells only), rebuilt on every mesh
  std::vector<std::shared_ptr<Form>> force_forms_;
  std::unique_ptr<L2Projection> force_projection_;
  // flow.cell_force, rebuilt on every mesh
  std::shared_ptr<const Function> phi_cells_;
  std::vector<double> cell_force_;           ///< F at the nodes of f_membrane (node-major)
  std::vector<std::int32_t> phi_dof_at_node_; ///< phi_cells' dof at each of those nodes
  // cells[i].viscosity (several phase fields only)
  std::vector<double> group_viscosity_; ///< eta_i of each group; empty: eta(phi_cells) (2.56)
  std::shared_ptr<Function> viscosity_;
  std::vector<std::shared_ptr<const Function>> cell_phis_;
  std::vector<std::string> force_fields_; ///< the reads named <name>.force
};
} // namespace cellphase
