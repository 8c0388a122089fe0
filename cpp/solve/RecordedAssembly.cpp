#include "solve/RecordedAssembly.h"
#include "solve/AijBlocks.h"
#include <algorithm>
#include <numeric>

namespace cellphase
{
namespace
{
using aij::Blocks;
using aij::blocks_of;

/// The scalar local indices of a call: blocked ones unrolled by the block size.
void unroll(std::span<const std::int32_t> idx, int bs, std::vector<PetscInt>& out)
{
  out.resize(idx.size() * bs);
  for (std::size_t i = 0; i < idx.size(); ++i)
    for (int k = 0; k < bs; ++k)
      out[i * bs + k] = PetscInt(idx[i]) * bs + k;
}

/// The value array of a sequential AIJ block, checked out for writing.
struct Values
{
  Mat block = nullptr;
  PetscScalar* v = nullptr;
  explicit Values(Mat b) : block(b)
  {
    if (block)
      MatSeqAIJGetArray(block, &v);
  }
  ~Values()
  {
    if (block)
      MatSeqAIJRestoreArray(block, &v);
  }
  Values(const Values&) = delete;
  Values& operator=(const Values&) = delete;
};

PetscInt entries_of(Mat seq)
{
  MatInfo info;
  MatGetInfo(seq, MAT_LOCAL, &info);
  return PetscInt(info.nz_used);
}
} // namespace

void RecordedAssembly::assemble(Mat A, const void* form, const Assembler& assemble,
                                const std::function<void()>& finalise)
{
  PetscInt64 id = 0;
  PetscObjectGetId(reinterpret_cast<PetscObject>(A), &id);
  Record& r = records_[id];
  PetscObjectState state;
  MatGetNonzeroState(A, &state);
  const bool tried = r.ready && r.form == form && r.nonzero_state == state;
  // Every rank replays or every rank records: both end in collective assemblies.
  int replayed = tried && replay(A, r, assemble) ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &replayed, 1, MPI_INT, MPI_MIN,
                PetscObjectComm(reinterpret_cast<PetscObject>(A)));
  if (replayed)
  {
    ++replays_;
    finalise();
    return;
  }
  int any_tried = tried ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &any_tried, 1, MPI_INT, MPI_MAX,
                PetscObjectComm(reinterpret_cast<PetscObject>(A)));
  if (any_tried)
  {
    // A replay here or on another rank may have put rows of other ranks in the stash:
    // send them, then clear everything.
    MatAssemblyBegin(A, MAT_FLUSH_ASSEMBLY);
    MatAssemblyEnd(A, MAT_FLUSH_ASSEMBLY);
  }
  r = Record{};
  r.form = form;
  record(A, r, assemble, finalise);
}

void RecordedAssembly::record(Mat A, Record& r, const Assembler& assemble,
                              const std::function<void()>& finalise)
{
  MatZeroEntries(A);
  std::vector<PetscInt> rows, cols;
  auto logged = [&](bool blocked)
  {
    return [&, blocked](const std::span<const std::int32_t>& rs,
                        const std::span<const std::int32_t>& cs, const std::span<const T>& vals)
    {
      r.calls.push_back({blocked, std::int32_t(rs.size()), std::int32_t(cs.size())});
      r.rows.insert(r.rows.end(), rs.begin(), rs.end());
      r.cols.insert(r.cols.end(), cs.begin(), cs.end());
      rows.assign(rs.begin(), rs.end());
      cols.assign(cs.begin(), cs.end());
      return int(blocked ? MatSetValuesBlockedLocal(A, PetscInt(rows.size()), rows.data(),
                                                    PetscInt(cols.size()), cols.data(),
                                                    vals.data(), ADD_VALUES)
                         : MatSetValuesLocal(A, PetscInt(rows.size()), rows.data(),
                                             PetscInt(cols.size()), cols.data(), vals.data(),
                                             ADD_VALUES));
    };
  };
  assemble(logged(true), logged(false));
  finalise();
  MatGetNonzeroState(A, &r.nonzero_state);
  r.ready = find_positions(A, r);
  if (!r.ready)
    r = Record{};
}

