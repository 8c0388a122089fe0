#include "scene/Shapes.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <muParser.h>
#include <stdexcept>

namespace cellphase::scene
{
namespace
{

/// Signed distance from q to the ellipsoid x_i^2/e_i^2 = 1 (n = 2 or 3 axes). The closest
/// point is x_i = e_i^2 y_i / (s + e_i^2 - e_min^2) with s >= 0 the root of a convex,
/// decreasing function, so Newton started left of the root converges monotonically.
double ellipsoid_distance(const double* q, const double* e, int n)
{
  double y[3], d[3], x[3];
  double emin = e[0], g = 0;
  for (int i = 0; i < n; ++i)
  {
    y[i] = std::abs(q[i]); // symmetric: work in the first octant
    g += (y[i] / e[i]) * (y[i] / e[i]);
    emin = std::min(emin, e[i]);
  }
  for (int i = 0; i < n; ++i)
    d[i] = e[i] * e[i] - emin * emin;

  auto G = [&](double s, double* dG)
  {
    double sum = -1, der = 0;
    for (int i = 0; i < n; ++i)
    {
      if (y[i] == 0)
        continue;
      const double t = e[i] * y[i] / (s + d[i]);
      sum += t * t;
      der -= 2 * t * t / (s + d[i]);
    }
    if (dG)
      *dG = der;
    return sum;
  };

  double lo = 0, hi = 0;
  for (int i = 0; i < n; ++i)
  {
    lo = std::max(lo, e[i] * y[i] - d[i]); // G >= 0 up to here
    hi += (e[i] * y[i]) * (e[i] * y[i]);
  }
  hi = std::sqrt(hi); // G <= 0 from here

  if (lo == 0 && G(0, nullptr) <= 0)
  {
    // Point inside, on the plane of the shortest axis: the closest point leaves that plane.
    double rest = 1;
    int k = -1;
    for (int i = 0; i < n; ++i)
    {
      if (d[i] > 0)
      {
        x[i] = e[i] * e[i] * y[i] / d[i];
        rest -= (x[i] / e[i]) * (x[i] / e[i]);
      }
      else
      {
        x[i] = 0;
        if (k < 0)
          k = i;
      }
    }
    x[k] = emin * std::sqrt(std::max(rest, 0.0));
  }
  else
  {
    double s = lo;
    for (int it = 0; it < 200; ++it)
    {
      double dG;
      const double val = G(s, &dG);
      if (val <= 0 || dG == 0)
        break;
      double next = s - val / dG;
      if (!(next > s))
        break;
      if (next > hi)
        next = 0.5 * (s + hi);
      const bool converged = next - s <= 1e-15 * next;
      s = next;
      if (converged)
        break;
    }
    for (int i = 0; i < n; ++i)
      x[i] = e[i] * e[i] * y[i] / (s + d[i]);
  }

  double dist = 0;
  for (int i = 0; i < n; ++i)
    dist += (x[i] - y[i]) * (x[i] - y[i]);
  dist = std::sqrt(dist);
  return g < 1 ? -dist : dist;
}

/// f = |q - f1|^2 |q - f2|^2 - b^4 with the foci at (+-a, 0, 0): negative inside.
double cassini_f(const double* q, double a, double b)
{
  const double d1 = (q[0] - a) * (q[0] - a) + q[1] * q[1] + q[2] * q[2];
  const double d2 = (q[0] + a) * (q[0] + a) + q[1] * q[1] + q[2] * q[2];
  return d1 * d2 - b * b * b * b;
}

/// Distance from (u, v) to the segment pq; `nearest` (if given) receives its nearest point.
double segment_distance(double u, double v, const std::array<double, 2>& p,
                        const std::array<double, 2>& q, std::array<double, 2>* nearest = nullptr)
{
  const double ex = q[0] - p[0], ey = q[1] - p[1];
  const double len2 = ex * ex + ey * ey;
  const double t = len2 > 0 ? std::clamp(((u - p[0]) * ex + (v - p[1]) * ey) / len2, 0.0, 1.0) : 0.0;
  const double dx = u - p[0] - t * ex, dy = v - p[1] - t * ey;
  if (nearest)
    *nearest = {p[0] + t * ex, p[1] + t * ey};
  return std::sqrt(dx * dx + dy * dy);
}
} // namespace

CassiniQuarter::CassiniQuarter(double a, double b) : a_(a), b_(b)
{
  // r^2(theta) = a^2 cos 2theta +- sqrt(b^4 - a^4 sin^2 2theta): for b >= a one branch (+)
  // from the x axis (theta = 0) to the y axis; for b < a the loop about the focus, + out to
  // the largest theta (sin 2theta = b^2/a^2) and - back.
  const int n = coarse * fine;
  const double a2 = a * a, b4 = b * b * b * b;
  auto point = [&](double theta, double sign)
  {
    const double root = std::sqrt(std::max(0.0, b4 - a2 * a2 * std::sin(2 * theta) * std::sin(2 * theta)));
    const double r = std::sqrt(std::max(0.0, a2 * std::cos(2 * theta) + sign * root));
    return std::array<double, 2>{r * std::cos(theta), r * std::sin(theta)};
  };
  if (b >= a)
    for (int i = 0; i <= n; ++i)
      points_.push_back(point(0.5 * std::numbers::pi * i / n, 1));
  else
  {
    // theta = top (1 - (1 - s)^2): the branches meet at theta = top with a vertical
    // tangent in r(theta), where uniform theta would leave gaps of sqrt(dtheta).
    const double top = 0.5 * std::asin(b * b / a2);
    auto theta = [&](int i) { const double s = 1.0 - double(i) / (n / 2); return top * (1 - s * s); };
    for (int i = 0; i <= n / 2; ++i)
      points_.push_back(point(theta(i), 1));
    for (int i = n / 2 - 1; i >= 0; --i)
      points_.push_back(point(theta(i), -1));
  }
  // Each coarse chord and how far the fine points of its span are from it.
  sagitta_.resize(coarse);
  for (int j = 0; j < coarse; ++j)
    for (int i = j * fine; i <= (j + 1) * fine; ++i)
      sagitta_[j] = std::max(sagitta_[j], segment_distance(points_[i][0], points_[i][1],
                                                           points_[j * fine],
                                                           points_[(j + 1) * fine]));
}

double CassiniQuarter::distance(double u, double v) const
{
  // A coarse chord's distance is within its sagitta of its arc's: only the arcs that may
  // hold the nearest point are searched on the fine polyline.
  std::array<double, coarse> chord;
  double upper = std::numeric_limits<double>::infinity();
  for (int j = 0; j < coarse; ++j)
  {
    chord[j] = segment_distance(u, v, points_[j * fine], points_[(j + 1) * fine]);
    upper = std::min(upper, chord[j] + sagitta_[j]);
  }
  double best = std::numeric_limits<double>::infinity();
  std::array<double, 2> foot{};
  for (int j = 0; j < coarse; ++j)
    if (chord[j] - sagitta_[j] <= upper)
      for (int i = j * fine; i < (j + 1) * fine; ++i)
      {
        std::array<double, 2> near;
        const double d = segment_distance(u, v, points_[i], points_[i + 1], &near);
        if (d < best)
          best = d, foot = near;
      }
  // The slide along the tangent converges where the distance is well below the radius of
  // curvature; farther out the polyline's error (~2e-7 of the size) is small beside it.
  return best < 0.01 * (a_ + b_) ? refine(u, v, foot, best) : best;
}

double CassiniQuarter::refine(double u, double v, std::array<double, 2> p, double d) const
{
  // The polyline's foot point onto the curve g = 0 (g = f in the (x, rho) plane): Newton
  // steps onto the curve, each followed by a slide along the tangent towards (u, v), where
  // the foot point makes q - p normal to the curve.
  auto project = [&](std::array<double, 2>& x) -> std::array<double, 2>
  {
    for (int k = 0; k < 3; ++k)
    {
      const double d1 = (x[0] - a_) * (x[0] - a_) + x[1] * x[1];
      const double d2 = (x[0] + a_) * (x[0] + a_) + x[1] * x[1];
      const double g = d1 * d2 - b_ * b_ * b_ * b_;
      const std::array<double, 2> grad{2 * (x[0] - a_) * d2 + 2 * (x[0] + a_) * d1,
                                       2 * x[1] * (d1 + d2)};
      const double n2 = grad[0] * grad[0] + grad[1] * grad[1];
      if (!(n2 > 1e-30))
        return {0, 0};
      x[0] -= g * grad[0] / n2;
      x[1] -= g * grad[1] / n2;
      if (k == 2)
        return {grad[0] / std::sqrt(n2), grad[1] / std::sqrt(n2)};
    }
    return {0, 0};
  };
  for (int it = 0; it < 4; ++it)
  {
    const auto n = project(p);
    if (n[0] == 0 && n[1] == 0)
      return d;
    const std::array<double, 2> t{-n[1], n[0]};
    const double slide = (u - p[0]) * t[0] + (v - p[1]) * t[1];
    p[0] += slide * t[0];
    p[1] += slide * t[1];
  }
  if (const auto n = project(p); n[0] == 0 && n[1] == 0)
    return d;
  const double refined = std::hypot(u - p[0], v - p[1]);
  // The polyline is within ~2e-7 of the oval's size of the curve: a foot point that moved
  // the distance by more than 1e-6 of it has left for another part of the curve.
  return std::abs(refined - d) <= 1e-6 * (a_ + b_) ? refined : d;
}

namespace
{
/// Signed distance to the Cassini oval (a surface of revolution about the x axis in 3D):
/// the distance to the quarter curve of the first quadrant, which holds the nearest point
/// of the point mirrored there (the oval is symmetric about both axes); the sign of f.
double cassini_distance(const double* q, double a, double b, const CassiniQuarter& quarter)
{
  const double d = quarter.distance(std::abs(q[0]), std::sqrt(q[1] * q[1] + q[2] * q[2]));
  return cassini_f(q, a, b) < 0 ? -d : d;
}

} // namespace

struct SignedDistance::Expression
{
  mu::Parser parser;
  double x = 0, y = 0, z = 0;
};

SignedDistance::SignedDistance(const Cell& cell, int dim)
    : cell_(cell), dim_(dim), cos_(std::cos(cell.rotation)), sin_(std::sin(cell.rotation))
{
  if (cell.shape == ShapeKind::cassini)
    cassini_ = std::make_shared<const CassiniQuarter>(cell.cassini_a, cell.cassini_b);
  if (cell.shape != ShapeKind::expression && cell.shape != ShapeKind::field)
    return;
  expr_ = std::make_shared<Expression>();
  try
  {
    expr_->parser.DefineVar("x", &expr_->x);
    expr_->parser.DefineVar("y", &expr_->y);
    expr_->parser.DefineVar("z", &expr_->z);
    expr_->parser.SetExpr(cell.expression);
    expr_->parser.Eval(); // parse now, not at the first evaluation
  }
  catch (const mu::Parser::exception_type& e)
  {
    throw std::invalid_argument("cannot parse distance expression '" + cell.expression
                                + "': " + e.GetMsg());
  }
}

double SignedDistance::operator()(double x, double y, double z) const
{
  // Cell frame: translate to the centre, then undo the rotation about z.
  const double dx = x - cell_.center[0], dy = y - cell_.center[1];
  double q[3] = {cos_ * dx + sin_ * dy, -sin_ * dx + cos_ * dy,
                 dim_ == 3 ? z - cell_.center[2] : 0.0};
  switch (cell_.shape)
  {
  case ShapeKind::circle:
    return std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - cell_.radius;
  case ShapeKind::ellipse:
    return ellipsoid_distance(q, cell_.semi_axes.data(), dim_);
  case ShapeKind::cassini:
    return cassini_distance(q, cell_.cassini_a, cell_.cassini_b, *cassini_);
  case ShapeKind::expression:
    expr_->x = q[0];
    expr_->y = q[1];
    expr_->z = q[2];
    return expr_->parser.Eval();
  case ShapeKind::field:
  {
    // The distance whose tanh profile (2.12) is phi_0: r = -sqrt2 eps atanh(phi_0).
    const double phi = std::clamp(phi_value(x, y, z), -1 + 1e-15, 1 - 1e-15);
    return -std::sqrt(2.0) * cell_.field_epsilon * std::atanh(phi);
  }
  }
  return 0;
}

double SignedDistance::phi_value(double x, double y, double z) const
{
  const double dx = x - cell_.center[0], dy = y - cell_.center[1];
  expr_->x = cos_ * dx + sin_ * dy;
  expr_->y = -sin_ * dx + cos_ * dy;
  expr_->z = dim_ == 3 ? z - cell_.center[2] : 0.0;
  return expr_->parser.Eval();
}

std::string check_expression(const std::string& expression)
{
  mu::Parser p;
  double x = 0.1, y = 0.2, z = 0.3;
  try
  {
    p.DefineVar("x", &x);
    p.DefineVar("y", &y);
    p.DefineVar("z", &z);
    p.SetExpr(expression);
    int results = 0;
    p.Eval(results);
    if (results != 1)
      return "the expression gives " + std::to_string(results)
             + " values (comma-separated); it must give one";
  }
  catch (const mu::Parser::exception_type& e)
  {
    return e.GetMsg();
  }
  return {};
}

InitialPhaseField::InitialPhaseField(const Scene& s)
    : domain_(s.domain), epsilon_(s.numerics.epsilon)
{
  for (const Cell& c : s.cells)
    cells_.emplace_back(c, s.domain.dim);
  image_shifts_.push_back({0.0, 0.0, 0.0});
  for (int a : domain_.periodic)
  {
    const double L = domain_.upper[a] - domain_.lower[a];
    const std::size_t n = image_shifts_.size();
    for (std::size_t i = 0; i < n; ++i)
      for (double shift : {-L, L})
      {
        auto q = image_shifts_[i];
        q[a] += shift;
        image_shifts_.push_back(q);
      }
  }
}

double InitialPhaseField::nearest_image_distance(double x, double y, double z,
                                                 bool shapes_only) const
{
  double r = INFINITY;
  for (const auto& s : image_shifts_)
    for (const SignedDistance& d : cells_)
      if (!(shapes_only && d.is_field()))
        r = std::min(r, d(x + s[0], y + s[1], z + s[2]));
  return r;
}

double InitialPhaseField::distance(double x, double y, double z) const
{
  return nearest_image_distance(x, y, z, false);
}

double InitialPhaseField::operator()(double x, double y, double z) const
{
  // max_i tanh(-r_i/(sqrt2 eps)) = tanh(-min_i r_i/(sqrt2 eps)): tanh is monotone. A field
  // cell gives its phi_0 itself (exactly, not through atanh and tanh), at the point's image
  // in the domain (its formula or file describes the domain).
  double phi = -INFINITY;
  bool shapes = false;
  const auto in_domain = domain_.into_period(x, y, z);
  for (const SignedDistance& d : cells_)
    if (d.is_field())
      phi = std::max(phi, d.phi_value(in_domain[0], in_domain[1], in_domain[2]));
    else
      shapes = true;
  if (shapes)
  {
    const double r = nearest_image_distance(x, y, z, true);
    phi = std::max(phi, std::tanh(-r / (std::sqrt(2.0) * epsilon_)));
  }
  return phi;
}

} // namespace cellphase::scene
