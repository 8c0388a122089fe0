// Dimensionless numbers from physical units, thesis eqs. (3.12)-(3.17).
#pragma once
#include "scene/Scene.h"

namespace cellphase::scene
{
/// Re = rho V L / eta, Ca = 2 sqrt2 eta V / (3 sigma), Be = 4 sqrt2 eta V L^2 / (3 b_N),
/// Fa = eta V / (alpha L) (5.8), Pa = eta V L / k (6.4), time scale L / V. A number whose inputs are not all given keeps its default.
Numbers derive_numbers(const PhysicalUnits& u);

/// Which of Re, Ca, Be and the time scale the given units determine.
struct DerivedFlags
{
  bool Re = false, Ca = false, Be = false, Fa = false, Pa = false, time_scale = false;
};
DerivedFlags derivable_numbers(const PhysicalUnits& u);
} // namespace cellphase::scene
