# GTPase signalling network on the diffuse cell (thesis 2.6 and chapter 5), one implicit
# step after the flow and the phase field (section 5.3, step 4):
#   d_t(phib C)   + div(phib v C)   = D_C  div(phib grad C)  - gamma delta q          (5.16)
#   d_t(delta c1) + div(delta v c1) + div(delta c1 P_phi grad c~)
#                                   = d_c1 div(delta grad c1) + gamma delta h         (5.17), (5.21)
#   d_t(delta c2) + div(delta v c2) = d_c2 div(delta grad c2) - gamma delta h + gamma delta q  (5.18)
# c1, c2 live on the membrane (weight delta ~ |grad phi~| = |grad phi|/2, (2.39)), C in the
# cytoplasm (weight phib ~ phi~ = (1 + phi)/2, (2.36)). The membrane weight |grad phi~|
# integrates to 1 across the interface, so int delta c is the membrane's amount of c; the
# thesis writes (5.17)-(5.18) with |grad phi|, which is the same equation (c1 and c2 carry
# one weight each) and |0.5 grad phi| in (5.16), the same weight as here.
#
# Regularisation: the weights vanish away from the cell, where the matrix rows would be
# zero. Transport (time derivative, advection, diffusion) uses phib = phi~ + rho and
# delta = sqrt(|grad phi~|^2 + rho^2); the reactions use the unregularised |grad phi~|.
# Every term but the time derivative vanishes for the test function 1 (divergence form,
# and the reaction terms cancel between the species), so the scheme keeps
#   M = int phib C + delta (c1 + c2)
# to round-off. The amount with the unregularised weights, int phi~ C + |grad phi~| (c1 + c2),
# differs from M by at most rho int (C + c1 + c2); observables.csv has both.
#
# Kinetics (5.5), (5.6), linearised semi-implicitly (new values where they enter linearly,
# the saturating factors at the old values, as in [208]), which keeps the system linear
# and its reaction matrix an M-matrix for c >= 0:
#   h(c1, c2) = a1 c2 + a2 c1/(b1 + c1) c2 - a3 c1/(b2 + c1)
#            ~ a1 c2 + a2 c1^n/(b1 + c1^n) c2 - a3 c1 / (b2 + c1^n)
#   q(c1, c2, C) = a4 C (1 - c1 - c2)_+ - a5 c2  ~  a4 C (1 - c1^n - c2^n)_+ - a5 c2
# A new reaction is a term here (in every species it moves, with opposite signs) and its
# coefficient in `kinetics`; a new species is an entry of `species`, a sub-space of W and
# its transport term. The scene's reaction_diffusion section takes its keys from these
# literals (python/reaction_models.py writes them into a table at build time).
from ufl import (Coefficient, Constant, FunctionSpace, Identity, SpatialCoordinate, TestFunctions,
                 TrialFunctions, conditional, dot, dx, grad, gt, inner, max_value,
                 min_value, outer, split, sqrt)

from cellphase_ufl import DIM, P2, QDEG, constants, domain, mixed, velocity

# The species in the order of the mixed space: region and default diffusion (Table 5.1);
# the diffusion coefficient of species s is the constant D_<s>.
species = {"c1": ("membrane", 1.0), "c2": ("membrane", 1.0), "C": ("bulk", 20.0)}
# The kinetic constants and their defaults (Table 5.1; gamma is gamma-bar of (5.2)-(5.4)).
kinetics = {"a1": 0.0, "a2": 160.0, "a3": 1.0, "a4": 0.333, "a5": 10.0, "b1": 20.0,
            "b2": 0.5, "gamma": 400.0}
# The species whose concentration pushes the membrane out, -(1/Fa) c grad phi (5.7).
protrusion = "c1"

W = FunctionSpace(domain, mixed(len(species)))  # (c1, c2, C)
(c1, c2, C), (s1, s2, sC) = TrialFunctions(W), TestFunctions(W)
u0 = Coefficient(W)                           # (c1^n, c2^n, C^n)
c1_0, c2_0, C_0 = split(u0)
V = FunctionSpace(domain, P2)
phi = Coefficient(V)                          # phi^{n+1}
phi_old = Coefficient(V)                      # phi^n (the weights of d_t)
v = velocity()                                # v^{n+1} (zero without flow)

