// The two sequential AIJ blocks that hold a PETSc AIJ matrix' owned rows, for code that
// reads or writes their CSR arrays directly (solve/MumpsSolver, solve/RecordedAssembly).
#pragma once
#include <petscmat.h>

namespace cellphase::aij
{
inline bool is_type(Mat A, const char* type)
{
  PetscBool same = PETSC_FALSE;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), type, &same);
  return same;
}

/// The diagonal and off-diagonal blocks of A (a sequential matrix is its own diagonal
/// block, with no off-diagonal one) and the global column of every off-diagonal column;
/// both null for a matrix that is not AIJ.
struct Blocks
{
  Mat diagonal = nullptr, off_diagonal = nullptr;
  const PetscInt* off_columns = nullptr;
};

inline Blocks blocks_of(Mat A)
{
  Blocks b;
  if (is_type(A, MATSEQAIJ))
    b.diagonal = A;
  else if (is_type(A, MATMPIAIJ))
    MatMPIAIJGetSeqAIJ(A, &b.diagonal, &b.off_diagonal, &b.off_columns);
  return b;
}
} // namespace cellphase::aij
