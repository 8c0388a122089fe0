# Manufactured solution for the coupled (v, p, lambda) system of forms/flow_inextensible.py
# (Stokes, (3.67)-(3.68)) on the unit square with a fixed, non-circular phase field.
# The source comes from the strong form of (3.67)-(3.68) applied to the exact fields,
# written here independently of the weak form:
#   -div(2 eta D(v)) + grad p - div(lambda delta_phi P_phi) = f      (3.67), Stokes
#   delta_phi P_phi : grad v + xi eps^2 div(phi^2 grad lambda) = g    (3.68)
#   div v = 0
# with delta_phi P_phi = (|grad phi|^2 I - grad phi (x) grad phi) / (2 |grad phi|) of the
# exact phase field, the tanh profile that tests/cpp/test_inextensible.cpp interpolates
# into P2. lambda_ex has zero normal derivative on the box, so the natural condition of
# lambda holds; v_ex vanishes there (no-slip). The weak form sees the P2 interpolant of
# phi instead: an O(h^2) consistency error in delta_phi P_phi, below the P1 rates of p and
# lambda and (by duality) of the L2 rate 3 of v.
import os
from ufl import (Identity, SpatialCoordinate, as_vector, cos, div, dx, grad, inner, outer, pi,
                 sin, sqrt, sym, tanh)

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "flow_inextensible.py")).read())

xc = SpatialCoordinate(domain)
X, Y = xc[0], xc[1]
psi = sin(pi * X) ** 2 * sin(pi * Y) ** 2                     # stream function
v_ex = as_vector([psi.dx(1), -psi.dx(0)])                     # div v_ex = 0, v = 0 on the box
p_ex = cos(pi * X) * cos(pi * Y)                              # int p_ex = 0
lam_ex = 1 + cos(pi * X) * cos(2 * pi * Y)                    # grad lambda . n = 0 on the box

# The phase field of the test: q ~ signed distance to the ellipse 0.36 x 0.24 at (0.5, 0.5)
q_ex = (0.09 - ((X - 0.5) / 1.2) ** 2 - ((Y - 0.5) / 0.8) ** 2) / 0.6
phi_ex = tanh(q_ex / (sqrt(2.0) * eps))
g_ex = grad(phi_ex)
g_ex_norm = sqrt(inner(g_ex, g_ex) + GRAD_FLOOR**2)
delta_P_ex = (inner(g_ex, g_ex) * Identity(DIM) - outer(g_ex, g_ex)) / (2 * g_ex_norm)

# eta is 1 inside and outside in the test (eta(phi) constant): the viscous term needs no
# derivative of the interpolated phase field.
f_momentum = (-div(2 * sym(grad(v_ex))) + grad(p_ex)                        # (3.67)
              - div(lam_ex * delta_P_ex))
g_constraint = (inner(delta_P_ex, grad(v_ex))                              # (3.68)
                + xi * eps**2 * div(phi_ex**2 * grad(lam_ex)))

dx8 = dx(metadata={"quadrature_degree": 8})
L_mms = (inner(f_momentum, w) + g_constraint * r) * dx8

error_v = inner(v0 - v_ex, v0 - v_ex) * dx8
error_p = (p_h - p_ex) ** 2 * dx8
error_lam = (lam_h - lam_ex) ** 2 * dx8

forms = [a, L_mms, kinetic_energy, divergence_sq, phase_weight, phase_velocity_0,
         phase_velocity_1, pressure_integral, domain_volume, membrane_delta, energy_ch,
         lambda_dissipation, lambda_membrane, error_v, error_p, error_lam]
