#include "solve/MumpsSolver.h"
#include "solve/AijBlocks.h"
#include <algorithm>
#include <cstring>
#include <numeric>

namespace cellphase
{
namespace
{
using aij::Blocks;
using aij::blocks_of;
using aij::is_type;

// MUMPS' arrays are 1-based, as in its Fortran user guide.
MUMPS_INT& icntl(DMUMPS_STRUC_C& id, int i) { return id.icntl[i - 1]; }
double& cntl(DMUMPS_STRUC_C& id, int i) { return id.cntl[i - 1]; }
int infog(const DMUMPS_STRUC_C& id, int i) { return id.infog[i - 1]; }
int info(const DMUMPS_STRUC_C& id, int i) { return id.info[i - 1]; }

/// What INFOG(1) < 0 means (MUMPS 5.5 user guide, section 8).
std::string explain(int code, int detail)
{
  switch (code)
  {
  case -5:
  case -7:
  case -13:
    return "not enough memory (" + std::to_string(detail) + " entries could not be allocated)";
  case -6:
    return "the matrix is singular in structure (structural rank " + std::to_string(detail) + ")";
  case -8:
  case -9:
  case -14:
  case -15:
  case -17:
  case -20:
    return "its workspace is too small even after enlarging it (raise mat_mumps_icntl_14)";
  case -10:
    return "the matrix is numerically singular";
  default:
    return "see the MUMPS user guide (INFO(2) = " + std::to_string(detail) + ")";
  }
}

/// A workspace estimate that numerical pivoting exceeded; worth enlarging ICNTL(14).
bool workspace_too_small(int code)
{
  return code == -8 || code == -9 || code == -14 || code == -15 || code == -17 || code == -20;
}

/// The CSR arrays and values of a sequential AIJ matrix.
struct Csr
{
  PetscInt rows = 0;
  const PetscInt* ia = nullptr;
  const PetscInt* ja = nullptr;
  const PetscScalar* values = nullptr;
  PetscInt entries() const { return rows ? ia[rows] : 0; }
};

Csr csr_of(Mat seq, bool with_values)
{
  Csr c;
  PetscBool done;
  MatGetRowIJ(seq, 0, PETSC_FALSE, PETSC_FALSE, &c.rows, &c.ia, &c.ja, &done);
  if (!done)
    throw MumpsError("MUMPS solver: cannot read the rows of the matrix");
  if (with_values)
    MatSeqAIJGetArrayRead(seq, &c.values);
  return c;
}

void release(Mat seq, Csr& c)
{
  PetscBool done;
  MatRestoreRowIJ(seq, 0, PETSC_FALSE, PETSC_FALSE, &c.rows, &c.ia, &c.ja, &done);
  if (c.values)
    MatSeqAIJRestoreArrayRead(seq, &c.values);
}
} // namespace

MumpsSolver::MumpsSolver(MPI_Comm comm, int sym, const Controls& controls) : comm_(comm)
{
  MPI_Comm_size(comm, &ranks_);
  id_.comm_fortran = MUMPS_INT(MPI_Comm_c2f(comm));
  id_.par = 1; // the host takes part in the factorisation
  id_.sym = sym;
  id_.job = -1;
  dmumps_c(&id_);
  // Silent unless the scene asks for MUMPS' statistics (mat_mumps_icntl_4).
  for (int i = 1; i <= 4; ++i)
    icntl(id_, i) = 0;
  icntl(id_, 18) = ranks_ > 1 ? 3 : 0; // the matrix as distributed by PETSc
  for (const auto& [i, v] : controls.icntl)
    icntl(id_, i) = v;
  for (const auto& [i, v] : controls.cntl)
    cntl(id_, i) = v;
  if (icntl(id_, 4) > 0)
    for (int i = 1; i <= 3; ++i)
      if (!controls.icntl.count(i))
        icntl(id_, i) = 6; // MUMPS' own default: standard output
}

MumpsSolver::~MumpsSolver()
{
  id_.job = -2;
  dmumps_c(&id_);
}

bool MumpsSolver::reads(Mat A) { return is_type(A, MATSEQAIJ) || is_type(A, MATMPIAIJ); }

void MumpsSolver::run(int job, const char* phase)
{
  id_.job = job;
  dmumps_c(&id_);
  // A numerical pivoting that needs more room than the analysis estimated: twice the
  // relaxation, a few times, before giving up.
  for (int retry = 0; retry < 3 && workspace_too_small(infog(id_, 1)) && job == 2; ++retry)
  {
    icntl(id_, 14) = std::max(2 * icntl(id_, 14), 40);
    dmumps_c(&id_);
  }
  if (infog(id_, 1) < 0)
    throw MumpsError(std::string("MUMPS ") + phase + " failed with INFOG(1) = "
                     + std::to_string(infog(id_, 1)) + ": "
                     + explain(infog(id_, 1), infog(id_, 2)));
}

void MumpsSolver::read_pattern(Mat A)
{
  PetscInt rows, cols, first_col, last_col;
  MatGetSize(A, &rows, &cols);
  if (rows != cols)
    throw MumpsError("MUMPS solver: the matrix is not square");
  const PetscInt* ranges;
  MatGetOwnershipRanges(A, &ranges);
  row_ranges_.assign(ranges, ranges + ranks_ + 1);
  plan_current_ = false; // the rows' owners are new
  PetscInt last_row;
  MatGetOwnershipRange(A, &first_row_, &last_row);
  owned_rows_ = last_row - first_row_;
  MatGetOwnershipRangeColumn(A, &first_col, &last_col);

  // The entries in the order of [diagonal block, off-diagonal block] (PETSc's value arrays);
  // a symmetric factorisation takes the upper triangle only.
  const Blocks b = blocks_of(A);
  rows_.clear();
  cols_.clear();
  picks_.clear();
  std::int64_t position = 0;
  auto add_block = [&](Mat block, auto global_column)
  {
    Csr c = csr_of(block, false);
    for (PetscInt i = 0; i < c.rows; ++i)
      for (PetscInt e = c.ia[i]; e < c.ia[i + 1]; ++e, ++position)
      {
        const PetscInt row = first_row_ + i, col = global_column(c.ja[e]);
        if (id_.sym != 0 && col < row)
          continue;
        rows_.push_back(MUMPS_INT(row + 1));
        cols_.push_back(MUMPS_INT(col + 1));
        picks_.push_back(position);
      }
    release(block, c);
  };
  add_block(b.diagonal, [&](PetscInt j) { return first_col + j; });
  if (b.off_diagonal)
    add_block(b.off_diagonal, [&](PetscInt j) { return b.off_columns[j]; });
  if (std::int64_t(picks_.size()) == position)
    picks_.clear(); // every entry, in order: the values are taken as they are
  // A copy of the values unless MUMPS reads PETSc's array itself (one rank, every entry).
  values_.resize(ranks_ > 1 || !picks_.empty() ? rows_.size() : 0);

  id_.n = MUMPS_INT(rows);
  if (ranks_ > 1)
  {
    id_.nnz_loc = MUMPS_INT8(rows_.size());
    id_.irn_loc = rows_.data();
    id_.jcn_loc = cols_.data();
  }
  else
  {
    id_.nnz = MUMPS_INT8(rows_.size());
    id_.irn = rows_.data();
    id_.jcn = cols_.data();
  }
  owned_rhs_rows_.resize(owned_rows_);
  std::iota(owned_rhs_rows_.begin(), owned_rhs_rows_.end(), MUMPS_INT(first_row_ + 1));
  run(1, "analysis");
}

void MumpsSolver::read_values(Mat A)
{
  const Blocks b = blocks_of(A);
  Csr d = csr_of(b.diagonal, true);
  Csr o;
  if (b.off_diagonal)
    o = csr_of(b.off_diagonal, true);
  const PetscInt nd = d.entries();
  if (picks_.empty())
  {
    std::memcpy(values_.data(), d.values, sizeof(double) * nd);
    if (b.off_diagonal)
      std::memcpy(values_.data() + nd, o.values, sizeof(double) * o.entries());
  }
  else
    for (std::size_t e = 0; e < picks_.size(); ++e)
      values_[e] = picks_[e] < nd ? d.values[picks_[e]] : o.values[picks_[e] - nd];
  release(b.diagonal, d);
  if (b.off_diagonal)
    release(b.off_diagonal, o);
  (ranks_ > 1 ? id_.a_loc : id_.a) = values_.data();
}

void MumpsSolver::factorise(Mat A)
{
  PetscObjectState state;
  MatGetNonzeroState(A, &state);
  if (A != pattern_of_ || state != nonzero_state_)
  {
    read_pattern(A);
    pattern_of_ = A;
    nonzero_state_ = state;
  }
  if (ranks_ == 1 && picks_.empty())
  {
    // PETSc's value array is MUMPS' input as it is (MUMPS reads A, it does not change it).
    const PetscScalar* values;
    MatSeqAIJGetArrayRead(A, &values);
    id_.a = const_cast<PetscScalar*>(values);
    try
    {
      run(2, "factorisation");
    }
    catch (...)
    {
      MatSeqAIJRestoreArrayRead(A, &values);
      throw;
    }
    MatSeqAIJRestoreArrayRead(A, &values);
    return;
  }
  read_values(A);
  run(2, "factorisation");
}

void MumpsSolver::solve(std::span<double* const> columns, std::int64_t rows)
{
  if (rows != owned_rows_)
    throw MumpsError("MUMPS solve: the vectors have " + std::to_string(rows)
                     + " owned entries, the factorised matrix " + std::to_string(owned_rows_)
                     + " owned rows");
  const int k = int(columns.size());
  const std::size_t n = std::size_t(owned_rows_);
  rhs_.resize(n * k);
  for (int j = 0; j < k; ++j)
    std::copy_n(columns[j], n, rhs_.data() + j * n);
  id_.nrhs = k;
  if (ranks_ == 1)
  {
    icntl(id_, 20) = 0; // dense right-hand sides, overwritten by the solution
    icntl(id_, 21) = 0;
    id_.rhs = rhs_.data();
    id_.lrhs = MUMPS_INT(n);
    run(3, "solve");
    for (int j = 0; j < k; ++j)
      std::copy_n(rhs_.data() + j * n, n, columns[j]);
    return;
  }
  icntl(id_, 20) = 10; // distributed right-hand sides: every rank gives its owned rows
  icntl(id_, 21) = 1;  // distributed solution: every rank gets the rows of its fronts
  id_.nloc_rhs = MUMPS_INT(n);
  id_.lrhs_loc = MUMPS_INT(n);
  id_.irhs_loc = owned_rhs_rows_.data();
  id_.rhs_loc = rhs_.data();
  const int held = info(id_, 23); // rows of the solution on this rank, set by the factorisation
  id_.lsol_loc = held;
  sol_.resize(std::size_t(held) * k);
  sol_rows_.resize(held);
  id_.sol_loc = sol_.data();
  id_.isol_loc = sol_rows_.data();
  run(3, "solve");
  return_solution(columns, k);
}

void MumpsSolver::plan_return()
{
  // Every solution row to the rank that owns it: the counts, then the row numbers (local to
  // the owner); the values follow at every solve in return_solution.
  ReturnPlan& p = plan_;
  p.held_rows = sol_rows_;
  const int held = int(sol_rows_.size());
  std::vector<int> owner(held);
  p.send_counts.assign(ranks_, 0);
  for (int i = 0; i < held; ++i)
  {
    const PetscInt row = sol_rows_[i] - 1;
    owner[i] = int(std::upper_bound(row_ranges_.begin(), row_ranges_.end(), row)
                   - row_ranges_.begin()) - 1;
    ++p.send_counts[owner[i]];
  }
  p.send_offsets.assign(ranks_ + 1, 0);
  std::partial_sum(p.send_counts.begin(), p.send_counts.end(), p.send_offsets.begin() + 1);
  p.slot.resize(held);
  std::vector<int> rows_out(held), fill(p.send_offsets.begin(), p.send_offsets.end() - 1);
  for (int i = 0; i < held; ++i)
  {
    p.slot[i] = fill[owner[i]]++;
    rows_out[p.slot[i]] = int(sol_rows_[i] - 1 - row_ranges_[owner[i]]);
  }
  p.recv_counts.resize(ranks_);
  MPI_Alltoall(p.send_counts.data(), 1, MPI_INT, p.recv_counts.data(), 1, MPI_INT, comm_);
  p.recv_offsets.assign(ranks_ + 1, 0);
  std::partial_sum(p.recv_counts.begin(), p.recv_counts.end(), p.recv_offsets.begin() + 1);
  const int received = p.recv_offsets[ranks_];
  if (received != owned_rows_)
    throw MumpsError("MUMPS solve returned " + std::to_string(received) + " of the "
                     + std::to_string(owned_rows_) + " owned rows of the solution");
  p.rows_in.resize(received);
  MPI_Alltoallv(rows_out.data(), p.send_counts.data(), p.send_offsets.data(), MPI_INT,
                p.rows_in.data(), p.recv_counts.data(), p.recv_offsets.data(), MPI_INT, comm_);
  plan_current_ = true;
}

void MumpsSolver::return_solution(std::span<double* const> columns, int k)
{
  // The rows held here come from MUMPS' mapping of the fronts (the same at every solve
  // with the same factors, "normally", says its guide, and after a refactorisation on the
  // same pattern). A new plan when they or their owners changed on any rank: its exchange
  // is collective.
  int changed = plan_current_ && sol_rows_ == plan_.held_rows ? 0 : 1;
  MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT, MPI_MAX, comm_);
  if (changed)
    plan_return();
  const ReturnPlan& p = plan_;
  const std::size_t held = sol_rows_.size();
  std::vector<double> values_out(held * k);
  for (std::size_t i = 0; i < held; ++i)
    for (int j = 0; j < k; ++j)
      values_out[std::size_t(p.slot[i]) * k + j] = sol_[i + j * held];
  // The k values of a row travel together: the plan's counts and offsets times k.
  std::vector<int> send_counts(ranks_), send_offsets(ranks_), recv_counts(ranks_),
      recv_offsets(ranks_);
  for (int r = 0; r < ranks_; ++r)
  {
    send_counts[r] = p.send_counts[r] * k, send_offsets[r] = p.send_offsets[r] * k;
    recv_counts[r] = p.recv_counts[r] * k, recv_offsets[r] = p.recv_offsets[r] * k;
  }
  const std::size_t received = p.rows_in.size();
  std::vector<double> values_in(received * k);
  MPI_Alltoallv(values_out.data(), send_counts.data(), send_offsets.data(), MPI_DOUBLE,
                values_in.data(), recv_counts.data(), recv_offsets.data(), MPI_DOUBLE, comm_);
  for (std::size_t e = 0; e < received; ++e)
    for (int j = 0; j < k; ++j)
      columns[j][p.rows_in[e]] = values_in[e * k + j];
}
} // namespace cellphase
