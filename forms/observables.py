# Functionals written to observables.csv every step (section 5.3 and 3.2.2), on the
# standalone P2 fields phi and mu.
from ufl import (Coefficient, FiniteElement, FunctionSpace, SpatialCoordinate, TestFunction,
                 conditional, cos, dx, grad, inner, lt, sin, sqrt)

from cellphase_ufl import DIM, P2, QDEG, W, cell, constants, domain, dW

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
# Along a periodic axis of period L a cell may lie across the periodic face. The angle of
# int phi~ exp(i k x), k = 2 pi / L (the circular mean) locates it; the point half a period
# away (`cut`, where phi~ = 0) is where the axis is cut open: x < cut counts as x + L, and
# int phi~ x over the opened axis is the centre as for a cell inside the box.
# (FFCx names constants after their variables, so each gets one)
wave_0, wave_1, wave_2 = constants("wave_0", "wave_1", "wave_2")
cut_0, cut_1, cut_2 = constants("cut_0", "cut_1", "cut_2")
period_0, period_1, period_2 = constants("period_0", "period_1", "period_2")
wave, cut = [wave_0, wave_1, wave_2], [cut_0, cut_1, cut_2]
period = [period_0, period_1, period_2]
com_cos = [phit * cos(wave[i] * x[i]) * dxq for i in range(DIM)]
com_sin = [phit * sin(wave[i] * x[i]) * dxq for i in range(DIM)]
com_open = [phit * conditional(lt(x[i], cut[i]), x[i] + period[i], x[i]) * dx for i in range(DIM)]
com_cos_0, com_cos_1, com_sin_0, com_sin_1 = com_cos[0], com_cos[1], com_sin[0], com_sin[1]
com_open_0, com_open_1 = com_open[0], com_open[1]
# Second moments int phi~ x_i x_j of the cell (inclination angle of a 2D cell, in C++)
moment_xx = phit * x[0] * x[0] * dx
moment_xy = phit * x[0] * x[1] * dx
moment_yy = phit * x[1] * x[1] * dx
# Weights w_i such that sum_i w_i delta_i is the volume int delta (3.10) and the first
# variation of E_CH at phi, int kappa delta (3.24), of a P2 function delta.
q = TestFunction(V)
volume_weights = q * dx
area_weights = (eps * inner(grad(phi), grad(q)) + dW(phi) * q / eps) * dxq
# Local stretching of the membrane, s = sqrt2 eps |grad phi| / (1 - phi^2): 1 for the
# equilibrium profile (2.12) at every phi. A flow that stretches the membrane by a factor s
# compresses the profile across it by 1/s (incompressibility) and so multiplies |grad phi|
# by s; the gradient flows relax it back. Integrated per cell over the band |phi| < 1/2 as
# a DG0 vector, with the band's measure per cell as weight (min/max of the cell means in C++).
z = TestFunction(FunctionSpace(domain, FiniteElement("DG", cell, 0)))
band = conditional(lt(abs(phi), 0.5), 1.0, 0.0)
stretch = sqrt(2.0) * eps * sqrt(inner(grad(phi), grad(phi))) / (1 - phi**2)
stretch_sum = band * stretch * z * dxq
stretch_weight = band * z * dxq
# Interaction energy of one cell with the others, its term of (7.5): int B(phi) w_sum / In
# (w_sum = sum_j w_j, a P2 field; 1/In applied in C++).
from cellphase_ufl import B_of  # noqa: E402
w_sum = Coefficient(FunctionSpace(domain, P2))
interaction_energy = B_of(phi, eps) * w_sum * dxq
# What the flow carries across the edge of a cell's own mesh per unit time: the outflow term
# of cellphase_ufl.own_mesh_outflow tested with psi = 1, int max(v . n, 0) (1 + phi) ds.
from cellphase_ufl import OUTFLOW_DEGREE, leaving, velocity  # noqa: E402
from ufl import ds  # noqa: E402
v = velocity()
edge_outflow = leaving(v, 1.0) * (1 + phi) * ds(degree=OUTFLOW_DEGREE)
forms = [edge_outflow, interaction_energy, com_cos_0, com_cos_1, com_sin_0, com_sin_1, com_open_0, com_open_1, stretch_sum, stretch_weight, volume_weights, area_weights, phi_integral, cell_volume, energy_ch, helfrich_mu, com_0, com_1,
         moment_xx, moment_xy, moment_yy]
if DIM == 3:
    com_2 = com[2]
    com_cos_2, com_sin_2, com_open_2 = com_cos[2], com_sin[2], com_open[2]
    forms += [com_2, com_cos_2, com_sin_2, com_open_2]
