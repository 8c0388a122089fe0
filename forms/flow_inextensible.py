# Locally inextensible membrane (Aland et al.), section 3.4.3: the flow step of forms/flow.py
# with a local multiplier lambda solved together with v and p in one system,
#   momentum (3.67):  ... = ... + div(delta_phi P_phi lambda)
#   constraint (3.68): xi eps^2 div(phi^2 grad lambda) + delta_phi P_phi : grad v
#                        = xi2 (c - 1)/c delta_phi                 (3.71), concentration variant
#                        + area_source delta_phi                   global area, (3.69)
# with delta_phi = |grad phi|/2 and P_phi = I - grad phi (x) grad phi / |grad phi|^2.
# phi here is phi_cells = max_i phi_i, the union of the cells (7.14)-(7.16).
#
# Weak form (test w, q, r; delta_phi = 0 on the boundary, natural condition for lambda):
#   momentum:   ... + (lambda delta_phi P_phi, grad w) = ...
#   constraint: (delta_phi P_phi : grad v, r) - xi eps^2 (phi^2 grad lambda, grad r) = (rhs, r)
# Testing with (v, lambda) shows the dissipation -xi eps^2 |phi grad lambda|^2 of (3.76).
# r = 1 gives int delta_phi P_phi : grad v = int rhs: the rate of change of the membrane
# area; the global constant of lambda (lambda_global of (3.69)) is the multiplier of this row.
import os

import cellphase_ufl

exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "flow.py")).read())

from ufl import Identity, outer, sqrt  # noqa: E402

from cellphase_ufl import W  # noqa: E402

THL = FunctionSpace(domain, MixedElement([P2v, P1, P1]))   # v, p, lambda
(v, p, lam), (w, q, r) = TrialFunctions(THL), TestFunctions(THL)
phi_cells = Coefficient(Vphi)   # union of the cells' phase fields, (7.14)
conc = Coefficient(Vphi)        # membrane concentration c of (3.70); 1 without the variant
lam_h = Coefficient(Q)          # lambda after a step (observables)
eps, xi, xi2, area_source = constants("eps", "xi", "xi2", "area_source")

# |grad phi| is regularised where phi is flat (far from the membrane, delta_phi P_phi -> 0
# there either way: its numerator is quadratic in grad phi).
GRAD_FLOOR = 1e-10
g = grad(phi_cells)
g_norm = sqrt(inner(g, g) + GRAD_FLOOR**2)
delta = g_norm / 2                                                     # delta_phi, 3.4.3
delta_P = (inner(g, g) * Identity(DIM) - outer(g, g)) / (2 * g_norm)   # delta_phi P_phi
# (c - 1)/c of (3.71); c is kept away from 0 (it is 1 on an unstretched membrane)
C_FLOOR = 0.05
stretch_penalty = (conc - 1) / max_value(conc, C_FLOOR)

membrane_a = (lam * inner(delta_P, grad(w))                          # div(delta P lambda), (3.67)
              + inner(delta_P, grad(v)) * r                          # delta P : grad v, (3.68)
              - xi * eps**2 * phi_cells**2 * inner(grad(lam), grad(r))) * dxq  # xi eps^2 div(phi^2 grad lambda)
membrane_L = (xi2 * stretch_penalty + area_source) * delta * r * dxq  # (3.71), (3.69)
a = momentum_a(v, p, w, q) + membrane_a
L = momentum_L(w) + membrane_L
a_stokes = momentum_a(v, p, w, q, inertia=False) + membrane_a   # Re = 0
a_cells = momentum_a(v, p, w, q, eta=eta_cells) + membrane_a      # the cells' viscosities (7.12)
a_stokes_cells = momentum_a(v, p, w, q, inertia=False, eta=eta_cells) + membrane_a
L_stokes = momentum_L(w, inertia=False) + membrane_L
a_bdf2 = momentum_a(v, p, w, q, bdf2=True) + membrane_a          # numerics.time_scheme: bdf2
L_bdf2 = momentum_L(w, bdf2=True) + membrane_L

# Observables
membrane_delta = delta * dxq                                            # int delta_phi ~ |Gamma|
energy_ch = (eps / 2 * inner(grad(phi_cells), grad(phi_cells))         # E_CH (2.22), the
             + W(phi_cells) / eps) * dxq                                # area of (3.11)
lambda_dissipation = xi * eps**2 * phi_cells**2 * inner(grad(lam_h), grad(lam_h)) * dxq  # (3.76)
lambda_membrane = lam_h * delta * dxq                                  # int lambda delta_phi
forms = [a, L, a_stokes, L_stokes, kinetic_energy, divergence_sq, phase_weight, phase_velocity_0,
         phase_velocity_1, pressure_integral, domain_volume, membrane_delta, energy_ch,
         lambda_dissipation, lambda_membrane, a_cells, a_stokes_cells, a_bdf2, L_bdf2]
if DIM == 3:
    phase_velocity_2 = phase_velocity[2]
    forms.append(phase_velocity_2)
