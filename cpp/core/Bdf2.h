// Variable-step BDF2, shared by the sub-problems that step at second order (phase field, flow):
// the step ratio w = dt_n / dt_{n-1}, the constants the BDF2 forms read
// (forms/cellphase_ufl.py, bdf2_constants) and the extrapolation to t^{n+1}.
#pragma once
#include "compat/Dolfinx.h"
#include <memory>
#include <span>

namespace cellphase
{
/// Whether a sub-problem holds the state before the present one (else its next step is
/// backward Euler, as the first one) and the step that led to the present state.
struct StepHistory
{
  bool have = false;
  double dt_prev = 0;
};

/// u* = (1 + w) u^n - w u^{n-1}: the linear extrapolation to t^{n+1}, w = dt_n / dt_{n-1}.
inline double extrapolate(double now, double before, double w)
{
  return (1 + w) * now - w * before;
}

/// star <- the extrapolation of now and before, entry by entry (same layout).
inline void extrapolate(std::span<const T> now, std::span<const T> before, double w,
                        std::span<T> star)
{
  for (std::size_t k = 0; k < star.size(); ++k)
    star[k] = extrapolate(now[k], before[k], w);
}

/// The constants bdf_c0, bdf_c1, bdf_c2 and bdf_w of the BDF2 forms:
/// d_t u ~ (c0 u^{n+1} - c1 u^n + c2 u^{n-1}) / dt with c0 = (1 + 2w)/(1 + w), c1 = 1 + w,
/// c2 = w^2/(1 + w). They start at backward Euler's values (w = 0).
class Bdf2Constants
{
public:
  Bdf2Constants()
      : c0_(std::make_shared<Constant>(1.0)), c1_(std::make_shared<Constant>(1.0)),
        c2_(std::make_shared<Constant>(0.0)), w_(std::make_shared<Constant>(0.0))
  {
  }
  /// The coefficients of the step with ratio w (0: backward Euler).
  void set(double w)
  {
    w_->value[0] = w;
    c0_->value[0] = (1 + 2 * w) / (1 + w);
    c1_->value[0] = 1 + w;
    c2_->value[0] = w * w / (1 + w);
  }
  double w() const { return w_->value[0]; }
  /// Bind them by name for the forms.
  void add_to(ConstantMap& constants) const
  {
    constants.insert({{"bdf_c0", c0_}, {"bdf_c1", c1_}, {"bdf_c2", c2_}, {"bdf_w", w_}});
  }

private:
  std::shared_ptr<Constant> c0_, c1_, c2_, w_;
};
} // namespace cellphase
