// Initial cell shapes as signed distance functions, and the initial phase field (2.12).
#pragma once
#include "scene/Scene.h"
#include <array>
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
/// The quarter of a Cassini oval |x - f1| |x - f2| = b^2 (foci (+-a, 0)) in the first
/// quadrant as a polyline of coarse x fine chords, and the distance of a point of the
/// first quadrant to it (chord error below 1e-6 of the oval's size).
class CassiniQuarter
{
public:
  CassiniQuarter(double a, double b);
  double distance(double u, double v) const;

private:
  /// The distance d to the polyline refined to the curve from the polyline's foot point p.
  double refine(double u, double v, std::array<double, 2> p, double d) const;

  static constexpr int coarse = 64, fine = 32;
  double a_, b_;
  std::vector<std::array<double, 2>> points_;
  std::vector<double> sagitta_;
};

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
  std::shared_ptr<const CassiniQuarter> cassini_; ///< shape cassini
};

/// Empty if `expression` is a valid muparser expression in x, y, z giving one value;
/// otherwise muparser's message.
std::string check_expression(const std::string& expression);

/// phi_0 = max over cells of tanh(-r_i / (sqrt2 eps)): +1 inside cells, -1 outside. On a
/// periodic domain r_i is the distance to the nearest periodic image of cell i, so that a
/// cell near a periodic side reaches across it, and a point beyond a side (a node of a
/// wrapped patch, compat/Patch.h) takes the value of its image in the domain.
class InitialPhaseField
{
public:
  explicit InitialPhaseField(const Scene& s);
  double operator()(double x, double y, double z = 0) const;
  /// Smallest signed distance over all cells (negative inside some cell).
  double distance(double x, double y, double z = 0) const;

private:
  /// Smallest signed distance from (x, y, z) or any of its images to a cell; only the
  /// shape cells (not the field cells) when `shapes_only`.
  double nearest_image_distance(double x, double y, double z, bool shapes_only) const;
  std::vector<SignedDistance> cells_;
  Domain domain_;
  double epsilon_;
  /// Shifts to a point's images a period either way along each periodic axis, the zero
  /// shift first (fixed by the domain, so built once).
  std::vector<std::array<double, 3>> image_shifts_;
};

} // namespace cellphase::scene
