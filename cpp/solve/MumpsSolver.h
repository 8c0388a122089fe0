// MUMPS called directly (dmumps_c) for the direct solves of LinearSolver.
//
// PETSc 3.18's MUMPS interface builds a new VecScatter (index sets, a sorted star forest)
// for every multi-right-hand-side solve on several ranks to bring MUMPS' distributed
// solution back: about 10 ms of a 33 ms solve of the 79k-dof vesicle matrix on 2 ranks,
// a cost that does not shrink with more ranks. Here the matrix goes to MUMPS as it lies in
// PETSc's AIJ arrays (distributed input on several ranks, ICNTL(18) = 3), the right-hand
// sides stay distributed (ICNTL(20) = 10) and the solution comes back to the rows' owners
// with one all-to-all exchange.
#pragma once
#include <dmumps_c.h>
#include <petscmat.h>
#include <cstdint>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace cellphase
{
/// A MUMPS phase that failed, with MUMPS' error code INFOG(1) explained.
struct MumpsError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

class MumpsSolver
{
public:
  /// Control parameters by their index in the MUMPS user guide: ICNTL(i) and CNTL(i).
  struct Controls
  {
    std::map<int, int> icntl;
    std::map<int, double> cntl;
  };

  /// sym as MUMPS' SYM: 0 unsymmetric (LU), 1 symmetric positive definite, 2 symmetric
  /// (L D L^T with pivoting).
  MumpsSolver(MPI_Comm comm, int sym, const Controls& controls);
  ~MumpsSolver();
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  /// Whether A is stored in a form this class reads (sequential or MPI AIJ).
  static bool reads(Mat A);
  /// Factorise A. The symbolic analysis runs when A or its nonzero pattern is new; with
  /// the same pattern only the numerical factorisation is repeated.
  void factorise(Mat A);
  /// Solves A x = b in place for every column: columns[j] holds the `rows` owned rows of
  /// b_j on entry and of x_j on return (one sweep over the factors for all columns).
  void solve(std::span<double* const> columns, std::int64_t rows);

private:
  void run(int job, const char* phase);
  void read_pattern(Mat A);
  void read_values(Mat A);
  void plan_return();
  void return_solution(std::span<double* const> columns, int k);

  DMUMPS_STRUC_C id_{};
  MPI_Comm comm_;
  int ranks_ = 1;
  Mat pattern_of_ = nullptr;            ///< the matrix whose pattern MUMPS analysed
  PetscObjectState nonzero_state_ = -1; ///< and the state of that pattern
  std::vector<PetscInt> row_ranges_;    ///< first row of every rank, and the number of rows
  PetscInt first_row_ = 0, owned_rows_ = 0;
  std::vector<MUMPS_INT> rows_, cols_;  ///< 1-based global indices of the entries given
  std::vector<std::int64_t> picks_;     ///< symmetric: positions of the upper triangle's
                                        ///< entries in [diagonal block, off-diagonal block]
  std::vector<double> values_;
  std::vector<MUMPS_INT> owned_rhs_rows_; ///< 1-based global rows of the owned rhs entries
  std::vector<double> rhs_, sol_;
  std::vector<MUMPS_INT> sol_rows_;
  /// Several ranks: where the solution rows held here go. The plan (and its exchange of
  /// row numbers) is made again only when those rows or the matrix' pattern change.
  struct ReturnPlan
  {
    std::vector<MUMPS_INT> held_rows; ///< sol_rows_ the plan was made for
    std::vector<int> slot;            ///< send position of each held row
    std::vector<int> send_counts, send_offsets, recv_counts, recv_offsets;
    std::vector<int> rows_in;         ///< owned row of each received value
  };
  ReturnPlan plan_;
  bool plan_current_ = false; ///< made for the current pattern
};
} // namespace cellphase
