// A vector given by one formula per component in x, y, z (muparser syntax), e.g. the
// velocity profile of a prescribed wall: ["4*y*(1-y)", "0"].
#pragma once
#include <array>
#include <memory>
#include <string>

namespace cellphase::scene
{
class VectorFormula
{
public:
  /// The first `dim` formulas are used; throws std::invalid_argument naming a formula
  /// that does not parse.
  VectorFormula(const std::array<std::string, 3>& formulas, int dim);
  std::array<double, 3> operator()(double x, double y, double z) const;

private:
  struct Parsers;
  std::shared_ptr<Parsers> p_; // shared: copies evaluate with the same parsers (one thread)
  int dim_;
};
} // namespace cellphase::scene