(dt, rho, D_c1, D_c2, D_C, a1, a2, a3, a4, a5, b1, b2, gamma,
 chem_point, chem_xi) = constants(
    "dt", "rho", "D_c1", "D_c2", "D_C", "a1", "a2", "a3", "a4", "a5", "b1", "b2", "gamma",
    "chem_point", "chem_xi")
chem_dir = Constant(domain, shape=(DIM,))     # grad c~ of modes 1-3 (xi included)
chem_x0 = Constant(domain, shape=(DIM,))      # source point x0 of mode 4

dxq = dx(metadata={"quadrature_degree": QDEG})


def phi_tilde(p):
    """(1 + phi)/2 clipped to [0, 1]: phi overshoots +-1 slightly, and a negative bulk
    weight would make the bulk diffusion ill-posed there."""
    return min_value(max_value((1 + p) / 2, 0.0), 1.0)


def bulk_weight(p):
    return phi_tilde(p) + rho


def membrane_weight(p):
    g = grad(p) / 2
    return sqrt(inner(g, g) + rho**2)


def membrane_delta(p):
    """|grad phi~|, the diffuse surface delta of the reactions (2.39), (2.46)."""
    g = grad(p) / 2
    return sqrt(inner(g, g))


wB, wM, delta = bulk_weight(phi), membrane_weight(phi), membrane_delta(phi)
wB0, wM0 = bulk_weight(phi_old), membrane_weight(phi_old)

pos = lambda x: conditional(gt(x, 0), x, 0)   # (.)_+ of (5.6)
c1p = max_value(c1_0, 0.0)
h_lin = a1 * c2 + a2 * c1p / (b1 + c1p) * c2 - a3 * c1 / (b2 + c1p)      # (5.5)
q_lin = a4 * C * pos(1 - c1_0 - c2_0) - a5 * c2                          # (5.6)

# Chemotactic drift of c1 along the membrane (5.21): grad c~ = chem_dir (modes 1-3) or
# -xi (x - x0)/|x - x0| (mode 4, chem_point = 1); P_phi projects it onto the membrane.
x = SpatialCoordinate(domain)
r = x - chem_x0
grad_signal = chem_dir - chem_point * chem_xi * r / sqrt(inner(r, r) + 1e-30)
GRAD_FLOOR = 1e-10
gp = grad(phi)
P = Identity(DIM) - outer(gp, gp) / (inner(gp, gp) + GRAD_FLOOR**2)


def transport(c, s, w, D):
    """d_t(w c) (new part) + div(w v c) + D div(w grad c), tested with s; the advection is
    integrated by parts (zero for s = 1; v = 0 or v.n free of mass on the walls)."""
    return (w * c * s / dt - w * c * dot(v, grad(s)) + D * w * inner(grad(c), grad(s)))


a = (transport(c1, s1, wM, D_c1) + transport(c2, s2, wM, D_c2) + transport(C, sC, wB, D_C)
     - wM * c1 * inner(dot(P, grad_signal), grad(s1))) * dxq \
    - gamma * delta * (h_lin * s1 + (q_lin - h_lin) * s2 - q_lin * sC) * dxq
L = (wM0 * c1_0 * s1 + wM0 * c2_0 * s2 + wB0 * C_0 * sC) / dt * dxq

# Observables: a species' amount in the transport weight (what the scheme conserves) and in
# the unregularised weight (the amount on the diffuse membrane / in the diffuse cell).
z = Coefficient(V)   # one species
phi_h = Coefficient(V)
membrane_amount = membrane_weight(phi_h) * z * dxq
bulk_amount = bulk_weight(phi_h) * z * dxq
membrane_amount_cell = membrane_delta(phi_h) * z * dxq
bulk_amount_cell = phi_tilde(phi_h) * z * dxq

forms = [a, L, membrane_amount, bulk_amount, membrane_amount_cell, bulk_amount_cell]
