// Initial cell shapes as signed distance functions, and the initial phase field (2.12).
#pragma once
#include "scene/Scene.h"
#include <memory>
#include <string>
#include <vector>

namespace cellphase::scene
{

/// Signed distance to one cell's boundary, negative inside. Exact for circles/spheres and
/// ellipses/ellipsoids; first-order estimate f/|grad f| for Cassini ovals (accurate near
/// the zero level set, which is all the tanh profile needs); user-given for expressions.
/// Expressions are evaluated in the cell's frame (centre subtracted, rotation undone).
/// Copies of an expression cell share one muparser instance: do not evaluate them from
/// several threads at once (MPI ranks are separate processes and are fine).
class SignedDistance
{
public:
  /// Throws std::invalid_argument if an expression does not parse (the loader rejects
  /// such scenes first, see check_expression()).
  SignedDistance(const Cell& cell, int dim);
  double operator()(double x, double y, double z = 0) const;
  /// Shape field: its phi_0 at the point (the distance is -sqrt2 eps atanh(phi_0)).
  double phi_value(double x, double y, double z = 0) const;
  bool is_field() const { return cell_.shape == ShapeKind::field; }

private:
  struct Expression;
  Cell cell_;
  int dim_;
  double cos_, sin_;
  std::shared_ptr<Expression> expr_; // shared: copies reuse the compiled parser
};

/// Empty if `expression` is a valid muparser expression in x, y, z giving one value;
/// otherwise muparser's message.
std::string check_expression(const std::string& expression);

/// phi_0 = max over cells of tanh(-r_i / (sqrt2 eps)): +1 inside cells, -1 outside.
class InitialPhaseField
{
public:
  explicit InitialPhaseField(const Scene& s);
  double operator()(double x, double y, double z = 0) const;
  /// Smallest signed distance over all cells (negative inside some cell).
  double distance(double x, double y, double z = 0) const;

private:
  std::vector<SignedDistance> cells_;
  double epsilon_;
};

} // namespace cellphase::scene
