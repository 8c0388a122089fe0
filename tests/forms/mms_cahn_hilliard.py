# Manufactured solution for the split Cahn-Hilliard operator of forms/cahn_hilliard.py:
# phi = cos(pi x) cos(pi y), mu = -eps Lap phi + W'(phi)/eps is made steady by a source.
# The source is written from the thesis, independently of the production forms: the double
# well W = (phi^2 - 1)^2 / 4 of (2.22) differentiated by UFL.
import os
from ufl import SpatialCoordinate, cos, diff, div, dx, grad, pi, variable

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "cahn_hilliard.py")).read())

xc = SpatialCoordinate(domain)
phi_ex = variable(cos(pi * xc[0]) * cos(pi * xc[1]))
W_thesis = (phi_ex**2 - 1) ** 2 / 4                                           # (2.22)
mu_ex = -eps * div(grad(phi_ex)) + diff(W_thesis, phi_ex) / eps
f_phi = -gamma * div(grad(mu_ex))                                             # (2.25)
L_mms = L + f_phi * psi * dx(metadata={"quadrature_degree": 8})
uh = Coefficient(Wsp)
phih, muh = split(uh)
error_phi = (phih - phi_ex)**2 * dx(metadata={"quadrature_degree": 8})
error_mu = (muh - mu_ex)**2 * dx(metadata={"quadrature_degree": 8})
forms = [a, L_mms, error_phi, error_mu]
