# Manufactured solution for the split Helfrich operator of forms/helfrich_l2.py: the
# production forms a, L plus a source that makes phi = cos(pi x) cos(pi y) and
# mu = eps Lap phi - W0'(phi)/eps (3.23) a steady solution (grad . n = 0 on the unit square).
# The source is written from the thesis' formulas, independently of the production forms:
# W0'(phi) = (phi^2 - 1)(phi + sqrt2 H0 eps) as printed after (3.9), and W0'' by UFL's own
# differentiation of it, in the variation (3.22) Lap mu - W0''(phi) mu / eps^2.
import math
import os
from ufl import SpatialCoordinate, cos, diff, div, dx, grad, pi, variable

import cellphase_ufl
exec(open(os.path.join(os.path.dirname(cellphase_ufl.__file__), "helfrich_l2.py")).read())

xc = SpatialCoordinate(domain)
phi_ex = variable(cos(pi * xc[0]) * cos(pi * xc[1]))
dW0_thesis = (phi_ex**2 - 1) * (phi_ex + math.sqrt(2) * H0 * eps)   # W0', after (3.9)
ddW0_thesis = diff(dW0_thesis, phi_ex)                                # W0''
mu_ex = eps * div(grad(phi_ex)) - dW0_thesis / eps                    # (3.23)
f_phi = g * (div(grad(mu_ex)) - ddW0_thesis * mu_ex / eps**2)         # (3.22) at phi_ex
L_mms = L + f_phi * psi * dx(metadata={"quadrature_degree": 8})
uh = Coefficient(Wsp)
phih, muh = split(uh)
error_phi = (phih - phi_ex)**2 * dx(metadata={"quadrature_degree": 8})
error_mu = (muh - mu_ex)**2 * dx(metadata={"quadrature_degree": 8})
forms = [a, L_mms, error_phi, error_mu]
