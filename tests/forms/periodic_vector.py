# -Lap u + u = f for a P2 vector field (a blocked space, not a mixed one) on the unit
# square, periodic in x and y, for tests/cpp/test_periodic.cpp:
#   u = (cos(2 pi x + 0.3) sin(2 pi y + 0.7), sin(2 pi x + 0.4) cos(4 pi y + 0.1)).
from ufl import (Coefficient, FunctionSpace, SpatialCoordinate, TestFunction, TrialFunction,
                 VectorElement, as_vector, cos, div, dx, grad, inner, pi, sin)

from cellphase_ufl import cell, domain

V = FunctionSpace(domain, VectorElement("Lagrange", cell, 2))
u, v = TrialFunction(V), TestFunction(V)
dx8 = dx(metadata={"quadrature_degree": 8})
xc = SpatialCoordinate(domain)
u_ex = as_vector((cos(2 * pi * xc[0] + 0.3) * sin(2 * pi * xc[1] + 0.7),
                  sin(2 * pi * xc[0] + 0.4) * cos(4 * pi * xc[1] + 0.1)))

a = (inner(grad(u), grad(v)) + inner(u, v)) * dx
L = inner(-div(grad(u_ex)) + u_ex, v) * dx8
uh = Coefficient(V)
error = inner(uh - u_ex, uh - u_ex) * dx8
forms = [a, L, error]
