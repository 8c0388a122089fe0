# Incompressible two-phase flow, one semi-implicit step of section 5.3 (step 1) for the
# variable density/viscosity model of section 2.8:
#   Re [rho(phi) (d_t v + (v^n.grad) v^{n+1}) + (J.grad) v^{n+1}] + grad p
#       = div(2 eta(phi) D(v^{n+1})) + F,        div v^{n+1} = 0
# on a P2/P1 Taylor-Hood pair (section 5.3). Re = 0 gives (quasi-steady) Stokes; the switch
# `convection` = 0 drops the transport terms (time-dependent Stokes, constant matrix).
from ufl import (Coefficient, Constant, FiniteElement, FunctionSpace, MixedElement,
                 TestFunctions, TrialFunctions, VectorElement, div, dx, grad, inner,
                 max_value, min_value, sym)

from cellphase_ufl import (DIM, P2, QDEG, W, bdf2_constants, cell, constants, domain,
                           extrapolate)

P2v = VectorElement("Lagrange", cell, 2)
P1 = FiniteElement("Lagrange", cell, 1)
TH = FunctionSpace(domain, MixedElement([P2v, P1]))     # Taylor-Hood, section 5.3
Vvec = FunctionSpace(domain, P2v)
Vphi = FunctionSpace(domain, P2)
Q = FunctionSpace(domain, P1)

(v, p), (w, q) = TrialFunctions(TH), TestFunctions(TH)
v0 = Coefficient(Vvec)          # v^n; after a step the module stores v^{n+1} here
v1 = Coefficient(Vvec)          # v^{n-1} (numerics.time_scheme: bdf2)
phi = Coefficient(Vphi)         # phase field of the last phase-field step (bdf2: phi*, below)
mu = Coefficient(Vphi)          # its chemical potential (CH: -eps Lap phi + W'(phi)/eps)
f_membrane = Coefficient(Vvec)  # further interface forces, provided by the coupling
p_h = Coefficient(Q)            # pressure, for its mean value
(dt, Re, convection, rho0, rho1, eta0, eta1, mobility, capillary, one,
 degenerate) = constants("dt", "Re", "convection", "rho0", "rho1", "eta0", "eta1", "mobility",
                         "capillary", "one", "degenerate")
gravity = Constant(domain, shape=(DIM,))  # acceleration, multiplied by rho(phi)
force = Constant(domain, shape=(DIM,))    # body force density independent of the phase
# Second order in time (numerics.time_scheme: bdf2, docs/scenes.md "Time schemes"): the
# variable-step BDF2 of cellphase_ufl.bdf2_constants for d_t v, the transport velocity
# extrapolated, v* = (1 + w) v^n - w v^{n-1}; the C++ binds phi and mu to the extrapolated
# phase field phi*, mu* (the same formula), so that the flow is evaluated at t^{n+1} to
# O(dt^2) although the split solves it before the phase field.
bdf_c0, bdf_c1, bdf_c2, bdf_w = bdf2_constants()
v_star = extrapolate(v0, v1, bdf_w)

# Material laws. Index 1 is the cell (phi = +1), index 0 the surrounding fluid (phi = -1).
# phi is clipped to [-1, 1] so that P2 overshoots of the tanh profile (2.12) cannot make
# rho or eta negative for large contrasts.
phic = max_value(min_value(phi, 1.0), -1.0)


def rho_of(f):
    """Density interpolated linearly in phi like eta in (2.56)."""
    return rho1 * (1 + f) / 2 + rho0 * (1 - f) / 2


def eta_of(f):
    """(2.56): eta(phi) = eta1 (1+phi)/2 + eta0 (1-phi)/2 (the thesis prints (phi-1)/2 for
    the second weight, which would make eta negative outside; (1-phi)/2 is meant)."""
    return eta1 * (1 + f) / 2 + eta0 * (1 - f) / 2


def D(u):
    """Strain rate D = (grad v + grad v^T)/2, (2.49)."""
    return sym(grad(u))


rho = rho_of(phic)
eta = eta_of(phic)
# Extra mass flux of the thermodynamically consistent variable-density model (section 2.8):
# the term d rho/d phi gamma grad(dE/dphi).grad v there equals -(J.grad) v with
# J = -(rho1 - rho0)/2 * gamma * grad mu.
# gamma(phi) as in forms/cahn_hilliard.py: constant, or mobility W(phi) (`degenerate` = 1).
J = -(rho1 - rho0) / 2 * mobility * (1 - degenerate + degenerate * W(phi)) * grad(mu)

# Phase-dependent integrands are polynomials of degree up to 7 (rho v^n.grad v.w); the
# clipping makes them piecewise anyway, so QDEG (6) is used as for the phase-field forms.
# The pressure terms keep the exact automatic degree.
dxq = dx(metadata={"quadrature_degree": QDEG})


