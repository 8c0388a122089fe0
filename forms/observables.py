# Functionals written to observables.csv every step (section 5.3 and 3.2.2), on the
# standalone P2 fields phi and mu.
from ufl import (Coefficient, FunctionSpace, SpatialCoordinate, dx, grad, inner)

from cellphase_ufl import DIM, P2, QDEG, W, constants, domain, dW

V = FunctionSpace(domain, P2)
phi = Coefficient(V)
mu = Coefficient(V)
eps, H0 = constants("eps", "H0")
x = SpatialCoordinate(domain)
dxq = dx(metadata={"quadrature_degree": QDEG})
phit = (phi + 1) / 2  # (2.14)

phi_integral = phi * dx                                                        # V(phi), (3.10)
cell_volume = phit * dx                                                        # int phi~
energy_ch = (eps / 2 * inner(grad(phi), grad(phi)) + W(phi) / eps) * dxq       # (2.22)
helfrich_mu = mu**2 / (2 * eps) * dx                                           # (3.14) * Be
com = [phit * x[i] * dx for i in range(DIM)]                                   # (5.19)
com_0 = com[0]
com_1 = com[1]
# First variation of E_CH at phi in the direction delta: int kappa delta, (3.24)
delta = Coefficient(V)
area_variation = (eps * inner(grad(phi), grad(delta)) + dW(phi) * delta / eps) * dxq
forms = [area_variation, phi_integral, cell_volume, energy_ch, helfrich_mu, com_0, com_1]
if DIM == 3:
    com_2 = com[2]
    forms.append(com_2)
