#include "mesh/FieldTransfer.h"
#include "physics/FormTable.h"
#include <cmath>

namespace cellphase
{
std::shared_ptr<Space> create_p2_space(std::shared_ptr<Mesh> mesh, int dim)
{
  return compat::create_space(observable_forms(dim).p2_space, "phi", mesh);
}

std::shared_ptr<Space> create_vector_p2_space(std::shared_ptr<const Mesh> mesh, int dim)
{
  return compat::create_space(flow_forms(dim).space, "v0", mesh);
}

double integral_of(std::shared_ptr<const Function> f)
{
  auto V = f->function_space();
  const int dim = V->mesh()->topology().dim();
  auto form = compat::create_form(*observable_forms(dim).phi_integral, {}, {{"phi", f}}, {},
                                  V->mesh());
  return compat::assemble_scalar(*form);
}

void add_in_interface(std::shared_ptr<Function> phi, double amount)
{
  if (amount == 0) // nothing to add: spare the integral (`amount` is the same on every rank)
    return;
  // The correction shape (1 - phi^2) at the P2 nodes is its own P2 interpolant.
  auto shape = std::make_shared<Function>(phi->function_space());
  {
    auto p = phi->x()->array();
    auto s = shape->x()->mutable_array();
    for (std::size_t i = 0; i < p.size(); ++i)
      s[i] = std::max(0.0, 1 - p[i] * p[i]);
  }
  const double int_shape = integral_of(shape);
  if (int_shape > 0)
  {
    const double c = amount / int_shape;
    auto p = phi->x()->mutable_array();
    auto s = shape->x()->array();
    for (std::size_t i = 0; i < p.size(); ++i)
      p[i] += c * s[i];
  }
}

double mesh_volume(std::shared_ptr<const Space> V)
{
  auto one = std::make_shared<Function>(std::const_pointer_cast<Space>(V));
  one->x()->set(1.0);
  return integral_of(one);
}

FieldMap transfer_fields(const FieldMap& old, std::shared_ptr<Space> V, TransferReport& report)
{
  FieldMap fields;
  for (const auto& [name, f] : old)
  {
    auto g = std::make_shared<Function>(V);
    g->name = name;
    compat::transfer(f, *g);
    fields[name] = g;
  }
  restore_integral(old.at("phi"), fields.at("phi"), report);
  return fields;
}

void restore_integral(std::shared_ptr<const Function> phi_old, std::shared_ptr<Function> phi,
                      TransferReport& report, double shift)
{
  const double int_old = integral_of(phi_old) + shift, int_new = integral_of(phi);
  add_in_interface(phi, int_old - int_new);
  // Relative to the cell volume int (phi+1)/2 = (int phi + |Omega|)/2 on the new mesh.
  const double omega = mesh_volume(phi->function_space());
  const double cell_volume = (int_old + omega) / 2;
  report.volume_change_interpolated = std::abs(int_new - int_old) / 2 / cell_volume;
  report.volume_change_corrected = std::abs(integral_of(phi) - int_old) / 2 / cell_volume;
}
} // namespace cellphase