# Several cells with viscosities of their own: eta(phi_1, ..., phi_N) of (7.12),
# eta_0 (1 - phi_cells)/2 + sum_i eta_i (1 + phi_i)/2, given at the P2 nodes by the coupling.
eta_cells = Coefficient(Vphi)


def momentum_a(v, p, w, q, inertia=True, eta=eta, bdf2=False):
    """Bilinear form of one step of (2.47)/(2.56)/(2.57) for trial (v, p), test (w, q);
    without `inertia` the Stokes system (Re = 0) with none of the Re terms; `eta` the
    viscosity (default eta(phi) of (2.56)); `bdf2` the second-order step (c0 v^{n+1} and the
    transport velocity v* instead of v^{n+1} and v^n)."""
    viscous = 2 * eta * inner(D(v), D(w))  # -div(2 eta(phi) D(v)), (2.49)/(2.56) (written
    #   eta D there; with the factor 2, eta = 1 and div v = 0 give the Lap v of 5.3 (1))
    pressure = (-p * div(w)                                           # grad p, (2.47)/(2.56)
                - q * div(v)) * dx                                    # div v = 0, (2.57)
    if not inertia:
        return viscous * dxq + pressure
    time_derivative = (Re * rho * bdf_c0 / dt if bdf2 else Re * rho / dt) * inner(v, w)
    transport = v_star if bdf2 else v0
    return (time_derivative                                           # Re rho d_t v, 5.3 (1), (3.43)
            + convection * Re * inner(grad(v) * (rho * transport + J), w)  # (v^n.grad)v, 5.3 (1); J, 2.8
            # Temam's term: zero for div v^n = 0 (consistent). For constant rho and J = 0 it
            # makes the linearised convection do no work although v^n is only weakly
            # divergence-free, i.e. (2.59) holds discretely and E_kin obeys (2.61). (With
            # variable rho an exact discrete law would need rho(phi^{n+1}), unknown in step 1
            # of the split.)
            + convection * Re * rho / 2 * div(transport) * inner(v, w)
            + viscous) * dxq + pressure


# Body forces F of (2.47): rho_i g per phase and a constant force; the capillary force
# dE_S/dphi grad phi of model H (2.8, 5.3 (1)) with mu the CH chemical potential and
# `capillary` its prefactor (3 sigma / (2 sqrt2) in 2.8, 1/Ca with the scaling of 3.4);
# f_membrane carries the Helfrich/active forces (3.59), (5.7) once coupled.
def momentum_L(w, inertia=True, bdf2=False):
    """Right-hand side of one step for the velocity test function w (Stokes: no v^n)."""
    forces = (inner(rho * gravity + force, w)                         # F, (2.47)
              + capillary * mu * inner(grad(phi), w)                  # dE/dphi grad phi, 2.8
              + inner(f_membrane, w))                                 # (3.59), (5.7)
    if not inertia:
        return forces * dxq
    known = bdf_c1 * v0 - bdf_c2 * v1 if bdf2 else v0                 # BDF2: c1 v^n - c2 v^{n-1}
    return (Re * rho / dt * inner(known, w) + forces) * dxq           # v^n of d_t v, 5.3 (1)


a = momentum_a(v, p, w, q)
L = momentum_L(w)
# Re = 0: the same system without the inertial terms, which the module then skips
a_stokes = momentum_a(v, p, w, q, inertia=False)
# The same with the cells' own viscosities (7.12)
a_cells = momentum_a(v, p, w, q, eta=eta_cells)
a_stokes_cells = momentum_a(v, p, w, q, inertia=False, eta=eta_cells)
L_stokes = momentum_L(w, inertia=False)
# Second order in time (Re > 0; the Stokes forms serve both schemes)
a_bdf2 = momentum_a(v, p, w, q, bdf2=True)
L_bdf2 = momentum_L(w, bdf2=True)

# Observables of the current velocity (v0 after a step)
kinetic_energy = rho / 2 * inner(v0, v0) * dxq                           # (2.54)
divergence_sq = div(v0) ** 2 * dx                                        # |div v|^2
phase_weight = (1 + phi) / 2 * dx                                        # int phi~ (2.14)
phase_velocity = [(1 + phi) / 2 * v0[i] * dxq for i in range(DIM)]       # int phi~ v_i
phase_velocity_0 = phase_velocity[0]
phase_velocity_1 = phase_velocity[1]
pressure_integral = p_h * dx
domain_volume = one * dx

forms = [a, L, a_stokes, L_stokes, kinetic_energy, divergence_sq, phase_weight, phase_velocity_0,
         phase_velocity_1, pressure_integral, domain_volume, a_cells, a_stokes_cells, a_bdf2,
         L_bdf2]
if DIM == 3:
    phase_velocity_2 = phase_velocity[2]
    forms.append(phase_velocity_2)
