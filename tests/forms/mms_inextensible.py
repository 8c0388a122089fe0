# Manufactured solution for the coupled (v, p, lambda) system of forms/flow_inextensible.py
# (Stokes, (3.67)-(3.68)) on the unit square with a fixed, non-circular phase field.
# The right-hand side is the discrete bilinear form applied to the exact (v, p, lambda):
# the discrete solution is then the Galerkin projection of the exact one, and its errors
# are those of the P2/P1/P1 spaces alone (no consistency error of the strong form, which
# would need second derivatives of the P2 phase field across elements).
import os
from ufl import (SpatialCoordinate, TrialFunction, as_vector, cos, dx, pi, replace, sin)

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "flow_inextensible.py")).read())

xc = SpatialCoordinate(domain)
X, Y = xc[0], xc[1]
psi = sin(pi * X) ** 2 * sin(pi * Y) ** 2                     # stream function
v_ex = as_vector([psi.dx(1), -psi.dx(0)])                     # div v_ex = 0, v = 0 on the box
p_ex = cos(pi * X) * cos(pi * Y)                              # int p_ex = 0
lam_ex = 1 + sin(pi * X) * cos(2 * pi * Y)                    # a tension that varies along
u_ex = as_vector([v_ex[0], v_ex[1], p_ex, lam_ex])            # the membrane
L_mms = replace(a, {TrialFunction(THL): u_ex})

dx8 = dx(metadata={"quadrature_degree": 8})
error_v = inner(v0 - v_ex, v0 - v_ex) * dx8
error_p = (p_h - p_ex) ** 2 * dx8
error_lam = (lam_h - lam_ex) ** 2 * dx8

forms = [a, L_mms, kinetic_energy, divergence_sq, phase_weight, phase_velocity_0,
         phase_velocity_1, pressure_integral, domain_volume, membrane_delta, energy_ch,
         lambda_dissipation, lambda_membrane, error_v, error_p, error_lam]
