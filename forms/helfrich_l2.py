# L2 gradient flow of the diffuse Helfrich energy with volume and area constraints,
# (3.26)-(3.27) with Lagrange multipliers or (3.31)-(3.32) with penalties:
#   d_t phi = -gamma/Be ( Lap mu - W0''(phi) mu / eps^2 + lam_v + lam_a kappa^n ),   (3.27)
#             - gamma sigma kappa^n                       (surface tension 1/Ca, (3.83)-(3.84))
#   mu      = eps Lap phi - W0'(phi)/eps,                                          (3.23)
# boundary conditions phi = -1 (or natural), grad mu . n = 0 (section 3.4.1).
# lam_v, lam_a are computed in C++ from the unit loads below.
from ufl import (Coefficient, FunctionSpace, TestFunction, TestFunctions, TrialFunction,
                 TrialFunctions, dx, grad, inner, split)

from cellphase_ufl import (ADVECTION_DEGREE, P2, QDEG, advection, bdf2_constants, constants,
                           dddW0, ddW0, domain, dW0, helfrich_time_schemes, kappa_of, mixed,
                           velocity, own_mesh_advection, own_mesh_outflow)

Wsp = FunctionSpace(domain, mixed(2))
(phi, mu), (psi_test, nu) = TrialFunctions(Wsp), TestFunctions(Wsp)
u0 = Coefficient(Wsp)  # (phi^n, mu^n)
phi0, mu0 = split(u0)
dt, eps, gamma, Be, H0, S, lam_v, lam_a, sigma, row_psi = constants(
    "dt", "eps", "gamma", "Be", "H0", "S", "lam_v", "lam_a", "sigma", "row_psi")
# Every row of the phi equation is scaled by row_psi: 1 for Taylor; -eps/g for the
# stabilised scheme, whose psi-mu block -g (K + S/eps^2 M) then becomes eps (K + S/eps^2 M),
# the transpose of the nu-phi block: the matrix is symmetric (without flow) and an LDL^T
# factorisation with half the entries of LU serves it. The solution is unchanged.
psi = row_psi * psi_test
dxq = dx(metadata={"quadrature_degree": QDEG})
g = gamma / Be
kappa0 = kappa_of(phi0, mu0, H0)
v = velocity()  # flow velocity (zero without flow): the material derivative (3.41)
own_mesh, = constants("own_mesh")  # 1 on a cell's own mesh (numerics.mesh.cell_meshes: own)
outflow_lhs, outflow_rhs = own_mesh_outflow(phi, psi, v, own_mesh)  # the patch's edge

# Linear part shared by all time discretisations (Lap mu integrated by parts); `now` is the
# trial part of the time derivative (phi, or c0 phi for BDF2).
def linear_part(now):
    return (now * psi / dt - g * inner(grad(mu), grad(psi))
            + mu * nu + eps * inner(grad(phi), grad(nu))) * dx \
        + advection(phi, psi, v) * dx(degree=ADVECTION_DEGREE) \
        + outflow_lhs  # v . grad phi of (3.61) / (3.83)


# `before`: the known part of the time derivative; kappa: the explicit curvature.
def rhs_part(before, kappa):
    return before * psi / dt * dx \
        - (g * (lam_v + lam_a * kappa) + gamma * sigma * kappa) * psi * dxq \
        + own_mesh_advection(psi, v, own_mesh) * dx(degree=ADVECTION_DEGREE) + outflow_rhs


# Taylor linearisation (section 5.3) about (phi_l, mu_l):
#   W0''(phi) mu ~ W0''(phi_l) mu + W0'''(phi_l) mu_l (phi - phi_l)
#   W0'(phi)     ~ W0'(phi_l) + W0''(phi_l)(phi - phi_l)
def taylor(phi_l, mu_l):
    lhs = (- g / eps**2 * (ddW0(phi_l, eps, H0) * mu + dddW0(phi_l, eps, H0) * mu_l * phi) * psi
           + ddW0(phi_l, eps, H0) / eps * phi * nu) * dxq
    rhs = (- g / eps**2 * dddW0(phi_l, eps, H0) * mu_l * phi_l * psi
           - (dW0(phi_l, eps, H0) - ddW0(phi_l, eps, H0) * phi_l) / eps * nu) * dxq
    return lhs, rhs


# Backward Euler linearised about phi^n (the thesis' scheme) and BDF2
# (numerics.time_scheme: bdf2; cellphase_ufl.bdf2_constants) linearised about the
# extrapolation (phi*, mu*), whose curvature kappa* also drives the multipliers' loads.
u1 = Coefficient(Wsp)  # (phi^{n-1}, mu^{n-1})
phi1, mu1 = split(u1)
bdf_c0, bdf_c1, bdf_c2, bdf_w = bdf2_constants()
(a, L), (a_bdf2, L_bdf2), kappa_x = helfrich_time_schemes(
    linear_part, rhs_part, taylor, phi, (phi0, mu0), (phi1, mu1),
    (bdf_c0, bdf_c1, bdf_c2, bdf_w), H0)
