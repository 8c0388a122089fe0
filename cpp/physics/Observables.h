// The quantities written to observables.csv (section 5.3): volume, membrane length/area,
// energies, centre of mass (5.19), circularity (5.20).
#pragma once
#include "physics/PhaseFieldModule.h"

namespace cellphase
{
struct ObservableValues
{
  double phi_integral = 0;  ///< int phi, (3.10)
  double volume = 0;        ///< int (phi+1)/2
  double surface = 0;       ///< length (2D) or area (3D): 3/(2 sqrt2) E_CH
  double energy_ch = 0;     ///< (2.22)
  double helfrich = 0;      ///< (3.14), Helfrich models only (0 otherwise)
  double total_energy = 0;  ///< the energy of the model's gradient flow
  /// int phi~ x / int phi~; along a periodic axis the circular mean, in [lower, upper)
  std::array<double, 3> center{0, 0, 0};
  double circularity = 0;   ///< (5.20); sphericity in 3D
  double phi_min = 0, phi_max = 0;
  /// 2D: angle (degrees, in (-90, 90]) of the major axis of the second moments of phi~
  /// against the x axis; 0 for a circle and in 3D.
  double inclination_deg = 0;
  /// Local stretching s = sqrt2 eps |grad phi| / (1 - phi^2) of the membrane (1 for the
  /// equilibrium profile; > 1 stretched, < 1 compressed): the smallest and largest mean
  /// over the band |phi| < 1/2 of one mesh cell.
  double stretch_min = 0, stretch_max = 0;
  // Flow (zero without it), filled by the time loop from the flow module
  double kinetic_energy = 0;     ///< Re/2 int rho(phi) |v|^2, (3.12)/(2.54)
  double total_with_kinetic = 0; ///< kinetic + interface energy, whose law is (2.61)/(2.62)
  std::array<double, 3> cell_velocity{0, 0, 0}; ///< int phi~ v / int phi~
  double tension_mean = 0; ///< mean lambda on the membrane (inextensibility, 3.4.3)
};

class Observables
{
public:
  Observables(const scene::Scene& scene, const PhaseFieldModule& module);
  ObservableValues evaluate() const;

private:
  const scene::Scene& scene_;
  const PhaseFieldModule& module_;
  std::shared_ptr<Form> phi_integral_, volume_, energy_ch_, helfrich_;
  std::vector<std::shared_ptr<Form>> com_, moments_;
  std::shared_ptr<Form> stretch_sum_, stretch_weight_;
  /// per axis: the circular-mean moments on periodic axes (null otherwise)
  std::vector<std::shared_ptr<Form>> com_cos_, com_sin_, com_open_;
  std::array<std::shared_ptr<Constant>, 3> cut_; ///< where each periodic axis is opened
  /// min and max over the cells of int_band s / |band|, cells that meet the band only
  std::pair<double, double> stretch_range() const;
};
} // namespace cellphase
