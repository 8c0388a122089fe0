# Functionals written to observables.csv every step (section 5.3 and 3.2.2), on the
# standalone P2 fields phi and mu.
from ufl import (Coefficient, FunctionSpace, SpatialCoordinate, TestFunction, dx, grad,
                 inner)

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
# Second moments int phi~ x_i x_j of the cell (inclination angle of a 2D cell, in C++)
moment_xx = phit * x[0] * x[0] * dx
moment_xy = phit * x[0] * x[1] * dx
moment_yy = phit * x[1] * x[1] * dx
# Weights w_i such that sum_i w_i delta_i is the volume int delta (3.10) and the first
# variation of E_CH at phi, int kappa delta (3.24), of a P2 function delta.
q = TestFunction(V)
volume_weights = q * dx
area_weights = (eps * inner(grad(phi), grad(q)) + dW(phi) * q / eps) * dxq
forms = [volume_weights, area_weights, phi_integral, cell_volume, energy_ch, helfrich_mu, com_0, com_1,
         moment_xx, moment_xy, moment_yy]
if DIM == 3:
    com_2 = com[2]
    forms.append(com_2)
