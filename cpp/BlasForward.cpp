// BLAS-3 calls with a few columns, computed here instead of in the BLAS library.
//
// A MUMPS solve with k right-hand sides calls dgemm and dtrsm with n = k for every front:
// thousands of calls on blocks of a few hundred entries (a 2-right-hand-side solve of the
// 36k-dof vesicle matrix: 11 000 dgemm calls of 300 entries on average). OpenBLAS 0.3.21
// (Debian bookworm) locks a mutex, packs the block into a buffer and dispatches for each of
// them, which took more than a third of the solve (perf). For a few columns the loops below
// read each entry of A once and need no buffer. Linked into the executable and exported
// (CMakeLists.txt), these definitions come first in the dynamic symbol lookup, so MUMPS
// calls them; every other call goes on to the BLAS library's own routine.
#include <cstddef>
#include <dlfcn.h>
#include <vector>

namespace
{
using gemm_fn = void(const char*, const char*, const int*, const int*, const int*, const double*,
                     const double*, const int*, const double*, const int*, const double*, double*,
                     const int*);
using trsm_fn = void(const char*, const char*, const char*, const char*, const int*, const int*,
                     const double*, const double*, const int*, double*, const int*);

/// Up to this many columns (right-hand sides) the loops here run; MUMPS solves with 1 to 3.
constexpr int max_columns = 4;

bool untransposed(const char* t) { return *t == 'N' || *t == 'n'; }

/// The BLAS library's definition (the next one after this executable's).
template <typename F>
F* next_definition(const char* name)
{
  return reinterpret_cast<F*>(dlsym(RTLD_NEXT, name));
}

/// C = beta C, without reading C when beta = 0 (BLAS semantics: NaN in C does not propagate).
void scale_columns(int m, int n, double beta, double* c, std::ptrdiff_t ldc)
{
  if (beta == 1.0)
    return;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i)
      c[i + j * ldc] = beta == 0.0 ? 0.0 : beta * c[i + j * ldc];
}

/// C += alpha A op(B) for A m x k and N columns: each column of A is read once and added
/// to the N columns of C (a contiguous loop over i, which the compiler vectorises).
template <int N>
void add_plain_times(int m, int k, double alpha, const double* a, std::ptrdiff_t lda,
                     const double* b, std::ptrdiff_t b_row, std::ptrdiff_t b_col, double* c,
                     std::ptrdiff_t ldc)
{
  for (int l = 0; l < k; ++l)
  {
    double s[N];
    for (int j = 0; j < N; ++j)
      s[j] = alpha * b[l * b_row + j * b_col];
    const double* al = a + l * lda;
    for (int j = 0; j < N; ++j)
    {
      double* cj = c + j * ldc;
      const double sj = s[j];
#pragma omp simd
      for (int i = 0; i < m; ++i)
        cj[i] += al[i] * sj;
    }
  }
}

/// C += alpha A^T op(B) for A k x m and N columns: N dot products per column of A.
template <int N>
void add_transposed_times(int m, int k, double alpha, const double* a, std::ptrdiff_t lda,
                          const double* b, std::ptrdiff_t b_row, std::ptrdiff_t b_col, double* c,
                          std::ptrdiff_t ldc)
{
  // op(B) as N contiguous columns, so that every dot product runs over unit strides.
  thread_local std::vector<double> packed;
  packed.resize(std::size_t(k) * N);
  for (int j = 0; j < N; ++j)
    for (int l = 0; l < k; ++l)
      packed[l + j * std::ptrdiff_t(k)] = b[l * b_row + j * b_col];
  for (int i = 0; i < m; ++i)
  {
    const double* ai = a + i * lda;
    for (int j = 0; j < N; ++j)
    {
      const double* bj = packed.data() + j * std::ptrdiff_t(k);
      double sum = 0;
#pragma omp simd reduction(+ : sum)
      for (int l = 0; l < k; ++l)
        sum += ai[l] * bj[l];
      c[i + j * ldc] += alpha * sum;
    }
  }
}

template <int N>
void add_product(bool a_plain, int m, int k, double alpha, const double* a, std::ptrdiff_t lda,
                 const double* b, std::ptrdiff_t b_row, std::ptrdiff_t b_col, double* c,
                 std::ptrdiff_t ldc)
{
  if (a_plain)
    add_plain_times<N>(m, k, alpha, a, lda, b, b_row, b_col, c, ldc);
  else
    add_transposed_times<N>(m, k, alpha, a, lda, b, b_row, b_col, c, ldc);
}

