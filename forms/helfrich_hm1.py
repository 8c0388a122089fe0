# H^-1 gradient flow of the diffuse Helfrich energy with an area penalty, (3.33)-(3.35):
#   d_t phi = gamma Lap w,                                                          (3.34)
#   w       = 1/Be ( Lap mu - W0''(phi) mu / eps^2 + p2 (A - A0) kappa ) + sigma kappa,
#                                                                           (3.35), (3.87)
#   mu      = eps Lap phi - W0'(phi)/eps,                                           (3.23)
# natural boundary conditions grad w . n = grad mu . n = 0 keep int phi exactly.
# lam_a = p2 (A - A0) is evaluated at t^{n+1} through the unit load below (C++).
# sigma = 1/Ca is the surface tension of (3.78) (0 unless phase_field.surface_tension),
# explicit in kappa like the penalty.
from ufl import (Coefficient, FunctionSpace, TestFunction, TestFunctions, TrialFunction,
                 TrialFunctions, dx, grad, inner, split)

from cellphase_ufl import (ADVECTION_DEGREE, P2, QDEG, advection, bdf2_constants, constants,
                           dddW0, ddW0, domain, dW0, helfrich_time_schemes, kappa_of, mixed,
                           velocity, own_mesh_advection, own_mesh_outflow)

Wsp = FunctionSpace(domain, mixed(3))
(phi, mu, w), (psi, nu, zeta) = TrialFunctions(Wsp), TestFunctions(Wsp)
u0 = Coefficient(Wsp)  # (phi^n, mu^n, w^n)
phi0, mu0, w0 = split(u0)
dt, eps, gamma, Be, H0, S, lam_a, sigma = constants("dt", "eps", "gamma", "Be", "H0", "S",
                                                    "lam_a", "sigma")
dxq = dx(metadata={"quadrature_degree": QDEG})
kappa0 = kappa_of(phi0, mu0, H0)
v = velocity()  # flow velocity (zero without flow): the material derivative (3.41)
own_mesh, = constants("own_mesh")  # 1 on a cell's own mesh (numerics.mesh.cell_meshes: own)
outflow_lhs, outflow_rhs = own_mesh_outflow(phi, psi, v, own_mesh)  # the patch's edge

# Coupling stabilisation (flow.coupling_stabilisation = beta): the flow of the split saw the
# force w^n grad phi^n (3.59), the energy law asks for w^{n+1}; with a small mobility gamma
# the explicit bending force makes the split unstable unless dt ~ eta h^3 Be. An extra
# mobility on the step's change, -div(beta grad(w^{n+1} - w^n)), damps that mode: it keeps
# int phi exactly, is O(dt) (w^{n+1} - w^n = O(dt)), dissipates (beta |grad w^{n+1}|^2 less
# the explicit part, bounded by Young's inequality) and is zero for beta = 0.
beta_coupling, = constants("beta_coupling")
COUPLING_DEGREE = 3  # exact for P2 gradients; a block of its own: beta = 0 adds exact zeros


# Linear part shared by all time discretisations; `now` is the trial part of the time
# derivative (phi, or c0 phi for BDF2).
def linear_part(now):
    return (now * psi / dt + gamma * inner(grad(w), grad(psi))
            + w * zeta + 1 / Be * inner(grad(mu), grad(zeta))
            + mu * nu + eps * inner(grad(phi), grad(nu))) * dx \
        + advection(phi, psi, v) * dx(degree=ADVECTION_DEGREE) + outflow_lhs \
        + beta_coupling * inner(grad(w), grad(psi)) * dx(degree=COUPLING_DEGREE)


# `before`: the known part of the time derivative; kappa: the explicit curvature.
def rhs_part(before, kappa):
    return before * psi / dt * dx + (lam_a / Be + sigma) * kappa * zeta * dxq \
        + own_mesh_advection(psi, v, own_mesh) * dx(degree=ADVECTION_DEGREE) + outflow_rhs \
        + beta_coupling * inner(grad(w0), grad(psi)) * dx(degree=COUPLING_DEGREE)


# Taylor linearisation as in helfrich_l2.py (section 5.3), about (phi_l, mu_l)
def taylor(phi_l, mu_l):
    lhs = (1 / (Be * eps**2) * (ddW0(phi_l, eps, H0) * mu + dddW0(phi_l, eps, H0) * mu_l * phi)
           * zeta + ddW0(phi_l, eps, H0) / eps * phi * nu) * dxq
    rhs = (1 / (Be * eps**2) * dddW0(phi_l, eps, H0) * mu_l * phi_l * zeta
           - (dW0(phi_l, eps, H0) - ddW0(phi_l, eps, H0) * phi_l) / eps * nu) * dxq
    return lhs, rhs


