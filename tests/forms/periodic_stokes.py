# Taylor-Hood Stokes flow in the unit-square channel, periodic in x, no-slip at y = 0, 1:
#   -nu Lap u + grad p = f,  div u = 0,  f = (1, beta sin(2 pi x + 0.5) sin(pi y)).
# For beta = 0 the solution is the parabola u = (y (1 - y) / (2 nu), 0), p = const, which
# P2 contains, so the discrete velocity equals it to round-off.
from ufl import (Coefficient, FiniteElement, FunctionSpace, MixedElement, SpatialCoordinate,
                 TestFunctions, TrialFunctions, VectorElement, as_vector, div, dx, grad, inner,
                 pi, sin, split)

from cellphase_ufl import cell, constants, domain

Wsp = FunctionSpace(domain, MixedElement([VectorElement("Lagrange", cell, 2),
                                          FiniteElement("Lagrange", cell, 1)]))
(u, p), (v, q) = TrialFunctions(Wsp), TestFunctions(Wsp)
nu, beta = constants("nu", "beta")
xc = SpatialCoordinate(domain)
f = as_vector((1.0, beta * sin(2 * pi * xc[0] + 0.5) * sin(pi * xc[1])))

a = (nu * inner(grad(u), grad(v)) - p * div(v) - q * div(u)) * dx
L = inner(f, v) * dx(metadata={"quadrature_degree": 6})
uh = Coefficient(Wsp)
uh_u, uh_p = split(uh)
u_parabola = as_vector((xc[1] * (1 - xc[1]) / (2 * nu), 0.0))
error_u = inner(uh_u - u_parabola, uh_u - u_parabola) * dx(metadata={"quadrature_degree": 6})
divergence = div(uh_u)**2 * dx
forms = [a, L, error_u, divergence]
