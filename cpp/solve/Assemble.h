// Assembly of linear systems with Dirichlet conditions (identity rows, lifted right-hand
// side), shared by the physics modules.
#pragma once
#include "compat/Dolfinx.h"
#include <memory>

namespace cellphase
{
/// A PETSc matrix with the sparsity of the bilinear form a.
std::unique_ptr<dolfinx::la::petsc::Matrix> create_matrix(const Form& a);

/// A <- a with identity rows and columns at the BC dofs (A keeps its sparsity pattern,
/// so that MUMPS can keep its symbolic analysis).
void assemble_matrix(Mat A, const Form& a, const BCs& bcs);

/// The final assembly of A after the form's entries were added: 1 on the diagonal of the
/// BC dofs of V (their rows and columns were left out of the form's assembly).
void finish_matrix(Mat A, const Space& V, const BCs& bcs);

/// b <- L lifted by the BC values of a, with the BC values at the BC dofs.
void assemble_rhs(dolfinx::la::Vector<T>& b, const Form& L, const std::shared_ptr<const Form>& a,
                  const BCs& bcs);
} // namespace cellphase
