#include "solve/PeriodicSystem.h"
#include "util/Clock.h"

namespace cellphase
{
PeriodicSystem::PeriodicSystem(std::shared_ptr<const Form> a, std::shared_ptr<const Form> L,
                               const scene::Scene& scene, MPI_Comm comm,
                               const std::string& prefix,
                               const std::map<std::string, std::string>& options,
                               scene::Numerics::Solver solver)
    : a_(std::move(a)), L_(std::move(L))
{
  auto W = a_->function_spaces()[0];
  // The domain's sides: a cell's own mesh inside them has no periodic pairs.
  constraint_ = std::make_unique<PeriodicConstraint>(W, scene.domain.lower, scene.domain.upper,
                                                     scene.domain.periodic);
  A_ = std::make_unique<dolfinx::la::petsc::Matrix>(constraint_->create_matrix(*a_));
  b_ = std::make_unique<dolfinx::la::Vector<T>>(constraint_->create_vector());
  x_ = std::make_unique<dolfinx::la::Vector<T>>(constraint_->create_vector());
  solver_ = std::make_unique<LinearSolver>(comm, prefix, options);
  if (solver == scene::Numerics::Solver::reuse)
    solver_->reuse_factorisations(1e-10, 30, 8);
}

StepTimings PeriodicSystem::solve(const std::string& what)
{
  StepTimings t;
  auto t0 = Clock::now();
  constraint_->assemble_matrix(A_->mat(), *a_, {});
  constraint_->assemble_vector(*b_, *L_, a_, {});
  t.assemble = seconds_since(t0);
  t.factorise = solver_->set_operator(A_->mat());
  auto t1 = Clock::now();
  solver_->solve(*b_, *x_, what);
  constraint_->backsubstitute(*x_);
  t.solve = seconds_since(t1);
  return t;
}
} // namespace cellphase
