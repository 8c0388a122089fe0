# -Lap u + u = f with P2 on the unit cube (tetrahedra), periodic in x, y and z, for
# tests/cpp/test_periodic.cpp: u = cos(2 pi x + 0.3) sin(2 pi y + 0.7) cos(2 pi z + 0.2).
# The test forms are built for 2D; this one fixes 3D before the shared vocabulary loads.
import os

os.environ["CELLPHASE_DIM"] = "3"
from ufl import (Coefficient, FunctionSpace, SpatialCoordinate, TestFunction,  # noqa: E402
                 TrialFunction, cos, div, dx, grad, inner, pi, sin)

from cellphase_ufl import P2, domain  # noqa: E402

V = FunctionSpace(domain, P2)
u, v = TrialFunction(V), TestFunction(V)
dx6 = dx(metadata={"quadrature_degree": 6})
xc = SpatialCoordinate(domain)
u_ex = cos(2 * pi * xc[0] + 0.3) * sin(2 * pi * xc[1] + 0.7) * cos(2 * pi * xc[2] + 0.2)

a = (inner(grad(u), grad(v)) + u * v) * dx
L = (-div(grad(u_ex)) + u_ex) * v * dx6
uh = Coefficient(V)
error = (uh - u_ex)**2 * dx6
forms = [a, L, error]
