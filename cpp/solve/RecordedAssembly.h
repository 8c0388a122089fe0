// Matrix assembly that adds the element matrices straight into the value arrays of an AIJ
// matrix whose nonzero pattern is known.
//
// PETSc's MatSetValuesLocal maps every index to its global number, finds off-process
// columns in a hash table and searches each row for each column: 13 % of a GTPase step at
// eps 0.03 (perf). Here the first assembly of a form into a matrix goes through PETSc and
// records the element entries it adds; once the pattern is final (after the caller's final
// assembly) the record becomes, for each entry of an owned row, its position in the value
// array of the diagonal or off-diagonal block. Later assemblies of the same form into the
// same pattern add there directly (rows owned by other ranks still go through PETSc). The
// same values are added in the same order, so the sums are PETSc's bit for bit.
// Each call of the assembler is checked against the record (the same rows and columns);
// a mismatch on any rank starts the assembly again through PETSc on every rank and records
// anew.
#pragma once
#include "compat/Dolfinx.h"
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <vector>

namespace cellphase
{
class RecordedAssembly
{
public:
  /// The insertion function of dolfinx' and dolfinx_mpc's assemblers.
  using AddFn = std::function<int(const std::span<const std::int32_t>&,
                                  const std::span<const std::int32_t>&, const std::span<const T>&)>;
  /// The assembler, given an adder of blocked local indices (MatSetValuesBlockedLocal's)
  /// and one of scalar local indices (MatSetValuesLocal's).
  using Assembler = std::function<void(const AddFn& add_block, const AddFn& add)>;

  /// A <- 0, then `assemble` adds into A (ADD_VALUES), then `finalise` completes A (flush,
  /// diagonals, MAT_FINAL_ASSEMBLY). `form` names what is assembled: a record serves the
  /// same form and the same pattern of A only.
  void assemble(Mat A, const void* form, const Assembler& assemble,
                const std::function<void()>& finalise);
  /// Assemblies that added at recorded positions so far (the rest went through PETSc).
  int replays() const { return replays_; }

private:
  struct Call
  {
    bool blocked;
    std::int32_t rows, cols; ///< how many of the record's rows and columns it takes
  };
  struct Record
  {
    const void* form = nullptr;
    PetscObjectState nonzero_state = -1;
    std::vector<Call> calls;
    std::vector<std::int32_t> rows, cols; ///< the local indices of every call, in turn
    std::vector<std::int64_t> positions; ///< per owned-row entry: diagonal block's value
                                         ///< index, or its count plus the off-diagonal one's
    bool ready = false;
  };
  /// Through PETSc, logging the calls; then the positions, from A's final pattern.
  void record(Mat A, Record& r, const Assembler& assemble, const std::function<void()>& finalise);
  /// Adds at the recorded positions (no collective call); false if a call does not match
  /// the record, and A is then to be cleared by the caller.
  bool replay(Mat A, const Record& r, const Assembler& assemble);
  static bool find_positions(Mat A, Record& r);

  std::map<PetscInt64, Record> records_; ///< by the matrix' PETSc object id
  int replays_ = 0;
};
} // namespace cellphase
