# Manufactured solution for the flow step of forms/flow.py on the unit square: a steady
# divergence-free v (zero on the boundary), p with zero mean, a smooth phi in (-1, 1) for the
# variable viscosity/density (2.56) and a mu for the flux J and the capillary force. The
# source makes (v, p) steady for the continuous equations; one or more steps from the
# interpolated exact state must then stay within the Taylor-Hood discretisation error.
import os
from ufl import SpatialCoordinate, as_vector, cos, div, dx, grad, pi, sin

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "flow.py")).read())

xc = SpatialCoordinate(domain)
X, Y = xc[0], xc[1]
psi = sin(pi * X) ** 2 * sin(pi * Y) ** 2                     # stream function
v_ex = as_vector([psi.dx(1), -psi.dx(0)])                     # div v_ex = 0
p_ex = cos(pi * X) * cos(pi * Y)                              # int p_ex = 0
phi_ex = 0.8 * sin(2 * pi * X) * cos(pi * Y)
mu_ex = cos(pi * X) * sin(2 * pi * Y)

# (2.56) written here (not the production rho_of, eta_of): linear in phi between the phases
rho_e = rho1 * (1 + phi_ex) / 2 + rho0 * (1 - phi_ex) / 2
eta_e = eta1 * (1 + phi_ex) / 2 + eta0 * (1 - phi_ex) / 2
J_e = -(rho1 - rho0) / 2 * mobility * grad(mu_ex)
# Strong form of 5.3 (1) with the terms of 2.8 at the steady state (d_t v = 0):
f_src = (convection * Re * (grad(v_ex) * (rho_e * v_ex + J_e))
         - div(2 * eta_e * sym(grad(v_ex))) + grad(p_ex)
         - rho_e * gravity - force - capillary * mu_ex * grad(phi_ex))
dx8 = dx(metadata={"quadrature_degree": 8})
L_mms = L + inner(f_src, w) * dx8

error_v = inner(v0 - v_ex, v0 - v_ex) * dx8
error_p = (p_h - p_ex) ** 2 * dx8

forms = [a, L_mms, kinetic_energy, divergence_sq, phase_weight, phase_velocity_0,
         phase_velocity_1, pressure_integral, domain_volume, error_v, error_p]
