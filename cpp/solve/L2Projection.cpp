#include "solve/L2Projection.h"
#include "solve/Assemble.h"
#include <dolfinx/fem/assembler.h>
#include <stdexcept>
#include <string>

namespace cellphase
{
namespace
{
/// Global rows (or columns) of component c of a matrix of block size k: every k-th from c.
IS component_indices(Mat A, int k, int c)
{
  PetscInt first, last;
  MatGetOwnershipRange(A, &first, &last);
  IS is;
  ISCreateStride(PetscObjectComm(reinterpret_cast<PetscObject>(A)), (last - first) / k, first + c,
                 k, &is);
  return is;
}

/// The scalar matrix M if A (block size k) is M in every diagonal block of the components and
/// zero between them (the mass matrix of inner(u, w) dx); nullptr otherwise.
Mat scalar_block(Mat A, int k)
{
  std::vector<IS> is;
  for (int c = 0; c < k; ++c)
    is.push_back(component_indices(A, k, c));
  Mat M;
  MatCreateSubMatrix(A, is[0], is[0], MAT_INITIAL_MATRIX, &M);
  PetscReal scale;
  MatNorm(M, NORM_INFINITY, &scale);
  bool copies = true;
  for (int c = 0; c < k && copies; ++c)
    for (int d = 0; d < k && copies; ++d)
    {
      if (c == 0 && d == 0)
        continue;
      Mat S;
      MatCreateSubMatrix(A, is[c], is[d], MAT_INITIAL_MATRIX, &S);
      if (c == d)
        MatAXPY(S, -1.0, M, SUBSET_NONZERO_PATTERN);
      PetscReal off;
      MatNorm(S, NORM_INFINITY, &off); // collective: every rank decides alike
      copies = off <= 1e-14 * scale;
      MatDestroy(&S);
    }
  for (IS& i : is)
    ISDestroy(&i);
  if (!copies)
    MatDestroy(&M);
  return copies ? M : nullptr;
}
} // namespace

L2Projection::L2Projection(const Form& mass, const scene::Domain& domain, MPI_Comm comm,
                           const std::string& prefix)
{
  // Slave rows are identity rows, alike in every component, so the scalar block below
  // still serves all components.
  periodic_ = std::make_unique<PeriodicConstraint>(mass.function_spaces()[0], domain.lower,
                                                   domain.upper, domain.periodic);
  mass_ = std::make_unique<dolfinx::la::petsc::Matrix>(periodic_->create_matrix(mass));
  periodic_->assemble_matrix(mass_->mat(), mass, {});
  const int k = mass.function_spaces()[0]->dofmap()->index_map_bs();
  if (k > 1)
    if (Mat M = scalar_block(mass_->mat(), k))
    {
      mass_ = std::make_unique<dolfinx::la::petsc::Matrix>(M, false);
      components_ = k;
    }
  // Ordered by AMF: a mass matrix is factorised once per mesh, and MUMPS' automatic choice
  // (PORD) took most of that (3.6 % of a GTPase run at eps 0.03, a third of its remeshes).
  solver_ = std::make_unique<LinearSolver>(
      comm, prefix, std::map<std::string, std::string>{{"mat_mumps_icntl_7", "2"}},
      Symmetry::positive_definite);
  solver_->set_operator(mass_->mat());
}

L2Projection::~L2Projection() = default;

void L2Projection::project(const std::vector<const Form*>& forms, Function& out,
                           const std::string& what)
{
  const auto& V = *out.function_space();
  const auto map = V.dofmap()->index_map;
  const int k = V.dofmap()->index_map_bs();
  auto b = periodic_->create_vector(), x = periodic_->create_vector();
  b.set(0.0);
  for (const Form* L : forms)
    periodic_->add_load(b, *L);
  periodic_->finish(b, {}, 1.0);
  // The slaves' values from their masters, then copied into out (ghosts included).
  auto finish = [&]
  {
    periodic_->backsubstitute(x, out);
    out.x()->scatter_fwd();
  };
  if (components_ == 1)
  {
    solver_->solve(b, x, what);
    finish();
    return;
  }
  if (k != components_)
    throw std::logic_error("L2Projection: " + what + " onto a space of " + std::to_string(k)
                           + " components, the mass matrix has " + std::to_string(components_));
  // One right-hand side per component, solved together with the scalar mass matrix.
  const std::int32_t n = map->size_local();
  std::vector<std::unique_ptr<dolfinx::la::Vector<T>>> bc, xc;
  std::vector<const dolfinx::la::Vector<T>*> rhs;
  std::vector<dolfinx::la::Vector<T>*> sol;
  for (int c = 0; c < k; ++c)
  {
    bc.push_back(std::make_unique<dolfinx::la::Vector<T>>(map, 1));
    xc.push_back(std::make_unique<dolfinx::la::Vector<T>>(map, 1));
    auto in = bc.back()->mutable_array();
    for (std::int32_t i = 0; i < n; ++i)
      in[i] = b.array()[i * k + c];
    rhs.push_back(bc.back().get());
    sol.push_back(xc.back().get());
  }
  solver_->solve(rhs, sol, what);
  auto xa = x.mutable_array();
  for (int c = 0; c < k; ++c)
  {
    auto xs = xc[c]->array();
    for (std::int32_t i = 0; i < n; ++i)
      xa[i * k + c] = xs[i];
  }
  finish();
}
} // namespace cellphase
