// cpp/BlasForward.cpp: dgemm/dtrsm with a few columns give what the definitions of BLAS give
// (checked against plain loops), wider ones still reach the BLAS library, and the
// executable exports the definitions so that MUMPS binds to them.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

extern "C"
{
void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*,
            const double*, const int*, const double*, const int*, const double*, double*,
            const int*);
void dtrsm_(const char*, const char*, const char*, const char*, const int*, const int*,
            const double*, const double*, const int*, double*, const int*);
}

namespace
{
std::vector<double> random_values(std::size_t n, unsigned seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> v(n);
  for (auto& x : v)
    x = u(gen);
  return v;
}

// Column-major entry (i, j) of op(X) for X with leading dimension ld.
double op(const std::vector<double>& x, int ld, bool transposed, int i, int j)
{
  return transposed ? x[j + i * ld] : x[i + j * ld];
}

// Round-off of a sum of k products of numbers of size 1.
constexpr double kTol = 1e-13;
} // namespace

void gemm_matches_the_definition(int m, int k);
void triangular_solve_matches_the_definition(int m);

// C = alpha op(A) op(B) + beta C from the definition, for every shape and option MUMPS uses
// and more: n = 1..4 columns run in cpp/BlasForward.cpp, n = 5 in the BLAS library.
TEST(BlasForward, GemmMatchesTheDefinition)
{
  // Sizes of MUMPS' solve (blocks of 6 x 25 and 25 x 6 on average) and ones that leave
  // every remainder of the 4-row blocks.
  for (const auto& [m, k] : std::vector<std::pair<int, int>>{{37, 23}, {1, 1}, {2, 3}, {3, 1},
                                                             {5, 7}, {6, 25}, {25, 6}, {7, 2}})
    gemm_matches_the_definition(m, k);
}

void gemm_matches_the_definition(int m, int k)
{
  const int pad = 5;
  for (int n = 1; n <= 5; ++n)
    for (const bool ta : {false, true})
      for (const bool tb : {false, true})
        for (const double beta : {0.0, 0.5, 1.0})
        {
          const int lda = (ta ? k : m) + pad, ldb = (tb ? n : k) + pad, ldc = m + pad;
          const auto a = random_values(std::size_t(lda) * (ta ? m : k), 1);
          const auto b = random_values(std::size_t(ldb) * (tb ? k : n), 2);
          auto c = random_values(std::size_t(ldc) * n, 3);
          if (beta == 0) // BLAS does not read C then: NaN must not propagate
            for (auto& x : c)
              x = std::numeric_limits<double>::quiet_NaN();
          std::vector<double> expected(std::size_t(m) * n);
          const double alpha = -1.5;
          for (int j = 0; j < n; ++j)
            for (int i = 0; i < m; ++i)
            {
              double s = 0;
              for (int l = 0; l < k; ++l)
                s += op(a, lda, ta, i, l) * op(b, ldb, tb, l, j);
              expected[i + j * m] = alpha * s + (beta == 0 ? 0.0 : beta * c[i + j * ldc]);
            }
          dgemm_(ta ? "T" : "N", tb ? "T" : "N", &m, &n, &k, &alpha, a.data(), &lda, b.data(),
                 &ldb, &beta, c.data(), &ldc);
          for (int j = 0; j < n; ++j)
            for (int i = 0; i < m; ++i)
              EXPECT_NEAR(c[i + j * ldc], expected[i + j * m], kTol)
                  << "m " << m << " k " << k << " n " << n << " transa " << ta << " transb "
                  << tb << " beta " << beta << " entry " << i << "," << j;
        }
}

TEST(BlasForward, GemmWithEmptyProductOnlyScalesC)
{
  const int m = 4, n = 2, k = 0, ld = 4;
  std::vector<double> c(m * n, 2.0);
  const double alpha = 1, beta = 0.5, unused = 0;
  dgemm_("N", "N", &m, &n, &k, &alpha, &unused, &ld, &unused, &ld, &beta, c.data(), &ld);
  for (double x : c)
    EXPECT_EQ(x, 1.0);
}

// op(T) X = alpha B solved in place, for n = 1..4 (here) and 5 (the BLAS library).
TEST(BlasForward, TriangularSolveMatchesTheDefinition)
{
  for (const int m : {31, 1, 2, 3, 6, 9}) // 6: MUMPS' pivot blocks of the vesicle
    triangular_solve_matches_the_definition(m);
}

void triangular_solve_matches_the_definition(int m)
{
  const int lda = m + 3, ldb = m + 2;
  auto a = random_values(std::size_t(lda) * m, 6);
  for (int i = 0; i < m; ++i)
    a[i + i * lda] += 4; // well conditioned
  for (int n = 1; n <= 5; ++n)
    for (const double alpha : {1.0, -2.0})
      for (const bool lower : {false, true})
        for (const bool ta : {false, true})
          for (const bool unit : {false, true})
          {
            const auto x = random_values(std::size_t(ldb) * n, 7);
            // b = op(T) x / alpha with T the triangle of a (unit: ones on the diagonal).
            auto t = [&](int i, int j)
            {
              const int r = ta ? j : i, c = ta ? i : j; // entry (i, j) of op(T) is T(r, c)
              if (r == c)
                return unit ? 1.0 : a[r + c * lda];
              return (lower ? r > c : r < c) ? a[r + c * lda] : 0.0;
            };
            std::vector<double> b(std::size_t(ldb) * n, 0.0);
            for (int col = 0; col < n; ++col)
              for (int i = 0; i < m; ++i)
              {
                for (int j = 0; j < m; ++j)
                  b[i + col * ldb] += t(i, j) * x[j + col * ldb];
                b[i + col * ldb] /= alpha;
              }
            dtrsm_("L", lower ? "L" : "U", ta ? "T" : "N", unit ? "U" : "N", &m, &n, &alpha,
                   a.data(), &lda, b.data(), &ldb);
            for (int col = 0; col < n; ++col)
              for (int i = 0; i < m; ++i)
                EXPECT_NEAR(b[i + col * ldb], x[i + col * ldb], 1e-12)
                    << "m " << m << " n " << n << " alpha " << alpha << " lower " << lower
                    << " trans " << ta
                    << " unit " << unit << " entry " << i << "," << col;
          }
}

TEST(BlasForward, ExecutableExportsTheDefinitionsToSharedLibraries)
{
  // What a shared library (MUMPS) finds when it looks the names up.
  EXPECT_EQ(dlsym(RTLD_DEFAULT, "dgemm_"), reinterpret_cast<void*>(&dgemm_));
  EXPECT_EQ(dlsym(RTLD_DEFAULT, "dtrsm_"), reinterpret_cast<void*>(&dtrsm_));
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
