// The membrane concentration c of the concentration-based inextensibility (3.70)-(3.72):
// transported with the flow's velocity, c = 1 where the membrane has its initial area,
// c < 1 where it is stretched. Solved after the flow and the phase field of each step
// (operator split of 5.3); the flow reads c in the penalty of (3.71).
#pragma once
#include "compat/Dolfinx.h"
#include "compat/Periodic.h"
#include "physics/FormTable.h"
#include "solve/LinearSolver.h"
#include <memory>
#include <vector>

namespace cellphase
{
class ConcentrationModule
{
public:
  /// d_c of (3.70); `periodic` axes as for the other fields.
  ConcentrationModule(double diffusion, std::vector<int> periodic, MPI_Comm comm);

  /// On a (new) mesh: phi_cells (scalar P2) for P_phi and the initial c (scalar P2 on this
  /// mesh; null: c = 1). The velocity follows with set_velocity (the flow reads c, so c
  /// exists before the flow's velocity on a new mesh).
  void attach(std::shared_ptr<const Function> phi_cells,
              std::shared_ptr<const Function> initial = nullptr);
  /// The flow's velocity (vector P2 on the same mesh) that transports c.
  void set_velocity(std::shared_ptr<const Function> velocity);
  /// c^n -> c^{n+1} with the current velocity and phi_cells. Returns the wall time.
  double step(double dt);
  std::shared_ptr<Function> concentration() const { return c_; }

private:
  double diffusion_;
  std::vector<int> periodic_;
  MPI_Comm comm_;
  ConcentrationForms forms_;
  ConstantMap constants_;
  std::shared_ptr<Constant> dt_;
  std::shared_ptr<const Function> phi_cells_;
  std::shared_ptr<Function> c_, c_old_;
  std::shared_ptr<Form> a_, L_;
  std::unique_ptr<PeriodicConstraint> constraint_;
  std::unique_ptr<dolfinx::la::petsc::Matrix> A_;
  std::unique_ptr<dolfinx::la::Vector<T>> b_, x_;
  std::unique_ptr<LinearSolver> solver_;
};
} // namespace cellphase