common = linear_part(phi)  # the stabilised variant's linear part
rhs_common = rhs_part(phi0, kappa0)

# Coupling stabilisation (flow.coupling_stabilisation = beta), as in helfrich_hm1.py: the flow
# of the split saw the force (dE/dphi)^n grad phi^n (5.9), and this explicit bending force
# limits dt to about eta h^3 Be (eps 0.021 of Table 5.2: dt = 7e-4 grows a grid-scale mode,
# 3.5e-4 runs). An extra relaxation on the step's change of the bending part
# B = (Lap mu - W0''(phi) mu / eps^2) / Be of dE/dphi,
#   d_t phi + v . grad phi = -gamma dE/dphi^{n+1} - beta (B^{n+1} - B^n),
# damps that mode: it is O(dt), zero at a steady state, and zero for beta = 0. B^{n+1} is
# linearised about (phi^n, mu^n) (exact there, so the two parts cancel at phi^{n+1} = phi^n).
# The plain forms (a, L) stay without it: the *_coupled variants are assembled only when
# beta > 0 (its degree-7 quadrature would add 40 % to the phase field's assembly).
beta_coupling, = constants("beta_coupling")
dx_coupling = dx(metadata={"quadrature_degree": 7})


def bending_part(phi_, mu_):
    """Be B tested with psi (Lap mu by parts), the part of the row that the mobility term g
    carries, linearised about (phi^n, mu^n); the linearisation's constant part cancels
    between the two sides, so bending_part(phi0, mu0) is the right-hand side."""
    return (-inner(grad(mu_), grad(psi))
            - (ddW0(phi0, eps, H0) * mu_ + dddW0(phi0, eps, H0) * mu0 * phi_) * psi / eps**2)


coupling_lhs = beta_coupling / Be * bending_part(phi, mu) * dx_coupling
coupling_rhs = beta_coupling / Be * bending_part(phi0, mu0) * dx_coupling
a_coupled, L_coupled = a + coupling_lhs, L + coupling_rhs
a_bdf2_coupled, L_bdf2_coupled = a_bdf2 + coupling_lhs, L_bdf2 + coupling_rhs

# Stabilised: W0''(phi) mu ~ S mu + (W0''(phi^n) - S) mu^n,  W0'(phi) ~ W0'(phi^n) + S(phi - phi^n).
# S = 2 = W0''(-1) makes both exact in the bulk phase; the matrix is constant.
a_stab = common + (- g / eps**2 * S * mu * psi + S / eps * phi * nu) * dx
L_stab = rhs_common + (g / eps**2 * (ddW0(phi0, eps, H0) - S) * mu0 * psi
                       - (dW0(phi0, eps, H0) - S * phi0) / eps * nu) * dxq

# Unit loads of the multipliers: the solution is linear in (lam_v, lam_a), so
# phi^{n+1} = phi_0 + lam_v phi_v + lam_a phi_a, and a 2x2 system gives multipliers that
# hold the constraints at t^{n+1} (3.28)-(3.29) (the explicit treatment violates them,
# section 3.4.1), or penalties p1 (V - V0), p2 (A - A0) evaluated at t^{n+1} (3.32).
load_v = -g * psi * dx
load_a = -g * kappa0 * psi * dxq
load_a_bdf2 = -g * kappa_x * psi * dxq

# Initial mu from phi^0: L2 projection of eps Lap phi - W0'(phi)/eps (3.23)
V = FunctionSpace(domain, P2)
m, q = TrialFunction(V), TestFunction(V)
phi_init = Coefficient(V)
a_mu = m * q * dx
L_mu = (-eps * inner(grad(phi_init), grad(q)) - dW0(phi_init, eps, H0) / eps * q) * dxq

# dE/dphi of (3.84) at the state after a step, for the flow's interface force
# (dE/dphi) grad phi of (3.81) (Navier-Stokes-Helfrich, L2 flow): its L2 projection onto P2
# (mass matrix a_mu), Lap mu integrated by parts with grad mu . n = 0 (section 3.4.1).
phi_h = Coefficient(V)
mu_h = Coefficient(V)
L_dE = ((-inner(grad(mu_h), grad(q)) - ddW0(phi_h, eps, H0) * mu_h * q / eps**2
         + (lam_v + lam_a * kappa_of(phi_h, mu_h, H0)) * q) / Be
        + sigma * kappa_of(phi_h, mu_h, H0) * q) * dxq                   # (1/Ca) kappa, (3.84)

forms = [a, L, a_stab, L_stab, load_v, load_a, a_mu, L_mu, L_dE, a_bdf2, L_bdf2, load_a_bdf2,
         a_coupled, L_coupled, a_bdf2_coupled, L_bdf2_coupled]
