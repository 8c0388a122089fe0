// A linear system a(u, w) = L(w) on one space, assembled afresh every step under the
// scene's periodic constraint (domain.periodic) and solved by a LinearSolver with its own
// options prefix; with numerics.solver: reuse the factors of an earlier step precondition
// GMRES. The orientation field (6.16)-(6.17) and the species (5.2)-(5.4) are solved so.
#pragma once
#include "compat/Periodic.h"
#include "core/StepTimings.h"
#include "scene/Scene.h"
#include "solve/LinearSolver.h"
#include <map>
#include <memory>
#include <span>
#include <string>

namespace cellphase
{
class PeriodicSystem
{
public:
  /// a and L on the same space; `prefix`, `options` and `solver` (direct or reused
  /// factorisations) are the solver's.
  PeriodicSystem(std::shared_ptr<const Form> a, std::shared_ptr<const Form> L,
                 const scene::Scene& scene, MPI_Comm comm, const std::string& prefix,
                 const std::map<std::string, std::string>& options,
                 scene::Numerics::Solver solver);

  /// Assembles A and b from the forms' coefficients now, factorises (or reuses), solves;
  /// `what` names the system in an error. The timings of assembly, factorisation, solve.
  StepTimings solve(const std::string& what);
  /// The solution of the last solve, on the space's dofs (slaves filled in).
  std::span<const T> solution() const { return x_->array(); }
  /// Factorisations and Krylov iterations of the last solve.
  std::pair<int, int> take_counts() { return solver_->take_counts(); }

private:
  std::shared_ptr<const Form> a_, L_;
  std::unique_ptr<PeriodicConstraint> constraint_;
  std::unique_ptr<dolfinx::la::petsc::Matrix> A_;
  std::unique_ptr<dolfinx::la::Vector<T>> b_, x_;
  std::unique_ptr<LinearSolver> solver_;
};
} // namespace cellphase
