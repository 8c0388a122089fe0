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
  std::array<double, 3> center{0, 0, 0};
  double circularity = 0;   ///< (5.20); sphericity in 3D
  double phi_min = 0, phi_max = 0;
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
  std::vector<std::shared_ptr<Form>> com_;
};
} // namespace cellphase
