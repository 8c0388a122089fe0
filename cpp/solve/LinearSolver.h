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

private:
  void create_ksp(MPI_Comm comm);
  void solve_directly(const std::vector<const dolfinx::la::Vector<T>*>& bs,
                      const std::vector<dolfinx::la::Vector<T>*>& xs, const std::string& what);

  std::map<std::string, std::string> options_; ///< defaults with the scene's on top
  KSP ksp_ = nullptr;                          ///< any solver PETSc offers
  std::unique_ptr<MumpsSolver> mumps_;         ///< or MUMPS, called directly
  std::string prefix_;
  Symmetry symmetry_;
};
} // namespace cellphase
