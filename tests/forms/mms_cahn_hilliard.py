# Manufactured solution for the split Cahn-Hilliard operator of forms/cahn_hilliard.py:
# phi = cos(pi x) cos(pi y), mu = -eps Lap phi + W'(phi)/eps is made steady by a source.
import os
from ufl import SpatialCoordinate, cos, div, dx, grad, pi

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "cahn_hilliard.py")).read())

xc = SpatialCoordinate(domain)
phi_ex = cos(pi * xc[0]) * cos(pi * xc[1])
mu_ex = -eps * div(grad(phi_ex)) + dW(phi_ex) / eps
f_phi = -gamma * div(grad(mu_ex))                                             # (2.25)
L_mms = L + f_phi * psi * dx(metadata={"quadrature_degree": 8})
uh = Coefficient(Wsp)
phih, muh = split(uh)
error_phi = (phih - phi_ex)**2 * dx(metadata={"quadrature_degree": 8})
error_mu = (muh - mu_ex)**2 * dx(metadata={"quadrature_degree": 8})
forms = [a, L_mms, error_phi, error_mu]