bool RecordedAssembly::find_positions(Mat A, Record& r)
{
  const Blocks b = blocks_of(A);
  if (!b.diagonal)
    return false; // another matrix type: PETSc's insertion every time
  PetscInt rbs = 1, cbs = 1, first_row, last_row, first_col, last_col;
  MatGetBlockSizes(A, &rbs, &cbs);
  MatGetOwnershipRange(A, &first_row, &last_row);
  MatGetOwnershipRangeColumn(A, &first_col, &last_col);
  ISLocalToGlobalMapping row_map, col_map;
  MatGetLocalToGlobalMapping(A, &row_map, &col_map);
  if (!row_map || !col_map)
    return false;

  // CSR arrays of the blocks; the off-diagonal block's columns by global number.
  PetscInt nd = 0, no = 0;
  const PetscInt *ia = nullptr, *ja = nullptr, *ib = nullptr, *jb = nullptr;
  PetscBool done;
  MatGetRowIJ(b.diagonal, 0, PETSC_FALSE, PETSC_FALSE, &nd, &ia, &ja, &done);
  if (b.off_diagonal)
    MatGetRowIJ(b.off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &no, &ib, &jb, &done);
  const std::int64_t diagonal_entries = nd ? ia[nd] : 0;
  std::vector<PetscInt> off_order; // off-diagonal columns sorted by global number
  PetscInt off_columns = 0;
  if (b.off_diagonal)
  {
    MatGetSize(b.off_diagonal, nullptr, &off_columns);
    off_order.resize(off_columns);
    std::iota(off_order.begin(), off_order.end(), PetscInt(0));
    std::sort(off_order.begin(), off_order.end(),
              [&](PetscInt x, PetscInt y) { return b.off_columns[x] < b.off_columns[y]; });
  }
  auto find = [](const PetscInt* begin, const PetscInt* end, PetscInt col) -> std::int64_t
  {
    const PetscInt* at = std::lower_bound(begin, end, col);
    return at != end && *at == col ? at - begin : -1;
  };

  bool ok = true;
  std::vector<PetscInt> rows, cols, grows, gcols;
  std::size_t next_row = 0, next_col = 0;
  const PetscInt owned_rows = last_row - first_row;
  for (const Call& call : r.calls)
  {
    std::span<const std::int32_t> rs(r.rows.data() + next_row, call.rows);
    std::span<const std::int32_t> cs(r.cols.data() + next_col, call.cols);
    next_row += call.rows;
    next_col += call.cols;
    unroll(rs, call.blocked ? int(rbs) : 1, rows);
    unroll(cs, call.blocked ? int(cbs) : 1, cols);
    grows.resize(rows.size());
    gcols.resize(cols.size());
    ISLocalToGlobalMappingApply(row_map, PetscInt(rows.size()), rows.data(), grows.data());
    ISLocalToGlobalMappingApply(col_map, PetscInt(cols.size()), cols.data(), gcols.data());
    for (std::size_t i = 0; i < rows.size() && ok; ++i)
    {
      // The replay takes a local row below the owned count as owned: check that it is
      // this rank's row of the same number.
      const bool owned = rows[i] < owned_rows;
      if (owned != (grows[i] >= first_row && grows[i] < last_row)
          || (owned && grows[i] != first_row + rows[i]))
        ok = false;
      if (!owned || !ok)
        continue;
      const PetscInt row = rows[i];
      for (PetscInt gc : gcols)
      {
        std::int64_t at = -1;
        if (gc >= first_col && gc < last_col)
        {
          const std::int64_t k = find(ja + ia[row], ja + ia[row + 1], gc - first_col);
          at = k < 0 ? -1 : ia[row] + k;
        }
        else if (b.off_diagonal)
        {
          auto pos = std::lower_bound(off_order.begin(), off_order.end(), gc,
                                      [&](PetscInt x, PetscInt g) { return b.off_columns[x] < g; });
          if (pos != off_order.end() && b.off_columns[*pos] == gc)
          {
            const std::int64_t k = find(jb + ib[row], jb + ib[row + 1], *pos);
            at = k < 0 ? -1 : diagonal_entries + ib[row] + k;
          }
        }
        if (at < 0)
        {
          ok = false;
          break;
        }
        r.positions.push_back(at);
      }
    }
    if (!ok)
      break;
  }
  MatRestoreRowIJ(b.diagonal, 0, PETSC_FALSE, PETSC_FALSE, &nd, &ia, &ja, &done);
  if (b.off_diagonal)
    MatRestoreRowIJ(b.off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &no, &ib, &jb, &done);
  return ok;
}

bool RecordedAssembly::replay(Mat A, const Record& r, const Assembler& assemble)
{
  MatZeroEntries(A);
  const Blocks b = blocks_of(A);
  PetscInt rbs = 1, cbs = 1, first_row, last_row;
  MatGetBlockSizes(A, &rbs, &cbs);
  MatGetOwnershipRange(A, &first_row, &last_row);
  const PetscInt owned_rows = last_row - first_row;
  const std::int64_t diagonal_entries = entries_of(b.diagonal);
  bool matches = true;
  {
    Values diagonal(b.diagonal), off_diagonal(b.off_diagonal);
    std::size_t next_call = 0, next_row = 0, next_col = 0, next_position = 0;
    std::vector<PetscInt> rows, cols;
    auto replayed = [&](bool blocked)
    {
      return [&, blocked](const std::span<const std::int32_t>& rs,
                          const std::span<const std::int32_t>& cs, const std::span<const T>& vals)
      {
        if (!matches)
          return 0;
        if (next_call == r.calls.size())
          return (matches = false), 0;
        const Call& c = r.calls[next_call++];
        const bool same = c.blocked == blocked && c.rows == std::int32_t(rs.size())
                          && c.cols == std::int32_t(cs.size())
                          && std::equal(rs.begin(), rs.end(), r.rows.begin() + next_row)
                          && std::equal(cs.begin(), cs.end(), r.cols.begin() + next_col);
        if (!same)
          return (matches = false), 0;
        next_row += rs.size();
        next_col += cs.size();
        unroll(rs, blocked ? int(rbs) : 1, rows);
        const std::size_t ncols = cs.size() * (blocked ? cbs : 1);
        for (std::size_t i = 0; i < rows.size(); ++i)
        {
          const T* row_values = vals.data() + i * ncols;
          if (rows[i] < owned_rows)
            for (std::size_t j = 0; j < ncols; ++j)
            {
              const std::int64_t at = r.positions[next_position++];
              (at < diagonal_entries ? diagonal.v[at]
                                     : off_diagonal.v[at - diagonal_entries]) += row_values[j];
            }
          else // another rank's row: PETSc's stash takes it
          {
            unroll(cs, blocked ? int(cbs) : 1, cols);
            MatSetValuesLocal(A, 1, &rows[i], PetscInt(ncols), cols.data(), row_values, ADD_VALUES);
          }
        }
        return 0;
      };
    };
    assemble(replayed(true), replayed(false));
    matches = matches && next_call == r.calls.size() && next_position == r.positions.size();
  }
  return matches;
}
} // namespace cellphase
