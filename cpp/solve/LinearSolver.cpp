#include "solve/LinearSolver.h"
#include "util/Clock.h"

namespace cellphase
{
LinearSolver::LinearSolver(MPI_Comm comm, const std::string& prefix,
                           const std::map<std::string, std::string>& options)
    : prefix_(prefix)
{
  // Defaults first, the scene's options on top: both go to PETSc's options database
  // under this solver's prefix so that several solvers do not share settings.
  std::map<std::string, std::string> all{{"ksp_type", "preonly"},
                                         {"pc_type", "lu"},
                                         {"pc_factor_mat_solver_type", "mumps"}};
  for (const auto& [k, v] : options)
    all[k] = v;
  for (const auto& [k, v] : all)
    PetscOptionsSetValue(nullptr, ("-" + prefix_ + k).c_str(), v.empty() ? nullptr : v.c_str());
  KSPCreate(comm, &ksp_);
  KSPSetOptionsPrefix(ksp_, prefix_.c_str());
  KSPSetFromOptions(ksp_);
}

LinearSolver::~LinearSolver() { KSPDestroy(&ksp_); }

double LinearSolver::set_operator(Mat A)
{
  auto t0 = Clock::now();
  KSPSetOperators(ksp_, A, A);
  KSPSetUp(ksp_);
  return seconds_since(t0);
}

void LinearSolver::solve(const dolfinx::la::Vector<T>& b, dolfinx::la::Vector<T>& x,
                         const std::string& what)
{
  namespace lp = dolfinx::la::petsc;
  lp::Vector xv(lp::create_vector_wrap(x), false);
  lp::Vector bv(lp::create_vector_wrap(b), false);
  PetscErrorCode ierr = KSPSolve(ksp_, bv.vec(), xv.vec());
  KSPConvergedReason reason;
  KSPGetConvergedReason(ksp_, &reason);
  if (ierr != 0 || reason < 0)
    throw SolverError("linear solver of " + what + " did not converge (KSP reason "
                      + std::to_string(int(reason)) + ", PETSc error " + std::to_string(int(ierr))
                      + ")");
  x.scatter_fwd();
}
} // namespace cellphase
