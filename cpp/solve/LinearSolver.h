// A linear solver with its own options prefix. Direct MUMPS LU by default (LDL^T for a
// symmetric operator); the scene's numerics.petsc options override. Options that ask for
// MUMPS and nothing but its controls go to MUMPS directly (MumpsSolver); any other
// options build a PETSc KSP. Factorisations are reused until the operator changes.
#pragma once
#include "compat/Dolfinx.h"
#include "solve/MumpsSolver.h"
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cellphase
{
/// A linear solve that did not converge (KSP reason < 0).
struct SolverError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// What the caller knows about every operator it will pass: a symmetric one is factorised
/// as L D L^T (MUMPS keeps half the entries of LU, and a solve reads half as much).
enum class Symmetry
{
  general,
  symmetric,
  positive_definite
};

class LinearSolver
{
public:
  LinearSolver(MPI_Comm comm, const std::string& prefix,
               const std::map<std::string, std::string>& options,
               Symmetry symmetry = Symmetry::general);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Use A from now on and factorise it (the values of A changed or A is new).
  /// Returns the wall time of the set-up (factorisation for LU).
  double set_operator(Mat A);
  /// x = A^-1 b with the last factorisation; throws SolverError naming `what` on failure.
  void solve(const dolfinx::la::Vector<T>& b, dolfinx::la::Vector<T>& x, const std::string& what);
  /// xs[i] = A^-1 bs[i] for all i in one call: a direct solver sweeps its factors once
  /// for all right-hand sides (BLAS-3), which is cheaper than one solve after the other.
  void solve(const std::vector<const dolfinx::la::Vector<T>*>& bs,
             const std::vector<dolfinx::la::Vector<T>*>& xs, const std::string& what);

  /// Reuse factorisations (numerics.solver: reuse): set_operator keeps the factors of an
  /// earlier matrix as long as they serve, and solve runs GMRES on the current matrix
  /// preconditioned by them to relative residual `rtol`. A solve that needs more than
  /// `max_iterations` (or fails) factorises the current matrix and solves directly; one
  /// that needs more than `refactorise_after` factorises at the next set_operator.
  /// Only with MUMPS called directly (the default direct solver).
  void reuse_factorisations(double rtol, int max_iterations, int refactorise_after);
  /// Factorisations and Krylov iterations (of the reuse GMRES or of a PETSc KSP) since
  /// the last call (for the observables).
  std::pair<int, int> take_counts();

private:
  /// GMRES on A_ preconditioned by the factors held; false if it did not reach rtol.
  bool solve_preconditioned(const dolfinx::la::Vector<T>& b, dolfinx::la::Vector<T>& x);
  void factorise(Mat A);
  void create_ksp(MPI_Comm comm);
  void solve_directly(const std::vector<const dolfinx::la::Vector<T>*>& bs,
                      const std::vector<dolfinx::la::Vector<T>*>& xs, const std::string& what);

  std::map<std::string, std::string> options_; ///< defaults with the scene's on top
  KSP ksp_ = nullptr;                          ///< any solver PETSc offers
  std::unique_ptr<MumpsSolver> mumps_;         ///< or MUMPS, called directly
  std::string prefix_;
  Symmetry symmetry_;
  // Reused factorisations
  bool reuse_ = false;
  double rtol_ = 1e-10;
  int max_iterations_ = 30, refactorise_after_ = 8;
  Mat current_ = nullptr;      ///< the operator of the next solves
  Mat factorised_ = nullptr;   ///< the matrix (object) whose values were factorised last
  bool factors_current_ = false; ///< the factors are those of current_'s present values
  bool refactorise_ = true;    ///< factorise at the next set_operator
  PetscInt factor_rows_ = -1;  ///< global rows of the factorised matrix
  KSP gmres_ = nullptr;        ///< GMRES with the factors as a shell preconditioner
  int factorisations_ = 0, iterations_ = 0;
};
} // namespace cellphase
