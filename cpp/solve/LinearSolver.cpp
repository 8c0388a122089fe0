#include "solve/LinearSolver.h"
#include "util/Clock.h"
#include <algorithm>

namespace cellphase
{
LinearSolver::LinearSolver(MPI_Comm comm, const std::string& prefix,
                           const std::map<std::string, std::string>& options, Symmetry symmetry)
    : prefix_(prefix), symmetry_(symmetry)
{
  // Defaults first, the scene's options on top: both go to PETSc's options database
  // under this solver's prefix so that several solvers do not share settings.
  std::map<std::string, std::string> all{{"ksp_type", "preonly"},
                                         {"pc_type", symmetry == Symmetry::general ? "lu" : "cholesky"},
                                         {"pc_factor_mat_solver_type", "mumps"}};
  if (symmetry == Symmetry::general)
  {
    // Unsymmetric LU (the Taylor phase field, Navier-Stokes): MUMPS's automatic choice
    // recomputes an iterative row/column scaling at every factorisation (about 20 % of a
    // refactorisation here) and orders with PORD, whose analysis after each remesh costs
    // as much as three factorisations and runs on one rank. AMF analyses in a fraction of
    // that, fills a few per cent less than AMD/QAMD, and its tree splits better over two
    // ranks (vesicle: refactorisations 1.6x faster on 2 ranks, QAMD 1.45x); the unscaled
    // finite element matrices factorise to the same solution (benchmarks/vesicle_benchmark.py).
    all["mat_mumps_icntl_7"] = "2";
    all["mat_mumps_icntl_8"] = "0";
  }
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
  if (symmetry_ != Symmetry::general)
  {
    MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE);
    MatSetOption(A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE);
  }
  if (symmetry_ == Symmetry::positive_definite)
    MatSetOption(A, MAT_SPD, PETSC_TRUE);
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

void LinearSolver::solve(const std::vector<const dolfinx::la::Vector<T>*>& bs,
                         const std::vector<dolfinx::la::Vector<T>*>& xs, const std::string& what)
{
  if (bs.size() == 1)
    return solve(*bs[0], *xs[0], what);
  // Owned entries of every right-hand side as the columns of a dense matrix.
  const auto& map = *bs[0]->map();
  const int bs_ = bs[0]->bs();
  const PetscInt n = map.size_local() * bs_, N = map.size_global() * bs_;
  const PetscInt k = PetscInt(bs.size());
  MPI_Comm comm = map.comm();
  Mat B, X;
  MatCreateDense(comm, n, PETSC_DECIDE, N, k, nullptr, &B);
  MatCreateDense(comm, n, PETSC_DECIDE, N, k, nullptr, &X);
  PetscScalar* col;
  MatDenseGetArrayWrite(B, &col);
  for (PetscInt j = 0; j < k; ++j)
    std::copy_n(bs[j]->array().begin(), n, col + j * n);
  MatDenseRestoreArrayWrite(B, &col);
  const PetscErrorCode ierr = KSPMatSolve(ksp_, B, X);
  KSPConvergedReason reason;
  KSPGetConvergedReason(ksp_, &reason);
  if (ierr == 0 && reason >= 0)
  {
    const PetscScalar* out;
    MatDenseGetArrayRead(X, &out);
    for (PetscInt j = 0; j < k; ++j)
      std::copy_n(out + j * n, n, xs[j]->mutable_array().begin());
    MatDenseRestoreArrayRead(X, &out);
  }
  MatDestroy(&B);
  MatDestroy(&X);
  if (ierr != 0 || reason < 0)
    throw SolverError("linear solver of " + what + " did not converge (KSP reason "
                      + std::to_string(int(reason)) + ", PETSc error " + std::to_string(int(ierr))
                      + ")");
  for (auto* x : xs)
    x->scatter_fwd();
}
} // namespace cellphase
