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


# The advection term is integrated with its exact degree (P2 * P2 * grad P1 = 5), a rule of
# its own: FFCx then emits it as a separate block, and the code (and round-off) of the other
# terms is the same as without flow, where the block adds exact zeros.
ADVECTION_DEGREE = 5


def mixed(n):
    """n scalar P2 fields solved together (phi first)."""
    return MixedElement([P2] * n)


def constants(*names):
    """Scalar constants bound by name from C++ (extra names are ignored there)."""
    return [Constant(domain) for _ in names]


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
