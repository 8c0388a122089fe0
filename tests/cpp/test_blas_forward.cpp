// cpp/BlasForward.cpp: dgemm/dtrsm with one column give what the definitions of BLAS give
// (checked against plain loops), other shapes still reach the BLAS library, and the
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

TEST(BlasForward, GemmWithOneColumnMatchesTheDefinition)
{
  const int m = 37, k = 23, pad = 5;
  for (const bool ta : {false, true})
    for (const bool tb : {false, true})
      for (const double beta : {0.0, 0.5})
      {
        const int lda = (ta ? k : m) + pad, ldb = (tb ? 1 : k) + pad, ldc = m + pad;
        const int n = 1;
        const auto a = random_values(std::size_t(lda) * (ta ? m : k), 1);
        const auto b = random_values(std::size_t(ldb) * (tb ? k : 1), 2);
        auto c = random_values(std::size_t(ldc), 3);
        if (beta == 0) // BLAS does not read C then: NaN must not propagate
          for (auto& x : c)
            x = std::numeric_limits<double>::quiet_NaN();
        std::vector<double> expected(m);
        const double alpha = -1.5;
        for (int i = 0; i < m; ++i)
        {
          double s = 0;
          for (int l = 0; l < k; ++l)
            s += op(a, lda, ta, i, l) * op(b, ldb, tb, l, 0);
          expected[i] = alpha * s + (beta == 0 ? 0.0 : beta * c[i]);
        }
        dgemm_(ta ? "T" : "N", tb ? "T" : "N", &m, &n, &k, &alpha, a.data(), &lda, b.data(),
               &ldb, &beta, c.data(), &ldc);
        for (int i = 0; i < m; ++i)
          EXPECT_NEAR(c[i], expected[i], kTol) << "transa " << ta << " transb " << tb
                                                << " beta " << beta << " row " << i;
      }
}

TEST(BlasForward, GemmWithSeveralColumnsStillWorks)
{
  const int m = 9, n = 4, k = 6;
  const auto a = random_values(m * k, 4), b = random_values(k * n, 5);
  std::vector<double> c(m * n, 0.0);
  const double one = 1, zero = 0;
  dgemm_("N", "N", &m, &n, &k, &one, a.data(), &m, b.data(), &k, &zero, c.data(), &m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j)
    {
      double s = 0;
      for (int l = 0; l < k; ++l)
        s += a[i + l * m] * b[l + j * k];
      EXPECT_NEAR(c[i + j * m], s, kTol);
    }
}

TEST(BlasForward, TriangularSolveWithOneColumnMatchesTheDefinition)
{
  const int m = 31, lda = m + 3, n = 1, ldb = m;
  auto a = random_values(std::size_t(lda) * m, 6);
  for (int i = 0; i < m; ++i)
    a[i + i * lda] += 4; // well conditioned
  const double one = 1;
  for (const bool lower : {false, true})
    for (const bool ta : {false, true})
      for (const bool unit : {false, true})
      {
        const auto x = random_values(m, 7);
        // b = op(T) x with T the triangle of a (unit: ones on the diagonal).
        auto t = [&](int i, int j)
        {
          const int r = ta ? j : i, c = ta ? i : j; // entry (i, j) of op(T) is T(r, c)
          if (r == c)
            return unit ? 1.0 : a[r + c * lda];
          return (lower ? r > c : r < c) ? a[r + c * lda] : 0.0;
        };
        std::vector<double> b(m, 0.0);
        for (int i = 0; i < m; ++i)
          for (int j = 0; j < m; ++j)
            b[i] += t(i, j) * x[j];
        dtrsm_("L", lower ? "L" : "U", ta ? "T" : "N", unit ? "U" : "N", &m, &n, &one, a.data(),
               &lda, b.data(), &ldb);
        for (int i = 0; i < m; ++i)
          EXPECT_NEAR(b[i], x[i], 1e-12) << "lower " << lower << " trans " << ta << " unit "
                                         << unit << " row " << i;
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
