#include "physics/SharpInterface.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace cellphase
{
namespace
{
using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }
Vec lerp(const Vec& a, const Vec& b, double t)
{
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

// P2 node order of basix: the vertices, then the edges (2D: e0 = (1,2), e1 = (0,2),
// e2 = (0,1); 3D: (2,3), (1,3), (1,2), (0,3), (0,2), (0,1)). The linear cells on them:
constexpr int edges_2d[3][2] = {{1, 2}, {0, 2}, {0, 1}};
constexpr int edges_3d[6][2] = {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}};
constexpr int sub_2d[4][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}, {5, 3, 4}};
constexpr int sub_3d[8][4] = {{0, 9, 8, 7}, {1, 9, 6, 5}, {2, 8, 6, 4}, {3, 7, 5, 4},
                              {8, 5, 9, 6}, {8, 5, 6, 4}, {8, 5, 4, 7}, {8, 5, 7, 9}};

/// The affine map of one parent cell: barycentric coordinates and gradients, the P2
/// interpolant of nodal values and the gradient of the P2 phi at a point.
struct ParentCell
{
  int dim;
  Vec x0;
  std::array<Vec, 4> grad_lambda{}; ///< grad lambda_i
  std::array<double, 10> phi{};     ///< P2 nodal values

  ParentCell(int d, const std::array<Vec, 4>& v, const std::array<double, 10>& values)
      : dim(d), x0(v[0]), phi(values)
  {
    // J = [v1 - v0, v2 - v0 (, v3 - v0)]; grad lambda_i (i >= 1) are the rows of J^-1.
    Vec a = sub(v[1], v[0]), b = sub(v[2], v[0]), c = d == 3 ? sub(v[3], v[0]) : Vec{0, 0, 1};
    const double det = dot(a, cross(b, c));
    grad_lambda[1] = cross(b, c), grad_lambda[2] = cross(c, a), grad_lambda[3] = cross(a, b);
    for (int i = 1; i <= 3; ++i)
      for (auto& g : grad_lambda[i])
        g /= det;
    for (int k = 0; k < 3; ++k)
      grad_lambda[0][k] = -(grad_lambda[1][k] + grad_lambda[2][k] + (d == 3 ? grad_lambda[3][k] : 0));
  }

  std::array<double, 4> barycentric(const Vec& x) const
  {
    std::array<double, 4> lambda{};
    const Vec r = sub(x, x0);
    lambda[0] = 1;
    for (int i = 1; i <= dim; ++i)
      lambda[0] -= lambda[i] = dot(grad_lambda[i], r);
    return lambda;
  }

  /// The P2 interpolant of the nodal values `u` at x.
  double interpolate(const std::array<double, 10>& u, const Vec& x) const
  {
    const auto lambda = barycentric(x);
    const int nv = dim + 1, ne = dim == 2 ? 3 : 6;
    double value = 0;
    for (int i = 0; i < nv; ++i)
      value += u[i] * lambda[i] * (2 * lambda[i] - 1);
    for (int e = 0; e < ne; ++e)
    {
      const auto* ab = dim == 2 ? edges_2d[e] : edges_3d[e];
      value += u[nv + e] * 4 * lambda[ab[0]] * lambda[ab[1]];
    }
    return value;
  }

  /// grad phi at x, from the P2 field of this cell.
  Vec gradient(const Vec& x) const
  {
    const auto lambda = barycentric(x);
    Vec g{0, 0, 0};
    const int nv = dim + 1, ne = dim == 2 ? 3 : 6;
    for (int i = 0; i < nv; ++i)
      for (int k = 0; k < 3; ++k)
        g[k] += phi[i] * (4 * lambda[i] - 1) * grad_lambda[i][k];
    for (int e = 0; e < ne; ++e)
    {
      const auto* ab = dim == 2 ? edges_2d[e] : edges_3d[e];
      for (int k = 0; k < 3; ++k)
        g[k] += 4 * phi[nv + e]
                * (lambda[ab[0]] * grad_lambda[ab[1]][k] + lambda[ab[1]] * grad_lambda[ab[0]][k]);
    }
    return g;
  }
};

/// Values nudged so that none is 0 and no two are equal (relative 1e-12): the formulas
/// below divide by their differences; the measures move by O(1e-12) only.
template <std::size_t N>
void separate(std::array<double, N>& v)
{
  double scale = 0;
  for (double x : v)
    scale = std::max(scale, std::abs(x));
  const double tiny = 1e-12 * (scale > 0 ? scale : 1.0);
  for (std::size_t i = 0; i < N; ++i)
  {
    if (std::abs(v[i]) < tiny)
      v[i] = -tiny * (1 + double(i));
    for (std::size_t j = 0; j < i; ++j)
      if (std::abs(v[i] - v[j]) < tiny)
        v[i] += tiny * (2 + double(i));
  }
}

/// Fraction of a simplex where its linear function is positive: the sum over the positive
/// vertices of v_i^d / prod_{j != i} (v_i - v_j) (the divided difference of max(x, 0)^d).
template <std::size_t N>
double positive_fraction(const std::array<double, N>& v)
{
  double f = 0;
  for (std::size_t i = 0; i < N; ++i)
  {
    if (v[i] <= 0)
      continue;
    double term = std::pow(v[i], double(N - 1));
    for (std::size_t j = 0; j < N; ++j)
      if (j != i)
        term /= v[i] - v[j];
    f += term;
  }
  return std::clamp(f, 0.0, 1.0);
}
} // namespace

