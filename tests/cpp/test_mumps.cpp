// solve/MumpsSolver (MUMPS called directly, the default direct solve of LinearSolver)
// against PETSc's own MUMPS interface (a KSP, chosen here by an option that is not a MUMPS
// control) on 5-point matrices of a 40 x 40 grid: unsymmetric (LU), symmetric indefinite
// (L D L^T) and positive definite (Cholesky), three right-hand sides at once, new values
// on the same pattern, and a singular matrix. Both call the same MUMPS with the same
// controls, so the solutions agree to round-off. Also run on two ranks
// (tests/CMakeLists.txt), where the solution comes back from MUMPS' distribution.
#include "mpi_main.h"
#include "solve/LinearSolver.h"
#include <cmath>

using namespace cellphase;
namespace
{
constexpr PetscInt n = 40, N = n * n;

/// (4 + shift) u_ij - sum of the 4 neighbours, with +-convection on the x neighbours
/// (unsymmetric for convection != 0). Distributed by PETSc in contiguous row blocks.
Mat grid_matrix(double shift, double convection)
{
  Mat A;
  MatCreateAIJ(MPI_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, N, N, 5, nullptr, 4, nullptr, &A);
  PetscInt first, last;
  MatGetOwnershipRange(A, &first, &last);
  for (PetscInt r = first; r < last; ++r)
  {
    const PetscInt i = r % n, j = r / n;
    MatSetValue(A, r, r, 4 + shift, INSERT_VALUES);
    if (i > 0)
      MatSetValue(A, r, r - 1, -1 - convection, INSERT_VALUES);
    if (i < n - 1)
      MatSetValue(A, r, r + 1, -1 + convection, INSERT_VALUES);
    if (j > 0)
      MatSetValue(A, r, r - n, -1, INSERT_VALUES);
    if (j < n - 1)
      MatSetValue(A, r, r + n, -1, INSERT_VALUES);
  }
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  return A;
}

using Vector = dolfinx::la::Vector<T>;

std::shared_ptr<const dolfinx::common::IndexMap> row_map(Mat A)
{
  PetscInt first, last;
  MatGetOwnershipRange(A, &first, &last);
  return std::make_shared<dolfinx::common::IndexMap>(MPI_COMM_WORLD, last - first);
}

/// Three right-hand sides: smooth, oscillating and a point load.
std::vector<Vector> right_hand_sides(Mat A)
{
  PetscInt first, last;
  MatGetOwnershipRange(A, &first, &last);
  std::vector<Vector> bs;
  for (int k = 0; k < 3; ++k)
  {
    Vector b(row_map(A), 1);
    auto a = b.mutable_array();
    for (PetscInt r = first; r < last; ++r)
    {
      const double x = double(r % n) / n, y = double(r / n) / n;
      a[r - first] = k == 0 ? std::sin(3 * x) * std::cos(2 * y)
                     : k == 1 ? std::cos(40 * x * y) : (r == N / 2 + n / 3 ? 1.0 : 0.0);
    }
    bs.push_back(std::move(b));
  }
  return bs;
}

/// x_j = A^-1 b_j for all three columns, factorising A with the given solver.
std::vector<Vector> solve_all(Mat A, LinearSolver& solver)
{
  solver.set_operator(A);
  auto bs = right_hand_sides(A);
  std::vector<Vector> xs;
  for (auto& b : bs)
    xs.emplace_back(b.map(), 1);
  std::vector<const Vector*> b_ptrs;
  std::vector<Vector*> x_ptrs;
  for (std::size_t j = 0; j < bs.size(); ++j)
  {
    b_ptrs.push_back(&bs[j]);
    x_ptrs.push_back(&xs[j]);
  }
  solver.solve(b_ptrs, x_ptrs, "the test system");
  return xs;
}

/// Largest |x - y| / max |y| over the columns (over all ranks).
double relative_difference(const std::vector<Vector>& x, const std::vector<Vector>& y)
{
  double diff = 0, size = 0;
  for (std::size_t j = 0; j < x.size(); ++j)
  {
    const std::int32_t owned = x[j].map()->size_local();
    for (std::int32_t i = 0; i < owned; ++i)
    {
      diff = std::max(diff, std::abs(x[j].array()[i] - y[j].array()[i]));
      size = std::max(size, std::abs(y[j].array()[i]));
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &diff, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &size, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return diff / size;
}

/// max_j ||A x_j - b_j||_inf / ||b_j||_inf.
double relative_residual(Mat A, const std::vector<Vector>& xs)
{
  const auto bs = right_hand_sides(A);
  double worst = 0;
  for (std::size_t j = 0; j < xs.size(); ++j)
  {
    Vec x = dolfinx::la::petsc::create_vector_wrap(xs[j]);
    Vec b = dolfinx::la::petsc::create_vector_wrap(bs[j]);
    Vec r;
    VecDuplicate(b, &r);
    MatMult(A, x, r);
    VecAXPY(r, -1.0, b);
    PetscReal rn, bn;
    VecNorm(r, NORM_INFINITY, &rn);
    VecNorm(b, NORM_INFINITY, &bn);
    worst = std::max(worst, double(rn / bn));
    VecDestroy(&r);
    VecDestroy(&x);
    VecDestroy(&b);
  }
  return worst;
}

// The KSP path: PETSc's MUMPS interface, with the same MUMPS controls.
const std::map<std::string, std::string> through_petsc{{"ksp_norm_type", "none"}};

// Round-off of a direct solve of these matrices: the two interfaces agree bitwise for LU
// and Cholesky and to 2e-13 for L D L^T of the indefinite matrix (PETSc hands MUMPS the
// triangle in another order); relative residuals 1e-14 to 4e-12. Asserted 1e-10.
constexpr double round_off = 1e-10;

/// Solves with MUMPS directly and through PETSc's interface agree, and the residual is
/// round-off; A is destroyed.
void expect_direct_equals_petsc(Mat A, Symmetry symmetry)
{
  LinearSolver direct_solver(MPI_COMM_WORLD, "mumps_direct_", {}, symmetry);
  LinearSolver petsc_solver(MPI_COMM_WORLD, "mumps_petsc_", through_petsc, symmetry);
  const auto direct = solve_all(A, direct_solver);
  const auto petsc = solve_all(A, petsc_solver);
  EXPECT_LT(relative_difference(direct, petsc), round_off);
  EXPECT_LT(relative_residual(A, direct), round_off);
  MatDestroy(&A);
}
} // namespace

TEST(Mumps, UnsymmetricLuEqualsPetscInterface)
{
  expect_direct_equals_petsc(grid_matrix(0.01, 0.4), Symmetry::general);
}

TEST(Mumps, SymmetricIndefiniteLdltEqualsPetscInterface)
{
  Mat A = grid_matrix(-0.5, 0); // eigenvalues from -0.5 to 7.5: indefinite
  MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE);
  expect_direct_equals_petsc(A, Symmetry::symmetric);
}

TEST(Mumps, PositiveDefiniteCholeskyEqualsPetscInterface)
{
  expect_direct_equals_petsc(grid_matrix(0.1, 0), Symmetry::positive_definite);
}

TEST(Mumps, NewValuesOnTheSamePatternAreFactorisedAgain)
{
  // As a Taylor step: the same matrix object with new values, the same solver. The
  // solution must be that of the new values (x / 2 for A * 2), not of the old factors.
  Mat A = grid_matrix(0.01, 0.4);
  LinearSolver solver(MPI_COMM_WORLD, "mumps_reuse_", {}, Symmetry::general);
  const auto first = solve_all(A, solver);
  MatScale(A, 2.0); // new values on the same pattern
  auto second = solve_all(A, solver);
  for (auto& x : second)
    for (auto& v : x.mutable_array())
      v *= 2;
  EXPECT_LT(relative_difference(second, first), round_off);
  MatDestroy(&A);
}

TEST(Mumps, SecondSolveWithTheSameFactorsGivesTheSameSolution)
{
  // As a reused stabilised step: the solve alone, again. On two ranks the second solve
  // sends the solution back with the plan made at the first one.
  Mat A = grid_matrix(-0.5, 0);
  MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE);
  LinearSolver solver(MPI_COMM_WORLD, "mumps_again_", {}, Symmetry::symmetric);
  const auto first = solve_all(A, solver);
  auto bs = right_hand_sides(A);
  std::vector<Vector> again;
  for (auto& b : bs)
    again.emplace_back(b.map(), 1);
  solver.solve({&bs[0], &bs[1]}, {&again[0], &again[1]}, "the test system, again");
  solver.solve(bs[2], again[2], "the test system, one column");
  EXPECT_LT(relative_difference(again, first), round_off); // a wrong plan: O(1) errors
  MatDestroy(&A);
}

TEST(Mumps, SingularMatrixIsASolverErrorNamingMumps)
{
  // Row 0 emptied: no pivot can be found for it.
  Mat A = grid_matrix(0.01, 0.4);
  PetscInt first, last;
  MatGetOwnershipRange(A, &first, &last);
  const PetscInt row = 0;
  MatZeroRows(A, first == 0 ? 1 : 0, &row, 0.0, nullptr, nullptr);
  LinearSolver solver(MPI_COMM_WORLD, "mumps_singular_", {}, Symmetry::general);
  try
  {
    solver.set_operator(A);
    ADD_FAILURE() << "a singular matrix was factorised";
  }
  catch (const SolverError& e)
  {
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, "MUMPS factorisation failed", e.what());
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, "mumps_singular", e.what());
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, "singular", e.what());
  }
  MatDestroy(&A);
}
