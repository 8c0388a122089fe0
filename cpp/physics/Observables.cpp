#include "physics/Observables.h"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <dolfinx/fem/assembler.h>

namespace cellphase
{
Observables::Observables(const scene::Scene& scene, const PhaseFieldModule& module)
    : scene_(scene), module_(module)
{
  const int dim = scene.domain.dim;
  auto f = observable_forms(dim);
  const auto& fields = module.fields();
  auto mesh = module.space()->mesh();
  CoefficientMap coeffs{{"phi", fields.at("phi")}};
  if (scene::is_helfrich(scene.phase_field.model))
    coeffs["mu"] = fields.at("mu");
  ConstantMap constants{{"eps", std::make_shared<Constant>(scene.numerics.epsilon)},
                        {"H0", std::make_shared<Constant>(scene.phase_field.spontaneous_curvature)}};
  const auto& d = scene.domain;
  for (int i = 0; i < 3; ++i)
  {
    const bool periodic = i < dim && d.is_periodic(i);
    const double period = periodic ? d.upper[i] - d.lower[i] : 0.0;
    const std::string axis = std::to_string(i);
    constants["wave_" + axis] = std::make_shared<Constant>(periodic ? 2 * std::numbers::pi / period : 0.0);
    constants["period_" + axis] = std::make_shared<Constant>(period);
    cut_[i] = std::make_shared<Constant>(d.lower[i]);
    constants["cut_" + axis] = cut_[i];
  }
  auto make = [&](ufcx_form* form) { return compat::create_form(*form, {}, coeffs, constants, mesh); };
  phi_integral_ = make(f.phi_integral);
  volume_ = make(f.cell_volume);
  energy_ch_ = make(f.energy_ch);
  if (coeffs.count("mu"))
    helfrich_ = make(f.helfrich_mu);
  for (int i = 0; i < dim; ++i)
  {
    com_.push_back(make(f.com[i]));
    const bool periodic = d.is_periodic(i);
    com_cos_.push_back(periodic ? make(f.com_cos[i]) : nullptr);
    com_sin_.push_back(periodic ? make(f.com_sin[i]) : nullptr);
    com_open_.push_back(periodic ? make(f.com_open[i]) : nullptr);
  }
  if (dim == 2)
    for (auto* m : f.moments)
      moments_.push_back(make(m));
  auto cells = compat::create_space(f.stretch_space, "z", mesh);
  stretch_sum_ = compat::create_form(*f.stretch_sum, {cells}, coeffs, constants);
  stretch_weight_ = compat::create_form(*f.stretch_weight, {cells}, coeffs, constants);
}

std::pair<double, double> Observables::stretch_range() const
{
  auto cells = stretch_sum_->function_spaces()[0];
  dolfinx::la::Vector<T> sum(cells->dofmap()->index_map, 1), weight(cells->dofmap()->index_map, 1);
  for (auto [b, form] : {std::pair{&sum, stretch_sum_}, std::pair{&weight, stretch_weight_}})
  {
    b->set(0.0);
    dolfinx::fem::assemble_vector(b->mutable_array(), *form);
  }
  // DG0: every cell's integral is complete on its owner, no ghost accumulation needed.
  const auto n = cells->dofmap()->index_map->size_local();
  auto s = sum.array(), w = weight.array();
  double lo = 1e300, hi = -1e300;
  for (std::int32_t i = 0; i < n; ++i)
    if (w[i] > 0)
      lo = std::min(lo, s[i] / w[i]), hi = std::max(hi, s[i] / w[i]);
  MPI_Comm comm = cells->mesh()->comm();
  MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, comm);
  if (hi < lo) // no interface on the mesh
    return {0.0, 0.0};
  return {lo, hi};
}

ObservableValues Observables::evaluate() const
{
  ObservableValues v;
  v.phi_integral = compat::assemble_scalar(*phi_integral_);
  v.volume = compat::assemble_scalar(*volume_);
  v.energy_ch = compat::assemble_scalar(*energy_ch_);
  v.surface = 3 / (2 * std::sqrt(2.0)) * v.energy_ch;
  if (helfrich_)
    v.helfrich = compat::assemble_scalar(*helfrich_) / scene_.numbers.Be;
  v.total_energy = module_.total_energy(v.phi_integral, v.energy_ch, v.helfrich);
  const auto& d = scene_.domain;
  for (std::size_t i = 0; i < com_.size(); ++i)
  {
    if (!com_cos_[i])
    {
      v.center[i] = compat::assemble_scalar(*com_[i]) / v.volume;
      continue;
    }
    // Periodic axis: the circular mean locates the cell, the axis is opened half a period
    // away from it, and the centre is taken on the opened axis, back in [lower, upper).
    const double period = d.upper[i] - d.lower[i];
    auto wrap = [&](double x)
    { return d.lower[i] + std::fmod(std::fmod(x - d.lower[i], period) + period, period); };
    const double angle = std::atan2(compat::assemble_scalar(*com_sin_[i]),
                                    compat::assemble_scalar(*com_cos_[i]));
    cut_[i]->value[0] = wrap(angle / (2 * std::numbers::pi) * period + period / 2);
    v.center[i] = wrap(compat::assemble_scalar(*com_open_[i]) / v.volume);
  }
  const double pi = std::numbers::pi;
  if (!moments_.empty())
  {
    // Central second moments; the major axis is the eigenvector of the larger eigenvalue.
    // About the centre in the mesh's own coordinates (not moved into the domain: a wrapped
    // patch's cell may lie beyond a periodic side).
    const double cx = compat::assemble_scalar(*com_[0]) / v.volume;
    const double cy = compat::assemble_scalar(*com_[1]) / v.volume;
    const double ixx = compat::assemble_scalar(*moments_[0]) / v.volume - cx * cx;
    const double ixy = compat::assemble_scalar(*moments_[1]) / v.volume - cx * cy;
    const double iyy = compat::assemble_scalar(*moments_[2]) / v.volume - cy * cy;
    // A circle has no axis: report 0 instead of the angle of round-off and of the mesh's
    // anisotropy (relative moment differences ~1e-8 for a discretised circle).
    if (std::abs(ixx - iyy) + std::abs(ixy) > 1e-6 * (ixx + iyy))
    {
      v.inclination_deg = 0.5 * std::atan2(2 * ixy, ixx - iyy) * 180 / pi;
      if (v.inclination_deg <= -90 + 1e-6) // -90 and 90 are the same axis
        v.inclination_deg += 180;
    }
  }
  if (scene_.domain.dim == 2)
    v.circularity = 2 * std::sqrt(pi * v.volume) / v.surface; // (5.20)
  else
    v.circularity = std::cbrt(pi) * std::pow(6 * v.volume, 2.0 / 3.0) / v.surface;

  std::tie(v.stretch_min, v.stretch_max) = stretch_range();

  auto phi = module_.fields().at("phi")->x()->array();
  double lo = 1e300, hi = -1e300;
  int not_finite = 0;
  for (double p : phi)
  {
    lo = std::min(lo, p), hi = std::max(hi, p);
    not_finite += !std::isfinite(p);
  }
  MPI_Comm comm = module_.space()->mesh()->comm();
  MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &not_finite, 1, MPI_INT, MPI_SUM, comm);
  v.phi_min = not_finite ? std::nan("") : lo;
  v.phi_max = not_finite ? std::nan("") : hi;
  return v;
}
} // namespace cellphase