SharpMeasures sharp_measures(const Function& phi, const Function* mu, double H0, double eps)
{
  const auto& V = *phi.function_space();
  const Mesh& mesh = *V.mesh();
  const int dim = mesh.topology().dim();
  const int nv = dim + 1, n = dim == 2 ? 6 : 10;
  const auto& x = mesh.geometry().x();
  const auto& geometry = mesh.geometry().dofmap();
  auto values = phi.x()->array();
  struct Cell
  {
    std::array<Vec, 4> vertex{};
    std::array<Vec, 10> point{};  ///< the P2 nodes
    std::array<double, 10> p{};   ///< phi there
    double lo = 1e300, hi = -1e300, measure = 0;
  };
  auto cell_of = [&](std::int32_t c)
  {
    Cell k;
    auto dofs = V.dofmap()->cell_dofs(c);
    auto nodes = geometry.links(c);
    for (int i = 0; i <= dim; ++i)
      for (int d = 0; d < 3; ++d)
        k.vertex[i][d] = x[3 * nodes[i] + d];
    for (int i = 0; i < n; ++i)
    {
      k.p[i] = values[dofs[i]];
      k.lo = std::min(k.lo, k.p[i]), k.hi = std::max(k.hi, k.p[i]);
      if (i < nv)
        k.point[i] = k.vertex[i];
      else
      {
        const auto* ab = dim == 2 ? edges_2d[i - nv] : edges_3d[i - nv];
        k.point[i] = lerp(k.vertex[ab[0]], k.vertex[ab[1]], 0.5);
      }
    }
    const auto& v = k.vertex;
    k.measure = dim == 2 ? norm(cross(sub(v[1], v[0]), sub(v[2], v[0]))) / 2
                         : std::abs(dot(sub(v[1], v[0]), cross(sub(v[2], v[0]), sub(v[3], v[0])))) / 6;
    return k;
  };
  const std::int32_t cells = compat::num_owned_cells(mesh);

  SharpMeasures m;
  for (std::int32_t c = 0; c < cells; ++c)
  {
    const Cell k = cell_of(c);
    if (k.lo > 0)
    {
      m.inside += k.measure;
      continue;
    }
    if (k.hi <= 0)
      continue;
    ParentCell parent(dim, k.vertex, k.p);
    std::array<double, 10> mu_cell{};
    if (mu)
    {
      auto dofs = V.dofmap()->cell_dofs(c);
      auto mu_values = mu->x()->array();
      for (int i = 0; i < n; ++i)
        mu_cell[i] = mu_values[dofs[i]];
    }
    auto bend = [&](const Vec& at, double size)
    {
      m.surface += size;
      if (!mu)
        return;
      // kappa = (-mu + sqrt2 H0 (1 - phi^2)) / (eps |grad phi|) with phi = 0 here: the
      // diffuse curvature of (3.24) over eps |grad phi|, pointwise (no second derivatives).
      const double kappa =
          (-parent.interpolate(mu_cell, at) + std::sqrt(2.0) * H0) / (eps * norm(parent.gradient(at)));
      m.bending += 0.5 * (kappa - H0) * (kappa - H0) * size;
    };
    const int subcells = dim == 2 ? 4 : 8;
    // One sub-simplex s of the table: its nodal values (kept off zero) and points, and its
    // part of the enclosed measure.
    auto gather = [&](const auto& table, int s, auto& v, auto& q)
    {
      for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = k.p[table[s][i]], q[i] = k.point[table[s][i]];
      separate(v);
      m.inside += positive_fraction(v) * k.measure / subcells;
    };
    for (int s = 0; s < subcells; ++s)
    {
      if (dim == 2)
      {
        std::array<double, 3> v;
        std::array<Vec, 3> q;
        gather(sub_2d, s, v, q);
        std::vector<Vec> cut;
        for (int i = 0; i < 3; ++i)
          for (int j = i + 1; j < 3; ++j)
            if ((v[i] > 0) != (v[j] > 0))
              cut.push_back(lerp(q[i], q[j], v[i] / (v[i] - v[j])));
        if (cut.size() == 2)
          bend(lerp(cut[0], cut[1], 0.5), norm(sub(cut[1], cut[0])));
        continue;
      }
      std::array<double, 4> v;
      std::array<Vec, 4> q;
      gather(sub_3d, s, v, q);
      // The zero set: a triangle (one vertex apart) or a quadrilateral (two and two),
      // its corners on the edges whose ends differ in sign, in cyclic order.
      std::vector<int> plus, minus;
      for (int i = 0; i < 4; ++i)
        (v[i] > 0 ? plus : minus).push_back(i);
      auto crossing = [&](int i, int j) { return lerp(q[i], q[j], v[i] / (v[i] - v[j])); };
      std::vector<Vec> poly;
      if (plus.size() == 1 || minus.size() == 1)
      {
        const auto& one = plus.size() == 1 ? plus : minus;
        const auto& rest = plus.size() == 1 ? minus : plus;
        for (int r : rest)
          poly.push_back(crossing(one[0], r));
      }
      else if (plus.size() == 2)
        poly = {crossing(plus[0], minus[0]), crossing(plus[0], minus[1]),
                crossing(plus[1], minus[1]), crossing(plus[1], minus[0])};
      for (std::size_t t = 1; t + 1 < poly.size(); ++t)
      {
        Vec centroid{};
        for (int d = 0; d < 3; ++d)
          centroid[d] = (poly[0][d] + poly[t][d] + poly[t + 1][d]) / 3;
        bend(centroid, norm(cross(sub(poly[t], poly[0]), sub(poly[t + 1], poly[0]))) / 2);
      }
    }
  }
  std::array<double, 3> sums{m.inside, m.surface, m.bending};
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), 3, MPI_DOUBLE, MPI_SUM, mesh.comm());
  return {sums[0], sums[1], sums[2]};
}
} // namespace cellphase
