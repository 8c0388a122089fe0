#include "physics/FormTable.h"
#include "allen_cahn_2d.h"
#include "allen_cahn_3d.h"
#include "cahn_hilliard_2d.h"
#include "cahn_hilliard_3d.h"
#include "flow_2d.h"
#include "flow_3d.h"
#include "flow_inextensible_2d.h"
#include "flow_inextensible_3d.h"
#include "concentration_2d.h"
#include "concentration_3d.h"
#include "interface_force_2d.h"
#include "interface_force_3d.h"
#include "helfrich_hm1_2d.h"
#include "helfrich_hm1_3d.h"
#include "helfrich_l2_2d.h"
#include "helfrich_l2_3d.h"
#include "observables_2d.h"
#include "observables_3d.h"

namespace cellphase
{
// FFCx names every symbol form_<file>_<variable>; these macros pick the 2D or 3D file.
#define CELLPHASE_SYSTEM(F, D)                                                                  \
  f.a = form_##F##_##D##_a;                                                                     \
  f.L = form_##F##_##D##_L;                                                                     \
  f.a_stab = form_##F##_##D##_a_stab;                                                           \
  f.L_stab = form_##F##_##D##_L_stab;                                                           \
  f.space = functionspace_form_##F##_##D##_a;

#define CELLPHASE_MU_PROJECTION(F, D)                                                           \
  f.a_mu = form_##F##_##D##_a_mu;                                                               \
  f.L_mu = form_##F##_##D##_L_mu;

#define CELLPHASE_MODEL_TABLE(D)                                                                \
  switch (model)                                                                                \
  {                                                                                             \
  case scene::Model::allen_cahn:                                                                \
  case scene::Model::allen_cahn_volume:                                                         \
    CELLPHASE_SYSTEM(allen_cahn, D)                                                             \
    f.dW_integral = form_allen_cahn_##D##_dW_integral;                                          \
    break;                                                                                      \
  case scene::Model::cahn_hilliard:                                                             \
    CELLPHASE_SYSTEM(cahn_hilliard, D)                                                          \
    f.advected = true;                                                                          \
    break;                                                                                      \
  case scene::Model::helfrich_lagrange:                                                         \
  case scene::Model::helfrich_penalty:                                                          \
    CELLPHASE_SYSTEM(helfrich_l2, D)                                                            \
    CELLPHASE_MU_PROJECTION(helfrich_l2, D)                                                     \
    f.load_v = form_helfrich_l2_##D##_load_v;                                                   \
    f.load_a = form_helfrich_l2_##D##_load_a;                                                   \
    f.L_dE = form_helfrich_l2_##D##_L_dE;                                                       \
    f.advected = true;                                                                          \
    break;                                                                                      \
  case scene::Model::helfrich_hm1:                                                              \
    CELLPHASE_SYSTEM(helfrich_hm1, D)                                                           \
    f.load_a = form_helfrich_hm1_##D##_load_a;                                                  \
    f.load_int = form_helfrich_hm1_##D##_load_int;                                              \
    CELLPHASE_MU_PROJECTION(helfrich_hm1, D)                                                    \
    f.advected = true;                                                                          \
    break;                                                                                      \
  }

ModelForms model_forms(scene::Model model, int dim)
{
  ModelForms f;
  if (dim == 2)
  {
    CELLPHASE_MODEL_TABLE(2d)
  }
  else
  {
    CELLPHASE_MODEL_TABLE(3d)
  }
  return f;
}

ObservableForms observable_forms(int dim)
{
  ObservableForms f;
#define CELLPHASE_OBSERVABLES(D)                                                                \
  f.phi_integral = form_observables_##D##_phi_integral;                                         \
  f.interaction_energy = form_observables_##D##_interaction_energy;                             \
  f.cell_volume = form_observables_##D##_cell_volume;                                           \
  f.energy_ch = form_observables_##D##_energy_ch;                                               \
  f.helfrich_mu = form_observables_##D##_helfrich_mu;                                           \
  f.volume_weights = form_observables_##D##_volume_weights;                                     \
  f.area_weights = form_observables_##D##_area_weights;                                         \
  f.com[0] = form_observables_##D##_com_0;                                                      \
  f.com[1] = form_observables_##D##_com_1;                                                      \
  f.com_cos[0] = form_observables_##D##_com_cos_0;                                              \
  f.com_cos[1] = form_observables_##D##_com_cos_1;                                              \
  f.com_sin[0] = form_observables_##D##_com_sin_0;                                              \
  f.com_sin[1] = form_observables_##D##_com_sin_1;                                              \
  f.com_open[0] = form_observables_##D##_com_open_0;                                            \
  f.com_open[1] = form_observables_##D##_com_open_1;                                            \
  f.moments = {form_observables_##D##_moment_xx, form_observables_##D##_moment_xy,              \
               form_observables_##D##_moment_yy};                                               \
  f.p2_space = functionspace_form_observables_##D##_phi_integral;                               \
  f.stretch_sum = form_observables_##D##_stretch_sum;                                           \
  f.stretch_weight = form_observables_##D##_stretch_weight;                                     \
  f.stretch_space = functionspace_form_observables_##D##_stretch_sum;
  if (dim == 2)
  {
    CELLPHASE_OBSERVABLES(2d)
  }
  else
  {
    CELLPHASE_OBSERVABLES(3d)
    f.com[2] = form_observables_3d_com_2;
    f.com_cos[2] = form_observables_3d_com_cos_2;
    f.com_sin[2] = form_observables_3d_com_sin_2;
    f.com_open[2] = form_observables_3d_com_open_2;
  }
  return f;
}

FlowForms flow_forms(int dim, bool inextensible)
{
  FlowForms f;
#define CELLPHASE_FLOW(F, D)                                                                    \
  f.a = form_##F##_##D##_a;                                                                     \
  f.L = form_##F##_##D##_L;                                                                     \
  f.a_stokes = form_##F##_##D##_a_stokes;                                                       \
  f.L_stokes = form_##F##_##D##_L_stokes;                                                       \
  f.kinetic_energy = form_##F##_##D##_kinetic_energy;                                           \
  f.divergence_sq = form_##F##_##D##_divergence_sq;                                             \
  f.phase_weight = form_##F##_##D##_phase_weight;                                               \
  f.phase_velocity[0] = form_##F##_##D##_phase_velocity_0;                                      \
  f.phase_velocity[1] = form_##F##_##D##_phase_velocity_1;                                      \
  f.pressure_integral = form_##F##_##D##_pressure_integral;                                     \
  f.domain_volume = form_##F##_##D##_domain_volume;                                             \
  f.space = functionspace_form_##F##_##D##_a;
#define CELLPHASE_MULTIPLIER(D)                                                                 \
  f.has_multiplier = true;                                                                      \
  f.membrane_delta = form_flow_inextensible_##D##_membrane_delta;                               \
  f.energy_ch = form_flow_inextensible_##D##_energy_ch;                                         \
  f.lambda_dissipation = form_flow_inextensible_##D##_lambda_dissipation;                       \
  f.lambda_membrane = form_flow_inextensible_##D##_lambda_membrane;
  if (dim == 2 && !inextensible)
  {
    CELLPHASE_FLOW(flow, 2d)
  }
  else if (dim == 2)
  {
    CELLPHASE_FLOW(flow_inextensible, 2d)
    CELLPHASE_MULTIPLIER(2d)
  }
  else if (!inextensible)
  {
    CELLPHASE_FLOW(flow, 3d)
    f.phase_velocity[2] = form_flow_3d_phase_velocity_2;
  }
  else
  {
    CELLPHASE_FLOW(flow_inextensible, 3d)
    CELLPHASE_MULTIPLIER(3d)
    f.phase_velocity[2] = form_flow_inextensible_3d_phase_velocity_2;
  }
  return f;
}

ConcentrationForms concentration_forms(int dim)
{
  ConcentrationForms f;
  if (dim == 2)
  {
    f.a = form_concentration_2d_a;
    f.L = form_concentration_2d_L;
    f.space = functionspace_form_concentration_2d_a;
  }
  else
  {
    f.a = form_concentration_3d_a;
    f.L = form_concentration_3d_L;
    f.space = functionspace_form_concentration_3d_a;
  }
  return f;
}

InterfaceForceForms interface_force_forms(int dim)
{
  if (dim == 2)
    return {form_interface_force_2d_a, form_interface_force_2d_L};
  return {form_interface_force_3d_a, form_interface_force_3d_L};
}
} // namespace cellphase
