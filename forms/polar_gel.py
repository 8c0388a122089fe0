# Orientation field of an active polar gel (thesis chapter 6): one implicit step of the
# actin orientation P and its chemical potential P# after the flow (section 6.3, step 2):
#   d_t P + (v.grad) P = -Omega.P + xi D.P - (1/kappa) P#                           (6.16)
#   P# = (1/Pa) ( -Lap P + c1 |P|^2 P - c1 phi P + beta grad phi )                   (6.17)
# with Omega = (grad v^T - grad v)/2 (UFL's grad v is d_j v_i: -Omega.P turns P with the
# fluid), D = (grad v + grad v^T)/2, the natural condition grad P . n = 0 on the walls
# (section 6.2.5), phi = phi^n and v = v^{n+1}. |P|^2 P is linearised as in step 2:
#   |P|^2 P ~ |P^n|^2 P + 2 (P^n (x) P^n) P - 2 |P^n|^2 P^n.
# The forces of P on the flow (6.13) and of the phase field's potential (6.15) are below.
#
# Stabilisation: the flow takes P^n, P#^n explicitly. Through the alignment stress a mode
# of P# drives a velocity gradient of about (1 + xi)/2 |P|^2 P# / eta, which turns P back
# by about (1 + xi)^2/4 |P|^2 P# / eta =: k P# in the next step, against the implicit
# relaxation P#/kappa. For large dt the fine modes grow by -k kappa, unstable for
# k kappa > 1 (Table 6.1: k kappa ~ 1.8). The term S (P#^{n+1} - P#^n) in (6.16), with
# S > (k - 1/kappa)/2, makes the factor (S - k)/(S + 1/kappa) a contraction; it is O(dt)
# consistent, like the stabilised Cahn-Hilliard scheme, and S = 0 is the thesis' scheme.
#
# P# eliminated: P# enters (6.16) only as (1/kappa + S) int P#^{n+1}.q, and the weak
# (6.17), tested with the same vector P2 functions and the same quadrature, says that this
# integral is (1/Pa) times the right-hand side of (6.17) tested with q. Substituting it
# leaves a system for P alone whose solution is the P^{n+1} of the coupled (P#, P) system
# exactly, with half the unknowns (docs/scenes.md gives the time saved). The step's own
# P#^{n+1} is not needed: after the step P# is projected again from P^{n+1} and phi^{n+1}
# (L_sharp below; PolarGelSubProblem::finish_step says why).
from ufl import (Coefficient, FunctionSpace, TestFunction, TrialFunction, dot, dx, grad,
                 inner, outer, sym)

from cellphase_ufl import P2, P2vec, QDEG, constants, domain, velocity

V = FunctionSpace(domain, P2)
Vvec = FunctionSpace(domain, P2vec)
P, q = TrialFunction(Vvec), TestFunction(Vvec)
Pi, Psi = Coefficient(Vvec), Coefficient(Vvec)           # P^n, P#^n (and standalone P, P#)
phi = Coefficient(V)                                     # phi^n
v = velocity()                                           # v^{n+1} (zero without flow)
dt, Pa, c1, beta, xi, kappa, activity, S = constants("dt", "Pa", "c1", "beta", "xi", "kappa",
                                                     "activity", "S")
dxq = dx(metadata={"quadrature_degree": QDEG})

G = grad(v)
Omega = (G.T - G) / 2   # vorticity tensor of (6.9)
Dv = sym(G)             # deformation tensor of (6.9)

# (6.17) tested with q: int P#.q = sharp_lhs(P, q) + sharp_rhs(q), linearised at P^n
sharp_lhs = (inner(grad(P), grad(q))
             + c1 * (inner(Pi, Pi) * inner(P, q) + 2 * inner(Pi, P) * inner(Pi, q))
             - c1 * phi * inner(P, q)) / Pa
sharp_rhs = (-2 * c1 * inner(Pi, Pi) * inner(Pi, q) + beta * inner(grad(phi), q)) / Pa
relax = 1 / kappa + S   # the weight of P#^{n+1} in (6.16) with the stabilisation
# (6.16) tested with q, its P#^{n+1} replaced by (6.17)
a = (inner(P, q) / dt + inner(dot(grad(P), v), q) + inner(dot(Omega, P), q)
     - xi * inner(dot(Dv, P), q) + relax * sharp_lhs) * dxq
L = (inner(Pi, q) / dt + S * inner(Psi, q) - relax * sharp_rhs) * dxq

# P# of a given P (L2 projection of (6.17), with the vector P2 mass matrix of
# forms/interface_force.py): P#^0 for the flow's first step, and after every step P#^{n+1}
# of P^{n+1} and phi^{n+1}.
r = TestFunction(Vvec)
L_sharp = ((inner(grad(Pi), grad(r)) + c1 * inner(Pi, Pi) * inner(Pi, r)
            - c1 * phi * inner(Pi, r) + beta * inner(grad(phi), r)) / Pa) * dxq


def phi_tilde(p):
    return (1 + p) / 2


# Force of the orientation field on the flow, the P terms of (6.13) (phi# grad phi comes
# from the phase field's potential), as its L2 projection onto the velocity space:
#   grad P^T . P# + div( (P# (x) P - P (x) P#)/2 + xi (P# (x) P + P (x) P#)/2 )
#   + activity div(phi~ P (x) P),                activity = 1/Fa of (6.11)
# the divergences tested by parts (P vanishes outside the cell, so no wall term).
stress = (outer(Psi, Pi) - outer(Pi, Psi)) / 2 + xi * (outer(Psi, Pi) + outer(Pi, Psi)) / 2 \
    + activity * phi_tilde(phi) * outer(Pi, Pi)
force_L = (inner(dot(grad(Pi).T, Psi), r) - inner(stress, grad(r))) * dxq

# The orientation energy (6.4)
energy = (inner(grad(Pi), grad(Pi)) / 2 + c1 / 4 * inner(Pi, Pi) * (-2 * phi + inner(Pi, Pi))
          + beta * inner(Pi, grad(phi))) / Pa * dxq
# Its dissipation (1/kappa) int |P#|^2 of (6.10), and the mean of P over the cell
dissipation = inner(Psi, Psi) / kappa * dxq
P_cell = [phi_tilde(phi) * Pi[i] * dxq for i in range(2)]
P_cell_0, P_cell_1 = P_cell

forms = [a, L, L_sharp, force_L, energy, dissipation, P_cell_0, P_cell_1]
