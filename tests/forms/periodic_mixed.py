# A Cahn-Hilliard-like linear mixed P2 system for the periodic tests, so that the
# constraint acts on the sub-spaces of a mixed space:
#   u - dt Lap w = f,   w = -Lap u + u,
# manufactured solution u = cos(2 pi x + 0.3) sin(2 pi y + 0.7), periodic in x and y.
from ufl import (Coefficient, FunctionSpace, SpatialCoordinate, TestFunctions, TrialFunctions,
                 cos, div, dx, grad, inner, pi, sin, split)

from cellphase_ufl import constants, domain, mixed

Wsp = FunctionSpace(domain, mixed(2))
(u, w), (v, q) = TrialFunctions(Wsp), TestFunctions(Wsp)
(dt,) = constants("dt")
dx8 = dx(metadata={"quadrature_degree": 8})
xc = SpatialCoordinate(domain)
u_ex = cos(2 * pi * xc[0] + 0.3) * sin(2 * pi * xc[1] + 0.7)
w_ex = -div(grad(u_ex)) + u_ex

a = (u * v + dt * inner(grad(w), grad(v)) + w * q - inner(grad(u), grad(q)) - u * q) * dx
L = (u_ex - dt * div(grad(w_ex))) * v * dx8
uh = Coefficient(Wsp)
uh_u, uh_w = split(uh)
error_u = (uh_u - u_ex)**2 * dx8
error_w = (uh_w - w_ex)**2 * dx8
forms = [a, L, error_u, error_w]
