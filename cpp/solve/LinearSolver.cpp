#include "solve/LinearSolver.h"
#include "scene/MumpsControl.h"
#include "util/Clock.h"
#include <algorithm>
#include <optional>

namespace cellphase
{
namespace
{
/// The MUMPS controls of options that ask for a MUMPS factorisation and nothing else
/// (ksp_type preonly, pc_type lu or cholesky, MUMPS controls); nullopt for any other
/// option, which a PETSc KSP then honours.
std::optional<MumpsSolver::Controls> mumps_controls(const std::map<std::string, std::string>& all)
{
  MumpsSolver::Controls c;
  for (const auto& [key, value] : all)
  {
    const bool direct = (key == "ksp_type" && value == "preonly")
                        || (key == "pc_type" && (value == "lu" || value == "cholesky"))
                        || (key == "pc_factor_mat_solver_type" && value == "mumps");
    if (direct)
      continue;
    const scene::MumpsControl m = scene::read_mumps_control(key, value);
    if (m.status != scene::MumpsControl::Status::ok)
      return std::nullopt;
    if (m.integer)
      c.icntl[m.index] = int(m.value);
    else
      c.cntl[m.index] = m.value;
  }
  return c;
}
} // namespace

LinearSolver::LinearSolver(MPI_Comm comm, const std::string& prefix,
                           const std::map<std::string, std::string>& options, Symmetry symmetry)
    : prefix_(prefix), symmetry_(symmetry)
{
  // Defaults first, the scene's options on top.
  std::map<std::string, std::string> all{{"ksp_type", "preonly"},
                                         {"pc_type", symmetry == Symmetry::general ? "lu" : "cholesky"},
                                         {"pc_factor_mat_solver_type", "mumps"}};
  if (symmetry == Symmetry::general)
  {
    // Unsymmetric LU (the Taylor phase field, Navier-Stokes): MUMPS's automatic choice
    // orders with PORD, whose analysis after each remesh costs as much as three
    // factorisations and runs on one rank. AMF analyses in a fraction of that, fills a few
    // per cent less than AMD/QAMD, and its tree splits better over two ranks (vesicle:
    // refactorisations 1.6x faster on 2 ranks, QAMD 1.45x; benchmarks/vesicle_benchmark.py).
    all["mat_mumps_icntl_7"] = "2";
    // Rows and columns scaled iteratively (7), not by the automatic choice (77, about 20 %
    // of a refactorisation): the H^-1 flow with a small mobility (an RBC, gamma = 1e-7) in
    // the thesis' plain split has pivots far below its columns' largest entries, which
    // MUMPS delays when unscaled (factorisations 3x slower); elsewhere it costs about 2 %.
    all["mat_mumps_icntl_8"] = "7";
  }
  for (const auto& [k, v] : options)
    all[k] = v;
  options_ = all;
  if (const auto controls = mumps_controls(all))
  {
    // MUMPS' SYM: 0 LU, 1 positive definite (no pivoting), 2 symmetric indefinite.
    const int sym = all.at("pc_type") == "lu" ? 0 : symmetry == Symmetry::positive_definite ? 1 : 2;
    mumps_ = std::make_unique<MumpsSolver>(comm, sym, *controls);
  }
  else
    create_ksp(comm);
}

void LinearSolver::create_ksp(MPI_Comm comm)
{
  // Under this solver's prefix in PETSc's options database, so that several solvers do
  // not share settings.
  for (const auto& [k, v] : options_)
    PetscOptionsSetValue(nullptr, ("-" + prefix_ + k).c_str(), v.empty() ? nullptr : v.c_str());
  KSPCreate(comm, &ksp_);
  KSPSetOptionsPrefix(ksp_, prefix_.c_str());
  KSPSetFromOptions(ksp_);
}

LinearSolver::~LinearSolver()
{
  KSPDestroy(&ksp_);
  KSPDestroy(&gmres_);
}

void LinearSolver::reuse_factorisations(double rtol, int max_iterations, int refactorise_after)
{
  if (!mumps_)
    return; // a PETSc KSP chosen by the scene's options: left as it is
  reuse_ = true;
  rtol_ = rtol;
  max_iterations_ = max_iterations;
  refactorise_after_ = refactorise_after;
}

std::pair<int, int> LinearSolver::take_counts()
{
  std::pair<int, int> out{factorisations_, iterations_};
  factorisations_ = iterations_ = 0;
  return out;
}

void LinearSolver::factorise(Mat A)
{
  try
  {
    mumps_->factorise(A);
  }
  catch (const MumpsError& e)
  {
    throw SolverError("the linear system '" + prefix_.substr(0, prefix_.size() - 1)
                      + "': " + e.what());
  }
  ++factorisations_;
  factorised_ = A;
  MatGetSize(A, &factor_rows_, nullptr);
  factors_current_ = true;
  refactorise_ = false;
}

double LinearSolver::set_operator(Mat A)
{
  auto t0 = Clock::now();
  if (mumps_ && MumpsSolver::reads(A))
  {
    current_ = A;
    PetscInt rows = 0;
    MatGetSize(A, &rows, nullptr);
    // Reuse: keep the factors of the same matrix's earlier values (a new mesh makes a new
    // matrix) until a solve says they no longer serve.
    if (reuse_ && !refactorise_ && A == factorised_ && rows == factor_rows_)
    {
      factors_current_ = false;
      return seconds_since(t0);
    }
    factorise(A);
    return seconds_since(t0);
  }
  if (!ksp_) // a matrix type MUMPS is not given directly: PETSc converts it
  {
    mumps_.reset();
    create_ksp(PetscObjectComm(reinterpret_cast<PetscObject>(A)));
  }
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
  if (mumps_)
    return solve_directly({&b}, {&x}, what);
  namespace lp = dolfinx::la::petsc;
  lp::Vector xv(lp::create_vector_wrap(x), false);
  lp::Vector bv(lp::create_vector_wrap(b), false);
  PetscErrorCode ierr = KSPSolve(ksp_, bv.vec(), xv.vec());
  KSPConvergedReason reason;
  KSPGetConvergedReason(ksp_, &reason);
  PetscInt its = 0;
  KSPGetIterationNumber(ksp_, &its);
  iterations_ += int(its);
  if (ierr != 0 || reason < 0)
    throw SolverError("linear solver of " + what + " did not converge (KSP reason "
                      + std::to_string(int(reason)) + ", PETSc error " + std::to_string(int(ierr))
                      + ")");
  x.scatter_fwd();
}

void LinearSolver::solve(const std::vector<const dolfinx::la::Vector<T>*>& bs,
                         const std::vector<dolfinx::la::Vector<T>*>& xs, const std::string& what)
{
  if (mumps_)
    return solve_directly(bs, xs, what);
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

namespace
{
/// The shell preconditioner: y = (factors held)^-1 x.
PetscErrorCode apply_factors(PC pc, Vec x, Vec y)
{
  void* context = nullptr;
  PCShellGetContext(pc, &context);
  auto* mumps = static_cast<MumpsSolver*>(context);
  PetscInt n = 0;
  VecGetLocalSize(x, &n);
  VecCopy(x, y);
  PetscScalar* column = nullptr;
  VecGetArray(y, &column);
  double* columns[] = {column};
  try
  {
    mumps->solve(columns, n);
  }
  catch (const MumpsError&)
  {
    VecRestoreArray(y, &column);
    return PETSC_ERR_LIB;
  }
  VecRestoreArray(y, &column);
  return 0;
}
} // namespace

bool LinearSolver::solve_preconditioned(const dolfinx::la::Vector<T>& b, dolfinx::la::Vector<T>& x)
{
  if (!gmres_)
  {
    KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(current_)), &gmres_);
    KSPSetType(gmres_, KSPGMRES);
    KSPGMRESSetRestart(gmres_, max_iterations_);
    KSPSetPCSide(gmres_, PC_RIGHT); // the true residual is the one measured
    PC pc;
    KSPGetPC(gmres_, &pc);
    PCSetType(pc, PCSHELL);
    PCShellSetContext(pc, mumps_.get());
    PCShellSetApply(pc, apply_factors);
  }
  KSPSetOperators(gmres_, current_, current_);
  KSPSetTolerances(gmres_, rtol_, 0.0, PETSC_DEFAULT, max_iterations_);
  namespace lp = dolfinx::la::petsc;
  lp::Vector xv(lp::create_vector_wrap(x), false);
  lp::Vector bv(lp::create_vector_wrap(b), false);
  const PetscErrorCode ierr = KSPSolve(gmres_, bv.vec(), xv.vec());
  KSPConvergedReason reason;
  KSPGetConvergedReason(gmres_, &reason);
  PetscInt its = 0;
  KSPGetIterationNumber(gmres_, &its);
  iterations_ += int(its);
  if (ierr != 0 || reason < 0)
    return false;
  if (its > refactorise_after_)
    refactorise_ = true; // they still served, but not for long: new ones next time
  x.scatter_fwd();
  return true;
}

