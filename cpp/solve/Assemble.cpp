#include "solve/Assemble.h"

namespace cellphase
{
using namespace dolfinx;

std::unique_ptr<la::petsc::Matrix> create_matrix(const Form& a)
{
  return std::make_unique<la::petsc::Matrix>(fem::petsc::create_matrix(a), false);
}

void assemble_matrix(Mat A, const Form& a, const BCs& bcs)
{
  MatZeroEntries(A);
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A, ADD_VALUES), a, bcs);
  finish_matrix(A, *a.function_spaces()[0], bcs);
}

void finish_matrix(Mat A, const Space& V, const BCs& bcs)
{
  // INSERT (after a flush) rather than ADD: a dof shared by two BCs (a corner of two
  // walls) must still get a diagonal of 1, not 2.
  MatAssemblyBegin(A, MAT_FLUSH_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FLUSH_ASSEMBLY);
  fem::set_diagonal<T>(la::petsc::Matrix::set_fn(A, INSERT_VALUES), V, bcs);
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
}

void assemble_rhs(la::Vector<T>& b, const Form& L, const std::shared_ptr<const Form>& a,
                  const BCs& bcs)
{
  b.set(0.0);
  fem::assemble_vector(b.mutable_array(), L);
  fem::apply_lifting<T>(b.mutable_array(), {a}, {bcs}, {}, 1.0);
  b.scatter_rev(std::plus<T>());
  fem::set_bc<T>(b.mutable_array(), bcs);
}
} // namespace cellphase
