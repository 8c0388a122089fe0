#include "scene/Shapes.h"
#include <algorithm>
#include <cmath>
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

/// f / |grad f| with f = |q-f1|^2 |q-f2|^2 - b^4, foci at (+-a, 0, 0).
double cassini_distance(const double* q, double a, double b)
{
  const double r1[3] = {q[0] - a, q[1], q[2]};
  const double r2[3] = {q[0] + a, q[1], q[2]};
  const double d1 = r1[0] * r1[0] + r1[1] * r1[1] + r1[2] * r1[2];
  const double d2 = r2[0] * r2[0] + r2[1] * r2[1] + r2[2] * r2[2];
  const double f = d1 * d2 - b * b * b * b;
  double grad2 = 0;
  for (int i = 0; i < 3; ++i)
  {
    const double gi = 2 * (r1[i] * d2 + r2[i] * d1);
    grad2 += gi * gi;
  }
  const double r = f / std::sqrt(grad2);
  // grad f vanishes at the foci and the midpoint, far from the zero set: any finite value
  // of the right sign does there.
  const double cap = a + b;
  if (!std::isfinite(r) || std::abs(r) > 1e3 * cap)
    return std::copysign(cap, f);
  return r;
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
    return cassini_distance(q, cell_.cassini_a, cell_.cassini_b);
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

InitialPhaseField::InitialPhaseField(const Scene& s) : epsilon_(s.numerics.epsilon)
{
  for (const Cell& c : s.cells)
    cells_.emplace_back(c, s.domain.dim);
}

double InitialPhaseField::distance(double x, double y, double z) const
{
  double r = INFINITY;
  for (const SignedDistance& d : cells_)
    r = std::min(r, d(x, y, z));
  return r;
}

double InitialPhaseField::operator()(double x, double y, double z) const
{
  // max_i tanh(-r_i/(sqrt2 eps)) = tanh(-min_i r_i/(sqrt2 eps)): tanh is monotone. A field
  // cell gives its phi_0 itself (exactly, not through atanh and tanh).
  double phi = -INFINITY;
  bool shapes = false;
  for (const SignedDistance& d : cells_)
    if (d.is_field())
      phi = std::max(phi, d.phi_value(x, y, z));
    else
      shapes = true;
  if (shapes)
  {
    double r = INFINITY;
    for (const SignedDistance& d : cells_)
      if (!d.is_field())
        r = std::min(r, d(x, y, z));
    phi = std::max(phi, std::tanh(-r / (std::sqrt(2.0) * epsilon_)));
  }
  return phi;
}

} // namespace cellphase::scene
