// BLAS-3 calls with a few columns, computed here instead of in the BLAS library.
//
// A MUMPS solve with k right-hand sides calls dgemm and dtrsm with n = k for every front:
// thousands of calls on small blocks (a 2-right-hand-side solve of the 36k-dof vesicle
// matrix, L D L^T: about 5000 dgemm calls each with A and with A^T, of 6 x 25 and 25 x 6
// on average, and 5000 dtrsm calls each way on triangles of 6 rows). OpenBLAS 0.3.21
// (Debian bookworm) locks a mutex, packs the block into a buffer and dispatches for each of
// them, which took more than a third of the solve (perf). For a few columns the loops below
// read each entry of A once, keep the block of C in registers and need no buffer. Linked
// into the executable and exported (CMakeLists.txt), these definitions come first in the
// dynamic symbol lookup, so MUMPS calls them; every other call goes on to the BLAS
// library's own routine.
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <type_traits>
#include <dlfcn.h>

namespace
{
using gemm_fn = void(const char*, const char*, const int*, const int*, const int*, const double*,
                     const double*, const int*, const double*, const int*, const double*, double*,
                     const int*);
using trsm_fn = void(const char*, const char*, const char*, const char*, const int*, const int*,
                     const double*, const double*, const int*, double*, const int*);

/// Up to this many columns (right-hand sides) the loops here run; MUMPS solves with 1 to 3.
constexpr int max_columns = 4;

inline bool untransposed(const char* t) { return *t == 'N' || *t == 'n'; }

/// The BLAS library's definition (the next one after this executable's).
template <typename F>
F* next_definition(const char* name)
{
  return reinterpret_cast<F*>(dlsym(RTLD_NEXT, name));
}

// The loops below are compiled twice, for the baseline x86-64 and for AVX2 with FMA, and
// the first call picks the variant the processor runs (kernels are inlined into both).
#define CELLPHASE_KERNEL [[gnu::always_inline]] inline

/// C = beta C, without reading C when beta = 0 (BLAS semantics: NaN in C does not propagate);
/// dgemm's beta C and dtrsm's alpha B.
CELLPHASE_KERNEL void scale_columns(int m, int n, double beta, double* c, std::ptrdiff_t ldc)
{
  if (beta == 1.0)
    return;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i)
      c[i + j * ldc] = beta == 0.0 ? 0.0 : beta * c[i + j * ldc];
}

/// R consecutive doubles as one vector (R = 4: a ymm register with AVX2, two xmm without);
/// R = 1 is a plain double. (An alias template cannot carry the vector_size attribute.)
typedef double Lanes2 __attribute__((vector_size(16)));
typedef double Lanes4 __attribute__((vector_size(32)));
template <int R>
using Lanes = std::conditional_t<R == 4, Lanes4, std::conditional_t<R == 2, Lanes2, double>>;