void LinearSolver::solve_directly(const std::vector<const dolfinx::la::Vector<T>*>& bs,
                                  const std::vector<dolfinx::la::Vector<T>*>& xs,
                                  const std::string& what)
{
  if (reuse_ && !factors_current_)
  {
    bool served = true;
    for (std::size_t j = 0; j < bs.size() && served; ++j)
      served = solve_preconditioned(*bs[j], *xs[j]);
    if (served)
      return;
    factorise(current_); // the old factors no longer serve: the current matrix's own
  }
  // MUMPS solves in place: each x takes the owned entries of its b first.
  std::vector<double*> columns;
  const std::int64_t n = std::int64_t(bs[0]->map()->size_local()) * bs[0]->bs();
  for (std::size_t j = 0; j < bs.size(); ++j)
  {
    if (std::int64_t(bs[j]->map()->size_local()) * bs[j]->bs() != n
        || std::int64_t(xs[j]->map()->size_local()) * xs[j]->bs() != n)
      throw std::logic_error("LinearSolver: right-hand sides and solutions of different sizes");
    std::copy_n(bs[j]->array().begin(), n, xs[j]->mutable_array().begin());
    columns.push_back(xs[j]->mutable_array().data());
  }
  try
  {
    mumps_->solve(columns, n);
  }
  catch (const MumpsError& e)
  {
    throw SolverError("linear solver of " + what + " failed: " + e.what());
  }
  for (auto* x : xs)
    x->scatter_fwd();
}
} // namespace cellphase
