# Cahn-Hilliard equation (2.25) as a split system for (phi, mu):
#   d_t phi + v . grad phi = div(gamma grad mu),   mu = -eps Lap phi + W'(phi)/eps
# with natural boundary conditions grad mu . n = 0. v is the velocity of the flow step
# (model H, section 2.8), zero without flow; its term is implicit in phi^{n+1}.
# Mobility: gamma, or gamma W(phi^n) (`degenerate` = 1), the gamma(phi) of section 2.8.
# Walls: grad phi . n = cos(theta) (1 - phi^2) / (eps sqrt2), the contact angle of 2.8
# (theta through phi = +1; cos_theta = 0 is the natural condition), explicit in phi^n;
# the weak form of mu gets eps int (grad phi . n) nu ds.
import math

from ufl import (Coefficient, FunctionSpace, TestFunctions, TrialFunctions, ds, dx, grad,
                 inner, split)

from cellphase_ufl import (ADVECTION_DEGREE, QDEG, W, advection, bdf2_constants, constants, dW,
                           ddW, domain, extrapolate, mixed, velocity, own_mesh_advection, own_mesh_outflow)

Wsp = FunctionSpace(domain, mixed(2))
(phi, mu), (psi, nu) = TrialFunctions(Wsp), TestFunctions(Wsp)
u0 = Coefficient(Wsp)  # (phi^n, mu^n)
phi0, mu0 = split(u0)
v = velocity()
own_mesh, = constants("own_mesh")  # 1 on a cell's own mesh (numerics.mesh.cell_meshes: own)
outflow_lhs, outflow_rhs = own_mesh_outflow(phi, psi, v, own_mesh)  # the patch's edge
dt, eps, gamma, S, degenerate, cos_theta = constants("dt", "eps", "gamma", "S", "degenerate",
                                                    "cos_theta")
dxq = dx(metadata={"quadrature_degree": QDEG})
gamma_phi = gamma * (1 - degenerate + degenerate * W(phi0))           # gamma(phi), 2.8
wall = -cos_theta / math.sqrt(2) * (1 - phi0**2) * nu * ds           # contact angle, 2.8

# gamma(phi) makes the mobility term a polynomial of degree 12: QDEG as for W'.
# `now` is the trial part of the time derivative (phi, or c0 phi for BDF2).
def linear_part(now):
    return (now * psi / dt + mu * nu - eps * inner(grad(phi), grad(nu))) * dx \
        + gamma_phi * inner(grad(mu), grad(psi)) * dxq \
        + advection(phi, psi, v) * dx(degree=ADVECTION_DEGREE) + outflow_lhs  # v . grad phi, 2.8


common = linear_part(phi)
# Taylor linearisation of W'(phi) about phi^n (section 5.3)
a = common - ddW(phi0) / eps * phi * nu * dxq
patch = own_mesh_advection(psi, v, own_mesh) * dx(degree=ADVECTION_DEGREE) + outflow_rhs
L = phi0 * psi / dt * dx + patch + (dW(phi0) - ddW(phi0) * phi0) / eps * nu * dxq + wall
# Stabilised: W'(phi^n) + S (phi - phi^n), constant matrix
a_stab = common - S / eps * phi * nu * dx
L_stab = phi0 * psi / dt * dx + patch + (dW(phi0) - S * phi0) / eps * nu * dxq + wall

# BDF2 (numerics.time_scheme: bdf2; cellphase_ufl.bdf2_constants): W'(phi) linearised about
# the extrapolation phi*; the degenerate mobility and the contact angle stay at phi^n (first
# order: BDF2 is second order for the constant mobility and the natural condition only).
u1 = Coefficient(Wsp)  # (phi^{n-1}, mu^{n-1})
phi1, mu1 = split(u1)
bdf_c0, bdf_c1, bdf_c2, bdf_w = bdf2_constants()
phi_x = extrapolate(phi0, phi1, bdf_w)
a_bdf2 = linear_part(bdf_c0 * phi) - ddW(phi_x) / eps * phi * nu * dxq
L_bdf2 = (bdf_c1 * phi0 - bdf_c2 * phi1) * psi / dt * dx + patch \
    + (dW(phi_x) - ddW(phi_x) * phi_x) / eps * nu * dxq + wall

energy = (eps / 2 * inner(grad(phi0), grad(phi0)) + W(phi0) / eps) * dxq

forms = [a, L, a_stab, L_stab, energy, a_bdf2, L_bdf2]
