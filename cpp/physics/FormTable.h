// The FFCx-generated kernels of each model, for 2D (triangles) or 3D (tetrahedra).
#pragma once
#include "compat/Dolfinx.h"
#include "scene/Scene.h"
#include <string>

namespace cellphase
{
/// Forms of one phase-field model (see the matching file in forms/). Null where a model
/// has no such form.
struct ModelForms
{
  ufcx_form* a = nullptr;        ///< Taylor-linearised matrix (changes every step)
  ufcx_form* L = nullptr;
  ufcx_form* a_stab = nullptr;   ///< stabilised matrix (constant between remeshes)
  ufcx_form* L_stab = nullptr;
  /// BDF2 (numerics.time_scheme: bdf2): matrix and right-hand side with the state of the
  /// step before ("u1") and the constants bdf_c0, bdf_c1, bdf_c2, bdf_w
  ufcx_form* a_bdf2 = nullptr;
  ufcx_form* L_bdf2 = nullptr;
  ufcx_form* load_a_bdf2 = nullptr; ///< load_a with the extrapolated curvature
  /// a, L, a_bdf2, L_bdf2 with the coupling stabilisation (flow.coupling_stabilisation > 0;
  /// helfrich_l2.py, whose plain forms leave its costly quadrature out; constant
  /// "beta_coupling")
  ufcx_form* a_coupled = nullptr;
  ufcx_form* L_coupled = nullptr;
  ufcx_form* a_bdf2_coupled = nullptr;
  ufcx_form* L_bdf2_coupled = nullptr;
  ufcx_space_fn space = nullptr; ///< space of the state coefficient "u0" of `a`, and of
                                 ///< the advection velocity "v" (models with one)
  bool advected = false;         ///< `a` has the advection term with coefficient "v"
  // Initial mu as the L2 projection of (3.23) (Helfrich models)
  ufcx_form* a_mu = nullptr;
  ufcx_form* L_mu = nullptr;
  /// dE/dphi projected onto P2 (L2 Helfrich flows; coefficients "phi_h", "mu_h")
  ufcx_form* L_dE = nullptr;
  // Integrals of the explicit multipliers
  ufcx_form* dW_integral = nullptr;  ///< (2.27), allen_cahn
  ufcx_form* load_v = nullptr;       ///< unit loads of the volume and area multipliers or
  ufcx_form* load_a = nullptr;       ///< penalties, evaluated at t^{n+1} (Helfrich models)
  /// Explicit interaction source of (7.11) (helfrich_hm1; coefficients u0, w_sum, B_sum)
  ufcx_form* load_int = nullptr;
  /// The same source as a linear form on P2 (coefficients phi_h, w_sum, B_sum)
  ufcx_form* L_int = nullptr;
  /// -gamma grad(w_int) . grad(psi): the source's projection w_int in the mobility term, not
  /// in w (interaction.flow_force: false; coefficients u0, w_int)
  ufcx_form* load_int_mobility = nullptr;
  /// Explicit orientation-field source of (6.15) (helfrich_hm1; coefficients P_polar, u0)
  ufcx_form* load_polar = nullptr;
};

/// Functionals of forms/observables.py on the standalone P2 fields phi and mu.
struct ObservableForms
{
  ufcx_form* phi_integral = nullptr;
  ufcx_form* interaction_energy = nullptr; ///< int B(phi) w_sum, a cell's term of (7.5)
  /// int max(v . n, 0) (1 + phi) ds: what the flow "v" carries out of a cell's own mesh
  ufcx_form* edge_outflow = nullptr;
  ufcx_form* cell_volume = nullptr;
  ufcx_form* energy_ch = nullptr;
  ufcx_form* helfrich_mu = nullptr;
  ufcx_form* volume_weights = nullptr; ///< int q: volume of a P2 function as a dot product
  ufcx_form* area_weights = nullptr;   ///< int kappa(phi) q: first variation of E_CH
  std::array<ufcx_form*, 3> com{nullptr, nullptr, nullptr};
  /// int phi~ cos(k x_i), int phi~ sin(k x_i) (centre along periodic axes; constants wave_i)
  std::array<ufcx_form*, 3> com_cos{nullptr, nullptr, nullptr}, com_sin{nullptr, nullptr, nullptr};
  /// int phi~ x_i with the axis opened at the constant cut_i (x < cut_i counts as x + period_i)
  std::array<ufcx_form*, 3> com_open{nullptr, nullptr, nullptr};
  /// int phi~ x x, int phi~ x y, int phi~ y y (inclination of a 2D cell)
  std::array<ufcx_form*, 3> moments{nullptr, nullptr, nullptr};
  ufcx_space_fn p2_space = nullptr; ///< scalar P2 (coefficient "phi")
  /// Local stretching s of the membrane per DG0 cell: int_band s and the band's measure
  ufcx_form* stretch_sum = nullptr;
  ufcx_form* stretch_weight = nullptr;
  ufcx_space_fn stretch_space = nullptr; ///< DG0 (argument "z" of stretch_sum)
};

/// Forms of forms/flow.py (or a test file that extends it with the same names).
struct FlowForms
{
  ufcx_form* a = nullptr; ///< Taylor-Hood system of one semi-implicit step
  ufcx_form* L = nullptr;
  ufcx_form* a_stokes = nullptr; ///< the same for Re = 0, without the inertial terms
  ufcx_form* L_stokes = nullptr;
  /// a and a_stokes with the viscosity eta_cells given at the nodes (several cells, 7.12)
  ufcx_form* a_cells = nullptr;
  ufcx_form* a_stokes_cells = nullptr;
  /// numerics.time_scheme: bdf2 (Re > 0): BDF2's d_t v, transport velocity v*
  ufcx_form* a_bdf2 = nullptr;
  ufcx_form* L_bdf2 = nullptr;
  ufcx_form* kinetic_energy = nullptr;
  ufcx_form* divergence_sq = nullptr;
  ufcx_form* phase_weight = nullptr;
  std::array<ufcx_form*, 3> phase_velocity{nullptr, nullptr, nullptr};
  ufcx_form* pressure_integral = nullptr;
  ufcx_form* domain_volume = nullptr;
  ufcx_space_fn space = nullptr; ///< spaces of `a`: "v_0" (Taylor-Hood), "v0", "phi", "p_h"
  // Only forms/flow_inextensible.py (mixed v, p, lambda), (3.67)-(3.71):
  bool has_multiplier = false;            ///< `a` has the third sub-space lambda
  ufcx_form* membrane_delta = nullptr;     ///< int delta_phi
  ufcx_form* energy_ch = nullptr;          ///< E_CH of phi_cells (the area of (3.11))
  ufcx_form* lambda_dissipation = nullptr; ///< xi eps^2 int phi^2 |grad lambda|^2, (3.76)
  ufcx_form* lambda_membrane = nullptr;    ///< int lambda delta_phi
};

/// forms/concentration.py: one step of the membrane concentration (3.70).
struct ConcentrationForms
{
  ufcx_form* a = nullptr;
  ufcx_form* L = nullptr;
  ufcx_space_fn space = nullptr; ///< "c" (P2, the trial function), "c0", "phi", "v"
};

/// forms/interface_force.py: the projection of sum_i mu_i grad phi_i (7.12).
struct InterfaceForceForms
{
  ufcx_form* a = nullptr; ///< vector P2 mass matrix
  ufcx_form* L = nullptr; ///< capillary mu grad phi of one cell (coefficients "phi", "mu")
};

ModelForms model_forms(scene::Model model, int dim);
InterfaceForceForms interface_force_forms(int dim);
ObservableForms observable_forms(int dim);
/// forms/flow.py, or with `inextensible` forms/flow_inextensible.py.
FlowForms flow_forms(int dim, bool inextensible = false);
ConcentrationForms concentration_forms(int dim);

/// forms/<model>.py of a reaction-diffusion model (gtpase: (5.16)-(5.18)): the coupled
/// step of its species and their amounts.
struct ReactionForms
{
  ufcx_form* a = nullptr;
  ufcx_form* L = nullptr;
  ufcx_space_fn space = nullptr; ///< "u0" (the species), "phi", "phi_old", "v"
  ufcx_form* membrane_amount = nullptr;      ///< int delta z (the transport weight)
  ufcx_form* bulk_amount = nullptr;          ///< int phib z
  ufcx_form* membrane_amount_cell = nullptr; ///< int |grad phi~| z
  ufcx_form* bulk_amount_cell = nullptr;     ///< int phi~ z
};
ReactionForms reaction_forms(const std::string& model, int dim);

/// forms/polar_gel.py: the orientation field of an active polar gel (6.16)-(6.17).
struct PolarGelForms
{
  ufcx_form* a = nullptr;       ///< the step of P, with P#^{n+1} eliminated (vector P2)
  ufcx_form* L = nullptr;
  ufcx_form* L_sharp = nullptr; ///< P# of a given P (with the vector P2 mass matrix)
  ufcx_form* force_L = nullptr; ///< the P terms of the momentum equation (6.13)
  ufcx_form* energy = nullptr;  ///< (6.4)
  ufcx_form* dissipation = nullptr; ///< (1/kappa) int |P#|^2 of (6.10)
  std::array<ufcx_form*, 2> P_cell{nullptr, nullptr}; ///< int phi~ P_i
};
PolarGelForms polar_gel_forms(int dim);
} // namespace cellphase
