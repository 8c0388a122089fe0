# -Lap u + c u = f with P2 for the periodic tests (tests/cpp/test_periodic.cpp), with two
# manufactured solutions, both periodic in x on the unit square:
#   u_x  = cos(2 pi x + 0.3) exp(y)                periodic in x only (Dirichlet in y), c = 0
#   u_xy = cos(2 pi x + 0.3) sin(2 pi y + 0.7)     periodic in x and y, c = 1 (non-singular)
from ufl import (Coefficient, FunctionSpace, SpatialCoordinate, TestFunction, TrialFunction,
                 cos, div, dx, exp, grad, inner, pi, sin)

from cellphase_ufl import P2, constants, domain

V = FunctionSpace(domain, P2)
u, v = TrialFunction(V), TestFunction(V)
(c,) = constants("c")
dx8 = dx(metadata={"quadrature_degree": 8})
xc = SpatialCoordinate(domain)
u_x = cos(2 * pi * xc[0] + 0.3) * exp(xc[1])
u_xy = cos(2 * pi * xc[0] + 0.3) * sin(2 * pi * xc[1] + 0.7)

a = (inner(grad(u), grad(v)) + c * u * v) * dx
L_x = (-div(grad(u_x)) + c * u_x) * v * dx8
L_xy = (-div(grad(u_xy)) + c * u_xy) * v * dx8
uh = Coefficient(V)
error_x = (uh - u_x)**2 * dx8
error_xy = (uh - u_xy)**2 * dx8
forms = [a, L_x, L_xy, error_x, error_xy]
