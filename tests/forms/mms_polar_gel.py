# Manufactured solution for the orientation-field step of forms/polar_gel.py (6.16)-(6.17)
# on the unit square: P = (0.8 cos(pi x) cos(pi y), 0.6 cos(2 pi x) cos(pi y)) meets the
# natural condition grad P . n = 0; phi and v are given smooth fields (v divergence-free).
# P# is (6.17) of the exact P, written from the thesis with UFL's derivatives, and a source
# in (6.16) makes the exact state steady; one step from it must then reproduce it up to the
# discretisation error. Independent of the production form: only its a, L (the step of P
# with P# eliminated) and L_sharp (P# of a P) are used; P#^{n+1} is the projection of
# (6.17) of the computed P, as the program makes it after the step.
import os
from ufl import (SpatialCoordinate, TrialFunction, as_vector, cos, div, dot, dx, grad, inner,
                 pi, replace, sin)

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "polar_gel.py")).read())

xc = SpatialCoordinate(domain)
x_, y_ = xc[0], xc[1]
P_ex = as_vector([0.8 * cos(pi * x_) * cos(pi * y_), 0.6 * cos(2 * pi * x_) * cos(pi * y_)])
phi_ex = 0.9 * cos(pi * x_) * cos(pi * y_)
v_ex = as_vector([sin(pi * x_) * cos(pi * y_), -cos(pi * x_) * sin(pi * y_)]) / 2
# (6.17)
Ps_ex = (-div(grad(P_ex)) + c1 * inner(P_ex, P_ex) * P_ex - c1 * phi_ex * P_ex
         + beta * grad(phi_ex)) / Pa
# (6.16) with d_t P = 0: the source is the transport and relaxation of the exact state.
Gv = grad(v_ex)
Om = (Gv.T - Gv) / 2
Dm = (Gv + Gv.T) / 2
f_P = dot(grad(P_ex), v_ex) + dot(Om, P_ex) - xi * dot(Dm, P_ex) + Ps_ex / kappa
dx8 = dx(metadata={"quadrature_degree": 8})
L_mms = L + inner(f_P, q) * dx8
uh, Psh = Coefficient(Vvec), Coefficient(Vvec)           # P^{n+1} and its P#
mass = inner(TrialFunction(Vvec), q) * dx8
L_sharp_h = replace(L_sharp, {Pi: uh})
error_P = inner(uh - P_ex, uh - P_ex) * dx8
error_Ps = inner(Psh - Ps_ex, Psh - Ps_ex) * dx8
forms = [a, L_mms, mass, L_sharp_h, error_P, error_Ps]
