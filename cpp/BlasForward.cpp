// Matrix-times-one-vector BLAS-3 calls forwarded to their BLAS-2 counterparts.
//
// A MUMPS solve with one right-hand side calls dgemm and dtrsm with n = 1 for every front.
// OpenBLAS 0.3.21 (Debian bookworm) packs the whole factor block into a buffer for such a
// call (its gemm copy routines took a third of a solve's time), while dgemv and dtrsv read
// the block once: a Stokes solve with a reused factorisation runs about 20 % faster
// (benchmarks/flow_reuse.py). Linked into the executable and exported
// (CMakeLists.txt), these definitions come first in the dynamic symbol lookup, so MUMPS
// calls them; every other call goes on to the BLAS library's own routine.
#include <dlfcn.h>

namespace
{
using gemm_fn = void(const char*, const char*, const int*, const int*, const int*, const double*,
                     const double*, const int*, const double*, const int*, const double*, double*,
                     const int*);
using trsm_fn = void(const char*, const char*, const char*, const char*, const int*, const int*,
                     const double*, const double*, const int*, double*, const int*);

bool untransposed(const char* t) { return *t == 'N' || *t == 'n'; }

/// The BLAS library's definition (the next one after this executable's).
template <typename F>
F* next_definition(const char* name)
{
  return reinterpret_cast<F*>(dlsym(RTLD_NEXT, name));
}
} // namespace

extern "C"
{
void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a,
            const int* lda, const double* x, const int* incx, const double* beta, double* y,
            const int* incy);
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a,
            const int* lda, double* x, const int* incx);

/// C = alpha op(A) op(B) + beta C; for n = 1, C and op(B) are vectors: one dgemv.
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc)
{
  if (*n == 1 && *m > 0 && *k > 0)
  {
    const int one = 1;
    const int incb = untransposed(transb) ? 1 : *ldb; // a column of B, or a row of B^T
    if (untransposed(transa))                         // A is m x k
      dgemv_("N", m, k, alpha, a, lda, b, &incb, beta, c, &one);
    else // A is k x m
      dgemv_("T", k, m, alpha, a, lda, b, &incb, beta, c, &one);
    return;
  }
  static gemm_fn* blas = next_definition<gemm_fn>("dgemm_");
  blas(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
}

/// B = alpha op(A)^-1 B (side L); for n = 1 and alpha = 1, B is a vector: one dtrsv.
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
            const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            double* b, const int* ldb)
{
  if (*n == 1 && *m > 0 && *alpha == 1.0 && (*side == 'L' || *side == 'l'))
  {
    const int one = 1;
    dtrsv_(uplo, transa, diag, m, a, lda, b, &one);
    return;
  }
  static trsm_fn* blas = next_definition<trsm_fn>("dtrsm_");
  blas(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb);
}
}
