"""Shared UFL vocabulary of the cellphase forms: cell type, elements, double-well potentials.

Every form file is compiled twice by FFCx (2D triangles and 3D tetrahedra); the build sets
CELLPHASE_DIM, and this module picks the cell from it so the physics is written once.
"""
import math
import os

from ufl import (Constant, FiniteElement, Mesh, MixedElement, VectorElement, tetrahedron,
                 triangle)

DIM = int(os.environ.get("CELLPHASE_DIM", "2"))
cell = {2: triangle, 3: tetrahedron}[DIM]
domain = Mesh(VectorElement("Lagrange", cell, 1))
P2 = FiniteElement("Lagrange", cell, 2)


P2vec = VectorElement("Lagrange", cell, 2)


def velocity():
    """The flow velocity v^{n+1} that advects phi (operator split of section 5.3); the
    flow module's vector P2 field, or zero when the scene has no flow."""
    from ufl import Coefficient, FunctionSpace
    return Coefficient(FunctionSpace(domain, P2vec))


def advection(phi, psi, v):
    """v . grad(phi) tested with psi, written as -phi v . grad(psi) (integration by parts,
    v.n = 0 on walls, div v = 0): psi = 1 gives 0, so int phi is kept exactly although the
    Taylor-Hood v is only weakly divergence-free. (2.58), (3.45), (3.61), (3.83)."""
    from ufl import dot, grad
    return -phi * dot(v, grad(psi))


def own_mesh_advection(psi, v, own_mesh):
    """On a cell's own mesh (own_mesh = 1) phi + 1 is advected instead of phi: the same for
    div v = 0, but phi + 1 is the cell's own content, zero outside the patch, so the flux
    through the patch's edge is (phi + 1) v . n (see own_mesh_outflow). This is the phi-free
    part of -(phi + 1) v . grad(psi), on the right-hand side; own_mesh = 0 on the shared mesh."""
    from ufl import dot, grad
    return own_mesh * dot(v, grad(psi))


def own_mesh_outflow(phi, psi, v, own_mesh):
    """The boundary term of the advection of phi + 1 on a cell's own mesh (section 7.2), upwind:
    where the fluid leaves the patch (v . n > 0) phi + 1 leaves with it, implicit in phi^{n+1};
    where it enters, it brings phi + 1 = 0 (no other part of this cell lies outside). Without
    it nothing leaves, and what the flow carries to the edge piles up there. Returns the
    (lhs, rhs) parts of int max(v . n, 0) (phi + 1) psi ds; both are exact zeros on the shared
    mesh (own_mesh = 0) and on walls (v = 0)."""
    from ufl import ds
    dsq = ds(degree=OUTFLOW_DEGREE)
    return leaving(v, own_mesh) * phi * psi * dsq, -leaving(v, own_mesh) * psi * dsq


def leaving(v, own_mesh):
    """own_mesh max(v . n, 0): the normal velocity where the fluid leaves the mesh."""
    from ufl import FacetNormal, conditional, dot, gt
    n = FacetNormal(domain)
    return own_mesh * conditional(gt(dot(v, n), 0), dot(v, n), 0)


# The advection term is integrated with its exact degree (P2 * P2 * grad P1 = 5), a rule of
# its own: FFCx then emits it as a separate block, and the code (and round-off) of the other
# terms is the same as without flow, where the block adds exact zeros.
ADVECTION_DEGREE = 5
OUTFLOW_DEGREE = 6  # v . n phi psi on a facet: P2 * P2 * P2


def mixed(n):
    """n scalar P2 fields solved together (phi first)."""
    return MixedElement([P2] * n)


def constants(*names):
    """Scalar constants bound by name from C++ (extra names are ignored there)."""
    return [Constant(domain) for _ in names]


def bdf2_constants():
    """Constants of the variable-step BDF2 scheme (numerics.time_scheme: bdf2), section
    "Time schemes" of docs/scenes.md. With w = dt_n / dt_{n-1}:
      d_t phi(t^{n+1}) ~ (c0 phi^{n+1} - c1 phi^n + c2 phi^{n-1}) / dt_n,
      c0 = (1 + 2w) / (1 + w),  c1 = 1 + w,  c2 = w^2 / (1 + w),
    and the nonlinear terms are linearised about the extrapolation
      phi* = (1 + w) phi^n - w phi^{n-1} = phi^{n+1} + O(dt^2)
    instead of phi^n, so the Taylor linearisation of section 5.3 stays second order.
    Bind them to the globals bdf_c0, bdf_c1, bdf_c2, bdf_w (C++ sets them by name)."""
    return constants("bdf_c0", "bdf_c1", "bdf_c2", "bdf_w")


def extrapolate(now, before, w):
    """phi* = (1 + w) phi^n - w phi^{n-1}, the BDF2 linearisation point."""
    return (1 + w) * now - w * before