/// p[0 .. R-1] as a vector (a plain double for R = 1).
template <int R>
CELLPHASE_KERNEL auto rows_of(const double* p)
{
  if constexpr (R == 1)
    return *p;
  else
  {
    Lanes<R> v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
}

/// Rows i .. i+R-1 of C += alpha A op(B), A m x k (column l at a + l lda), N columns: the
/// R x N block of C stays in registers while the columns of A stream by, summed in two
/// interleaved halves (even and odd l) so that consecutive FMAs do not wait for each other.
/// MUMPS' fronts give blocks of a few rows (6 on average for the 36k-dof vesicle).
template <int N, int R>
CELLPHASE_KERNEL void plain_rows(int i, int k, double alpha, const double* a, std::ptrdiff_t lda,
                                 const double* b, std::ptrdiff_t b_row, std::ptrdiff_t b_col,
                                 double* c, std::ptrdiff_t ldc)
{
  using V = Lanes<R>;
  V even[N] = {}, odd[N] = {};
  int l = 0;
  for (; l + 2 <= k; l += 2)
  {
    const V a0 = rows_of<R>(a + i + l * lda), a1 = rows_of<R>(a + i + (l + 1) * lda);
    for (int j = 0; j < N; ++j)
    {
      even[j] += a0 * b[l * b_row + j * b_col];
      odd[j] += a1 * b[(l + 1) * b_row + j * b_col];
    }
  }
  if (l < k)
  {
    const V a0 = rows_of<R>(a + i + l * lda);
    for (int j = 0; j < N; ++j)
      even[j] += a0 * b[l * b_row + j * b_col];
  }
  for (int j = 0; j < N; ++j)
  {
    const V sum = alpha * (even[j] + odd[j]);
    if constexpr (R == 1)
      c[i + j * ldc] += sum;
    else
      for (int r = 0; r < R; ++r)
        c[i + r + j * ldc] += sum[r];
  }
}

/// Rows i .. i+R-1 of C += alpha A^T op(B), A k x m: row i of A^T is column i of A, so each
/// entry is a dot product over a column of A; R x N of them at once keep the FMAs
/// independent. Scalar on purpose: the rows of A^T are strided, and the file is compiled
/// without auto-vectorisation, which gathered them one by one (CMakeLists.txt).
template <int N, int R>
CELLPHASE_KERNEL void transposed_rows(int i, int k, double alpha, const double* a,
                                      std::ptrdiff_t lda, const double* b, std::ptrdiff_t b_row,
                                      std::ptrdiff_t b_col, double* c, std::ptrdiff_t ldc)
{
  double acc[R][N] = {};
  for (int l = 0; l < k; ++l)
  {
    double bl[N];
    for (int j = 0; j < N; ++j)
      bl[j] = b[l * b_row + j * b_col];
    for (int r = 0; r < R; ++r)
    {
      const double arl = a[l + (i + r) * lda];
      for (int j = 0; j < N; ++j)
        acc[r][j] += arl * bl[j];
    }
  }
  for (int r = 0; r < R; ++r)
    for (int j = 0; j < N; ++j)
      c[i + r + j * ldc] += alpha * acc[r][j];
}

/// Rows i .. i+R-1 of C += alpha op(A) op(B).
template <int N, int R>
CELLPHASE_KERNEL void product_rows(bool a_plain, int i, int k, double alpha, const double* a,
                                   std::ptrdiff_t lda, const double* b, std::ptrdiff_t b_row,
                                   std::ptrdiff_t b_col, double* c, std::ptrdiff_t ldc)
{
  if (a_plain)
    plain_rows<N, R>(i, k, alpha, a, lda, b, b_row, b_col, c, ldc);
  else
    transposed_rows<N, R>(i, k, alpha, a, lda, b, b_row, b_col, c, ldc);
}

/// C += alpha op(A) op(B) for N columns: blocks of 4 rows, then 2, then 1.
template <int N>
CELLPHASE_KERNEL void add_product(bool a_plain, int m, int k, double alpha, const double* a,
                                  std::ptrdiff_t lda, const double* b, std::ptrdiff_t b_row,
                                  std::ptrdiff_t b_col, double* c, std::ptrdiff_t ldc)
{
  int i = 0;
  for (; i + 4 <= m; i += 4)
    product_rows<N, 4>(a_plain, i, k, alpha, a, lda, b, b_row, b_col, c, ldc);
  if (i + 2 <= m)
  {
    product_rows<N, 2>(a_plain, i, k, alpha, a, lda, b, b_row, b_col, c, ldc);
    i += 2;
  }
  if (i < m)
    product_rows<N, 1>(a_plain, i, k, alpha, a, lda, b, b_row, b_col, c, ldc);
}

/// The N columns of op(T) X = B in place, T the upper or lower triangle of A (m x m), with
/// the columns side by side in the innermost loops (MUMPS' pivot blocks are a few rows).
template <int N>
CELLPHASE_KERNEL void solve_triangle(bool upper, bool plain, bool unit, int m, const double* a,
                                     std::ptrdiff_t lda, double* b, std::ptrdiff_t ldb)
{
  if (plain) // column k of T removes x_k from the other rows
    for (int step = 0; step < m; ++step)
    {
      const int k = upper ? m - 1 - step : step; // upper: backward, lower: forward
      double xk[N];
      for (int j = 0; j < N; ++j)
      {
        if (!unit)
          b[k + j * ldb] /= a[k + k * lda];
        xk[j] = b[k + j * ldb];
      }
      const double* ak = a + k * lda;
      const int from = upper ? 0 : k + 1, to = upper ? k : m;
      for (int i = from; i < to; ++i)
        for (int j = 0; j < N; ++j)
          b[i + j * ldb] -= xk[j] * ak[i];
    }
  else // row i of T^T is column i of T: a dot product with the rows already solved
    for (int step = 0; step < m; ++step)
    {
      const int i = upper ? step : m - 1 - step; // U^T: forward, L^T: backward
      const double* ai = a + i * lda;
      double t[N];
      for (int j = 0; j < N; ++j)
        t[j] = b[i + j * ldb];
      const int from = upper ? 0 : i + 1, to = upper ? i : m;
      for (int k = from; k < to; ++k)
        for (int j = 0; j < N; ++j)
          t[j] -= ai[k] * b[k + j * ldb];
      for (int j = 0; j < N; ++j)
        b[i + j * ldb] = unit ? t[j] : t[j] / ai[i];
    }
}

/// dgemm for 1 <= n <= max_columns (the caller checked n, m, k).
CELLPHASE_KERNEL void small_gemm(const char* transa, const char* transb, int m, int n, int k,
                                 double alpha, const double* a, int lda, const double* b,
                                 int ldb, double beta, double* c, int ldc)
{
  scale_columns(m, n, beta, c, ldc);
  if (alpha == 0.0 || m == 0 || k == 0)
    return;
  // Entry (l, j) of op(B) is b[l * b_row + j * b_col].
  const bool b_plain = untransposed(transb);
  const std::ptrdiff_t b_row = b_plain ? 1 : ldb, b_col = b_plain ? ldb : 1;
  const bool a_plain = untransposed(transa);
  switch (n)
  {
  case 1: add_product<1>(a_plain, m, k, alpha, a, lda, b, b_row, b_col, c, ldc); break;
  case 2: add_product<2>(a_plain, m, k, alpha, a, lda, b, b_row, b_col, c, ldc); break;
  case 3: add_product<3>(a_plain, m, k, alpha, a, lda, b, b_row, b_col, c, ldc); break;
  default: add_product<4>(a_plain, m, k, alpha, a, lda, b, b_row, b_col, c, ldc); break;
  }
}

/// dtrsm with side L for 1 <= n <= max_columns.
CELLPHASE_KERNEL void small_trsm(const char* uplo, const char* transa, const char* diag, int m,
                                 int n, double alpha, const double* a, int lda, double* b,
                                 int ldb)
{
  scale_columns(m, n, alpha, b, ldb);
  if (alpha == 0.0)
    return;
  const bool upper = *uplo == 'U' || *uplo == 'u';
  const bool unit = *diag == 'U' || *diag == 'u';
  const bool plain = untransposed(transa);
  switch (n)
  {
  case 1: solve_triangle<1>(upper, plain, unit, m, a, lda, b, ldb); break;
  case 2: solve_triangle<2>(upper, plain, unit, m, a, lda, b, ldb); break;
  case 3: solve_triangle<3>(upper, plain, unit, m, a, lda, b, ldb); break;
  default: solve_triangle<4>(upper, plain, unit, m, a, lda, b, ldb); break;
  }
}

void small_gemm_baseline(const char* ta, const char* tb, int m, int n, int k, double alpha,
                         const double* a, int lda, const double* b, int ldb, double beta,
                         double* c, int ldc)
{
  small_gemm(ta, tb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
}

[[gnu::target("avx2,fma")]] void small_gemm_avx2(const char* ta, const char* tb, int m, int n,
                                                  int k, double alpha, const double* a, int lda,
                                                  const double* b, int ldb, double beta,
                                                  double* c, int ldc)
{
  small_gemm(ta, tb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
}

void small_trsm_baseline(const char* uplo, const char* ta, const char* diag, int m, int n,
                         double alpha, const double* a, int lda, double* b, int ldb)
{
  small_trsm(uplo, ta, diag, m, n, alpha, a, lda, b, ldb);
}

[[gnu::target("avx2,fma")]] void small_trsm_avx2(const char* uplo, const char* ta,
                                                  const char* diag, int m, int n, double alpha,
                                                  const double* a, int lda, double* b, int ldb)
{
  small_trsm(uplo, ta, diag, m, n, alpha, a, lda, b, ldb);
}

/// AVX2 and FMA, unless CELLPHASE_BLAS_BASELINE is set (to test the baseline loops).
bool has_avx2_fma()
{
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")
                          && !std::getenv("CELLPHASE_BLAS_BASELINE");
  return yes;
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
    return (has_avx2_fma() ? small_gemm_avx2 : small_gemm_baseline)(
        transa, transb, *m, *n, *k, *alpha, a, *lda, b, *ldb, *beta, c, *ldc);
  static gemm_fn* blas = next_definition<gemm_fn>("dgemm_");
  blas(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
}

/// B = alpha op(A)^-1 B (side L); for n <= max_columns computed here.
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
            const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            double* b, const int* ldb)
{
  if (*n >= 1 && *n <= max_columns && *m >= 0 && (*side == 'L' || *side == 'l'))
    return (has_avx2_fma() ? small_trsm_avx2 : small_trsm_baseline)(uplo, transa, diag, *m, *n,
                                                                    *alpha, a, *lda, b, *ldb);
  static trsm_fn* blas = next_definition<trsm_fn>("dtrsm_");
  blas(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb);
}
}
