#include "physics/FormTable.h"
#include "form_table.h"
#include <stdexcept>
#include <string>

namespace cellphase
{
namespace
{
/// The entry of the generated table (python/form_table.py) for variable `name` of
/// forms/<file>.py compiled for `dim`, or null.
const generated::FormEntry* entry(const std::string& file, int dim, const std::string& name)
{
  for (std::size_t i = 0; i < generated::form_entry_count; ++i)
  {
    const auto& e = generated::form_entries[i];
    if (e.dim == dim && file == e.file && name == e.name)
      return &e;
  }
  return nullptr;
}

/// A form the file may leave out (null then).
ufcx_form* optional(const std::string& file, int dim, const std::string& name)
{
  const auto* e = entry(file, dim, name);
  return e ? e->form : nullptr;
}

/// A form the C++ cannot do without: a missing one is a mismatch of forms/ and cpp/.
ufcx_form* required(const std::string& file, int dim, const std::string& name)
{
  if (auto* f = optional(file, dim, name))
    return f;
  throw std::logic_error("forms/" + file + ".py (" + std::to_string(dim) + "D) has no form '"
                         + name + "' (list it in its `forms`)");
}

ufcx_space_fn space(const std::string& file, int dim, const std::string& form)
{
  required(file, dim, form);
  return entry(file, dim, form)->space;
}

const char* model_file(scene::Model model)
{
  switch (model)
  {
  case scene::Model::allen_cahn:
  case scene::Model::allen_cahn_volume: return "allen_cahn";
  case scene::Model::cahn_hilliard: return "cahn_hilliard";
  case scene::Model::helfrich_lagrange:
  case scene::Model::helfrich_penalty: return "helfrich_l2";
  case scene::Model::helfrich_hm1: return "helfrich_hm1";
  }
  throw std::logic_error("no form file for this model");
}
} // namespace

ModelForms model_forms(scene::Model model, int dim)
{
  const std::string file = model_file(model);
  ModelForms f;
  f.a = required(file, dim, "a");
  f.L = required(file, dim, "L");
  f.a_stab = required(file, dim, "a_stab");
  f.L_stab = required(file, dim, "L_stab");
  f.a_bdf2 = required(file, dim, "a_bdf2");
  f.L_bdf2 = required(file, dim, "L_bdf2");
  f.load_a_bdf2 = optional(file, dim, "load_a_bdf2");
  f.a_coupled = optional(file, dim, "a_coupled");
  f.L_coupled = optional(file, dim, "L_coupled");
  f.a_bdf2_coupled = optional(file, dim, "a_bdf2_coupled");
  f.L_bdf2_coupled = optional(file, dim, "L_bdf2_coupled");
  f.space = space(file, dim, "a");
  // Every model but Allen-Cahn carries the advection term with coefficient "v".
  f.advected = file != "allen_cahn";
  f.a_mu = optional(file, dim, "a_mu");
  f.L_mu = optional(file, dim, "L_mu");
  f.L_dE = optional(file, dim, "L_dE");
  f.load_v = optional(file, dim, "load_v");
  f.load_a = optional(file, dim, "load_a");
  f.load_int = optional(file, dim, "load_int");
  f.L_int = optional(file, dim, "L_int");
  f.load_int_mobility = optional(file, dim, "load_int_mobility");
  f.load_polar = optional(file, dim, "load_polar");
  // (2.27) is the multiplier of allen_cahn_volume only; plain Allen-Cahn has none.
  if (model == scene::Model::allen_cahn || model == scene::Model::allen_cahn_volume)
    f.dW_integral = required(file, dim, "dW_integral");
  return f;
}

ObservableForms observable_forms(int dim)
{
  const std::string file = "observables";
  auto get = [&](const std::string& name) { return required(file, dim, name); };
  ObservableForms f;
  f.phi_integral = get("phi_integral");
  f.interaction_energy = get("interaction_energy");
  f.edge_outflow = get("edge_outflow");
  f.cell_volume = get("cell_volume");
  f.energy_ch = get("energy_ch");
  f.helfrich_mu = get("helfrich_mu");
  f.volume_weights = get("volume_weights");
  f.area_weights = get("area_weights");
  for (int i = 0; i < dim; ++i)
  {
    const std::string axis = std::to_string(i);
    f.com[i] = get("com_" + axis);
    f.com_cos[i] = get("com_cos_" + axis);
    f.com_sin[i] = get("com_sin_" + axis);
    f.com_open[i] = get("com_open_" + axis);
  }
  f.moments = {get("moment_xx"), get("moment_xy"), get("moment_yy")};
  f.p2_space = space(file, dim, "phi_integral");
  f.stretch_sum = get("stretch_sum");
  f.stretch_weight = get("stretch_weight");
  f.stretch_space = space(file, dim, "stretch_sum");
  return f;
}

FlowForms flow_forms(int dim, bool inextensible)
{
  const std::string file = inextensible ? "flow_inextensible" : "flow";
  auto get = [&](const std::string& name) { return required(file, dim, name); };
  FlowForms f;
  f.a = get("a");
  f.L = get("L");
  f.a_stokes = get("a_stokes");
  f.L_stokes = get("L_stokes");
  f.a_cells = get("a_cells");
  f.a_stokes_cells = get("a_stokes_cells");
  f.a_bdf2 = get("a_bdf2");
  f.L_bdf2 = get("L_bdf2");
  f.kinetic_energy = get("kinetic_energy");
  f.divergence_sq = get("divergence_sq");
  f.phase_weight = get("phase_weight");
  for (int i = 0; i < dim; ++i)
    f.phase_velocity[i] = get("phase_velocity_" + std::to_string(i));
  f.pressure_integral = get("pressure_integral");
  f.domain_volume = get("domain_volume");
  f.space = space(file, dim, "a");
  if (inextensible)
  {
    f.has_multiplier = true;
    f.membrane_delta = get("membrane_delta");
    f.energy_ch = get("energy_ch");
    f.lambda_dissipation = get("lambda_dissipation");
    f.lambda_membrane = get("lambda_membrane");
  }
  return f;
}

ConcentrationForms concentration_forms(int dim)
{
  return {required("concentration", dim, "a"), required("concentration", dim, "L"),
          space("concentration", dim, "a")};
}

ReactionForms reaction_forms(const std::string& model, int dim)
{
  const std::string& file = model;
  auto get = [&](const std::string& name) { return required(file, dim, name); };
  return {get("a"), get("L"), space(file, dim, "a"), get("membrane_amount"), get("bulk_amount"),
          get("membrane_amount_cell"), get("bulk_amount_cell")};
}

PolarGelForms polar_gel_forms(int dim)
{
  auto get = [&](const std::string& name) { return required("polar_gel", dim, name); };
  return {get("a"),       get("L"),      get("L_sharp"),     get("force_L"),
          get("energy"),  get("dissipation"), {get("P_cell_0"), get("P_cell_1")}};
}

InterfaceForceForms interface_force_forms(int dim)
{
  return {required("interface_force", dim, "a"), required("interface_force", dim, "L")};
}
} // namespace cellphase