/// One column x of op(T) x = b, T the upper or lower triangle of A (m x m), in place:
/// the column-oriented loops of the reference BLAS (dtrsm, side L).
void solve_triangle(bool upper, bool plain, bool unit, int m, const double* a, std::ptrdiff_t lda,
                    double* x)
{
  auto at = [&](int i, int j) { return a[i + j * lda]; };
  if (plain && upper) // backward: x_k, then remove it from the rows above
    for (int k = m - 1; k >= 0; --k)
    {
      if (!unit)
        x[k] /= at(k, k);
      const double xk = x[k];
      const double* ak = a + k * lda;
#pragma omp simd
      for (int i = 0; i < k; ++i)
        x[i] -= xk * ak[i];
    }
  else if (plain) // lower, forward
    for (int k = 0; k < m; ++k)
    {
      if (!unit)
        x[k] /= at(k, k);
      const double xk = x[k];
      const double* ak = a + k * lda;
#pragma omp simd
      for (int i = k + 1; i < m; ++i)
        x[i] -= xk * ak[i];
    }
  else if (upper) // U^T is lower: forward, row i of U^T is column i of U
    for (int i = 0; i < m; ++i)
    {
      double t = 0;
      const double* ai = a + i * lda; // column i of U
#pragma omp simd reduction(+ : t)
      for (int k = 0; k < i; ++k)
        t += ai[k] * x[k];
      t = x[i] - t;
      x[i] = unit ? t : t / at(i, i);
    }
  else // L^T is upper: backward
    for (int i = m - 1; i >= 0; --i)
    {
      double t = 0;
      const double* ai = a + i * lda; // column i of L
#pragma omp simd reduction(+ : t)
      for (int k = i + 1; k < m; ++k)
        t += ai[k] * x[k];
      t = x[i] - t;
      x[i] = unit ? t : t / at(i, i);
    }
}
} // namespace

extern "C"
{
/// C = alpha op(A) op(B) + beta C; for n <= max_columns computed here.
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc)
{
  if (*n >= 1 && *n <= max_columns && *m >= 0 && *k >= 0)
  {
    scale_columns(*m, *n, *beta, c, *ldc);
    if (*alpha == 0.0 || *m == 0 || *k == 0)
      return;
    // Entry (l, j) of op(B) is b[l * b_row + j * b_col].
    const bool b_plain = untransposed(transb);
    const std::ptrdiff_t b_row = b_plain ? 1 : *ldb, b_col = b_plain ? *ldb : 1;
    const bool a_plain = untransposed(transa);
    switch (*n)
    {
    case 1: add_product<1>(a_plain, *m, *k, *alpha, a, *lda, b, b_row, b_col, c, *ldc); break;
    case 2: add_product<2>(a_plain, *m, *k, *alpha, a, *lda, b, b_row, b_col, c, *ldc); break;
    case 3: add_product<3>(a_plain, *m, *k, *alpha, a, *lda, b, b_row, b_col, c, *ldc); break;
    default: add_product<4>(a_plain, *m, *k, *alpha, a, *lda, b, b_row, b_col, c, *ldc); break;
    }
    return;
  }
  static gemm_fn* blas = next_definition<gemm_fn>("dgemm_");
  blas(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
}

/// B = alpha op(A)^-1 B (side L); for n <= max_columns computed here, column by column.
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
            const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            double* b, const int* ldb)
{
  if (*n >= 1 && *n <= max_columns && *m >= 0 && (*side == 'L' || *side == 'l'))
  {
    const bool upper = *uplo == 'U' || *uplo == 'u';
    const bool unit = *diag == 'U' || *diag == 'u';
    for (int j = 0; j < *n; ++j)
    {
      double* x = b + std::ptrdiff_t(j) * *ldb;
      for (int i = 0; i < *m; ++i)
        x[i] = *alpha == 0.0 ? 0.0 : *alpha * x[i];
      if (*alpha != 0.0)
        solve_triangle(upper, untransposed(transa), unit, *m, a, *lda, x);
    }
    return;
  }
  static trsm_fn* blas = next_definition<trsm_fn>("dtrsm_");
  blas(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb);
}
}
