#include "scene/Formula.h"
#include <muParser.h>
#include <stdexcept>
#include <vector>

namespace cellphase::scene
{
struct VectorFormula::Parsers
{
  std::array<mu::Parser, 3> parser;
  double x = 0, y = 0, z = 0;
};

VectorFormula::VectorFormula(const std::array<std::string, 3>& formulas, int dim)
    : p_(std::make_shared<Parsers>()), dim_(dim)
{
  for (int c = 0; c < dim; ++c)
  {
    try
    {
      mu::Parser& q = p_->parser[c];
      q.DefineVar("x", &p_->x);
      q.DefineVar("y", &p_->y);
      q.DefineVar("z", &p_->z);
      q.SetExpr(formulas[c]);
      q.Eval(); // parse now, not at the first evaluation
    }
    catch (const mu::Parser::exception_type& e)
    {
      throw std::invalid_argument("cannot parse '" + formulas[c] + "': " + e.GetMsg());
    }
  }
}

std::array<double, 3> VectorFormula::operator()(double x, double y, double z) const
{
  p_->x = x, p_->y = y, p_->z = z;
  std::array<double, 3> v{0, 0, 0};
  for (int c = 0; c < dim_; ++c)
    v[c] = p_->parser[c].Eval();
  return v;
}
} // namespace cellphase::scene
