# Manufactured solution for the split Helfrich operator of forms/helfrich_l2.py: the
# production forms a, L plus a source that makes phi = cos(pi x) cos(pi y) and
# mu = eps Lap phi - W0'(phi)/eps (3.23) a steady solution (grad . n = 0 on the unit square).
import os
from ufl import SpatialCoordinate, cos, div, dx, grad, pi

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "helfrich_l2.py")).read())

xc = SpatialCoordinate(domain)
phi_ex = cos(pi * xc[0]) * cos(pi * xc[1])
mu_ex = eps * div(grad(phi_ex)) - dW0(phi_ex, eps, H0) / eps
f_phi = g * (div(grad(mu_ex)) - ddW0(phi_ex, eps, H0) * mu_ex / eps**2)   # (3.27) at phi_ex
L_mms = L + f_phi * psi * dx(metadata={"quadrature_degree": 8})
uh = Coefficient(Wsp)
phih, muh = split(uh)
error_phi = (phih - phi_ex)**2 * dx(metadata={"quadrature_degree": 8})
error_mu = (muh - mu_ex)**2 * dx(metadata={"quadrature_degree": 8})
forms = [a, L_mms, error_phi, error_mu]