def helfrich_time_schemes(linear_part, rhs_part, taylor, phi, now, before, bdf, H0):
    """The Helfrich flows' (helfrich_l2.py, helfrich_hm1.py) two time discretisations from
    their parts: linear_part(trial of d_t phi), rhs_part(known part of d_t phi, explicit
    curvature), taylor(phi_l, mu_l) -> (lhs, rhs) of the linearisation about (phi_l, mu_l).
    now = (phi^n, mu^n), before = (phi^{n-1}, mu^{n-1}), bdf = (c0, c1, c2, w).
    Returns backward Euler about phi^n, the thesis' scheme, as (a, L); BDF2 about the
    extrapolation (phi*, mu*) as (a_bdf2, L_bdf2); and kappa(phi*, mu*) for the loads."""
    (phi0, mu0), (phi1, mu1), (c0, c1, c2, w) = now, before, bdf
    lhs, rhs = taylor(phi0, mu0)
    euler = (linear_part(phi) + lhs, rhs_part(phi0, kappa_of(phi0, mu0, H0)) + rhs)
    phi_x, mu_x = extrapolate(phi0, phi1, w), extrapolate(mu0, mu1, w)
    kappa_x = kappa_of(phi_x, mu_x, H0)
    lhs_x, rhs_x = taylor(phi_x, mu_x)
    bdf2 = (linear_part(c0 * phi) + lhs_x, rhs_part(c1 * phi0 - c2 * phi1, kappa_x) + rhs_x)
    return euler, bdf2, kappa_x


# Double-well potential W(phi) = (phi^2-1)^2/4 and its derivatives, section 2.5.1.
def W(phi):
    return (phi**2 - 1) ** 2 / 4


def dW(phi):
    return (phi**2 - 1) * phi


def ddW(phi):
    return 3 * phi**2 - 1


# Modified double well W0 of the Helfrich energy with spontaneous curvature H0, (3.9)/(3.22).
def dW0(phi, eps, H0):
    return (phi**2 - 1) * (phi + math.sqrt(2) * H0 * eps)


def ddW0(phi, eps, H0):
    return 3 * phi**2 + 2 * math.sqrt(2) * H0 * eps * phi - 1


def dddW0(phi, eps, H0):
    return 6 * phi + 2 * math.sqrt(2) * H0 * eps


def kappa_of(phi, mu, H0):
    """Diffuse mean curvature kappa = -eps Lap phi + W'(phi)/eps (3.24) written with the
    Helfrich mu = eps Lap phi - W0'(phi)/eps (3.23): kappa = -mu - sqrt2 H0 (phi^2-1)."""
    return -mu - math.sqrt(2) * H0 * (phi**2 - 1)


# Quadrature degree for the nonlinear terms: the automatic estimate (P2 to the 4th power and
# more) costs much assembly time and buys no accuracy over the interpolation error.
QDEG = 6


# Interaction between cells, section 7.1.2. B(phi) = (phi^2 - 1)^2 / eps lives in the
# diffuse interface of a cell; the interaction function of a cell is a function of the
# signed distance d = -(eps/sqrt2) ln((1 + phi)/(1 - phi)) to its membrane, computed from
# its phase field (7.3) instead of a distance computation. The Lennard-Jones-like w-bar of
# Fig. 7.7 (r1, r2: repulsion strength and range; a1, a2, a3: adhesion strength, position
# and range) is the Gaussian w of (7.2) for r1 = r2 = 1, a1 = 0. Zero where |phi| >= 1.
# cpp/physics/InteractionFunction.h evaluates the same functions at the nodes.
def B_of(phi, eps):
    return (phi**2 - 1)**2 / eps


def dB_of(phi, eps):
    return 4 * phi * (phi**2 - 1) / eps


def _inside_band(phi):
    from ufl import conditional, lt
    return lambda value: conditional(lt(abs(phi), 1 - 1e-12), value, 0.0)


def _distance(phi, eps):
    from ufl import ln, max_value, min_value, sqrt
    p = max_value(min_value(phi, 1 - 1e-12), -1 + 1e-12)
    return -eps / sqrt(2.0) * ln((1 + p) / (1 - p)), p


def interaction_w(phi, eps, r1, r2, a1, a2, a3):
    from ufl import exp
    d, _ = _distance(phi, eps)
    w = r1 * exp(-d**2 / (r2 * eps**2)) - a1 * exp(-(d - a2 * eps)**2 / (a3 * eps**2))
    return _inside_band(phi)(w)


def interaction_dw(phi, eps, r1, r2, a1, a2, a3, reach):
    """d w / d phi = (d w / d d) (d d / d phi), d d / d phi = -(eps / sqrt2) 2 / (1 - phi^2),
    where |d| < reach eps (interaction.derivative_reach; unlimited by default). d d / d phi
    grows like e^(sqrt2 |d| / eps): a long-range w (the adhesion of the Lennard-Jones-like
    potential, a3 = 20) makes the term w'_i B(phi_j) of (7.11) huge inside cell j, far from
    cell i's membrane, where it moves phi_i instead of the membrane."""
    from ufl import conditional, exp, lt, sqrt
    d, p = _distance(phi, eps)
    dw_dd = (-2 * d / (r2 * eps**2) * r1 * exp(-d**2 / (r2 * eps**2))
             + 2 * (d - a2 * eps) / (a3 * eps**2) * a1 * exp(-(d - a2 * eps)**2 / (a3 * eps**2)))
    dw = conditional(lt(abs(d), reach * eps), dw_dd * (-eps / sqrt(2.0)) * 2 / (1 - p**2), 0.0)
    return _inside_band(phi)(dw)
