#include "compat/PeriodicImages.h"

namespace cellphase::compat
{
namespace
{
std::array<double, 3>& stored_periods()
{
  static std::array<double, 3> periods{0, 0, 0};
  return periods;
}
} // namespace

void set_periods(const std::array<double, 3>& periods) { stored_periods() = periods; }

const std::array<double, 3>& periods() { return stored_periods(); }

bool any_periodic()
{
  for (double L : periods())
    if (L > 0)
      return true;
  return false;
}

void move_into(std::span<double> points, const Box& box)
{
  const auto& L = periods();
  for (int a = 0; a < 3; ++a)
  {
    if (L[a] <= 0 || box[a] > box[3 + a])
      continue;
    const double tol = 1e-9 * L[a];
    for (std::size_t i = a; i < points.size(); i += 3)
    {
      double& x = points[i];
      if (x < box[a] - tol && x + L[a] <= box[3 + a] + tol)
        x += L[a];
      else if (x > box[3 + a] + tol && x - L[a] >= box[a] - tol)
        x -= L[a];
    }
  }
}
} // namespace cellphase::compat