# Backward Euler linearised about phi^n (the thesis' scheme) and BDF2
# (numerics.time_scheme: bdf2; cellphase_ufl.bdf2_constants) linearised about the
# extrapolation (phi*, mu*), whose curvature kappa* also drives the multipliers' loads.
u1 = Coefficient(Wsp)  # (phi^{n-1}, mu^{n-1}, w^{n-1})
phi1, mu1, w1 = split(u1)
bdf_c0, bdf_c1, bdf_c2, bdf_w = bdf2_constants()
(a, L), (a_bdf2, L_bdf2), kappa_x = helfrich_time_schemes(
    linear_part, rhs_part, taylor, phi, (phi0, mu0), (phi1, mu1),
    (bdf_c0, bdf_c1, bdf_c2, bdf_w), H0)
common = linear_part(phi)  # the stabilised variant's linear part
rhs_common = rhs_part(phi0, kappa0)

# Stabilised constant-matrix variant as in helfrich_l2.py
a_stab = common + (1 / (Be * eps**2) * S * mu * zeta + S / eps * phi * nu) * dx
L_stab = rhs_common + (- 1 / (Be * eps**2) * (ddW0(phi0, eps, H0) - S) * mu0 * zeta
                       - (dW0(phi0, eps, H0) - S * phi0) / eps * nu) * dxq

# Unit load of the area penalty: the solution is linear in lam_a, so the penalty can be
# evaluated at t^{n+1} (with E_CH linearised) instead of explicitly; see PhaseFieldModule.
load_a = 1 / Be * kappa0 * zeta * dxq
load_a_bdf2 = 1 / Be * kappa_x * zeta * dxq

# Initial mu from phi^0 (L2 projection of (3.23))
V = FunctionSpace(domain, P2)
m, q = TrialFunction(V), TestFunction(V)
phi_init = Coefficient(V)
a_mu = m * q * dx
L_mu = (-eps * inner(grad(phi_init), grad(q)) - dW0(phi_init, eps, H0) / eps * q) * dxq

# Interaction with the other cells, (7.11) with one interaction number In: an explicit
# source in the equation of w = phi^natural (7.7), from the sums over the other cells
# w_sum = sum_j w_j and B_sum = sum_j B(phi_j) (P2 fields at t^n, cpp/physics/Interaction).
from cellphase_ufl import dB_of, interaction_dw  # noqa: E402
w_sum, B_sum = Coefficient(V), Coefficient(V)
In_inv, r1, r2, a1, a2, a3, dw_reach = constants("In_inv", "r1", "r2", "a1", "a2", "a3",
                                                 "dw_reach")
load_int = In_inv * (dB_of(phi0, eps) * w_sum
                     + interaction_dw(phi0, eps, r1, r2, a1, a2, a3, dw_reach) * B_sum) * zeta * dxq

# The same source as a P2 field (its L2 projection, with a1 phi_h of one's choice): with
# interaction.refresh the module replaces the part of w that load_int made from phi^n by
# the one of phi^{n+1} and the other cells' phi^{n+1} after the step, so that the flow's
# next force (7.12) does not lag the cells' positions by a step.
phi_h = Coefficient(V)
L_int = In_inv * (dB_of(phi_h, eps) * w_sum
                  + interaction_dw(phi_h, eps, r1, r2, a1, a2, a3, dw_reach) * B_sum) * q * dxq

# interaction.flow_force: false. Summed over the cells, the interaction's part of the flow's
# force (7.12) is a gradient, (1/In) grad sum_{i != j} B(phi_i) w_j, which the pressure
# absorbs. The module then keeps the interaction out of w (which the flow reads) and gives
# it to the mobility term instead: gamma Lap(w + w_int) with w_int = P(source), the L2
# projection of L_int at phi^n. In exact arithmetic the same step as with load_int.
w_int = Coefficient(V)
load_int_mobility = -gamma * inner(grad(w_int), grad(psi)) * dx

forms = [a, L, a_stab, L_stab, load_a, a_mu, L_mu, load_int, L_int, load_int_mobility, a_bdf2,
         L_bdf2, load_a_bdf2]

# The orientation field of an active polar gel in phi# (6.15): dE_P/dphi of (6.4),
# (1/Pa) (-(c1/2) |P|^2 - beta div P) with P = P^{n+1} (section 6.3, step 3; (6.15) prints
# +c1/2, but the derivative of -(c1/2) |P|^2 phi in (6.4) and the scheme of step 3 have -).
# An explicit source in the equation of w = phi#, like load_int.
from ufl import div  # noqa: E402
from cellphase_ufl import P2vec  # noqa: E402
P_polar = Coefficient(FunctionSpace(domain, P2vec))
Pa_inv, polar_c1, polar_beta = constants("Pa_inv", "polar_c1", "polar_beta")
load_polar = Pa_inv * (-polar_c1 / 2 * inner(P_polar, P_polar) - polar_beta * div(P_polar)) \
    * zeta * dxq
forms.append(load_polar)
