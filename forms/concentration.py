# Membrane concentration c of the concentration-based inextensibility (3.70):
#   d_t c + v.grad c + c P_phi : grad v = d_c div(P_phi grad c)     in Omega,
# c = 1 on an unstretched membrane, c < 1 where it is stretched, c > 1 where compressed.
# One implicit Euler step after the flow and the phase field (operator split of 5.3): v is
# v^{n+1}, P_phi is taken at phi^{n+1}. Natural (zero-flux) boundary condition.
from ufl import (Coefficient, FunctionSpace, Identity, TestFunction, TrialFunction, dot, dx,
                 grad, inner, outer)

from cellphase_ufl import DIM, P2, QDEG, constants, domain, velocity

V = FunctionSpace(domain, P2)
c, s = TrialFunction(V), TestFunction(V)
c0 = Coefficient(V)      # c^n
phi = Coefficient(V)     # phi^{n+1} (the union of the cells, (7.14))
v = velocity()           # v^{n+1}
dt, diffusion = constants("dt", "diffusion")

GRAD_FLOOR = 1e-10
g = grad(phi)
P = Identity(DIM) - outer(g, g) / (inner(g, g) + GRAD_FLOOR**2)   # P_phi, 3.4.3
dxq = dx(metadata={"quadrature_degree": QDEG})

a = (c * s / dt                                          # d_t c
     + dot(v, grad(c)) * s                               # v.grad c
     + c * inner(P, grad(v)) * s                         # c P_phi : grad v
     + diffusion * inner(P * grad(c), grad(s))) * dxq    # -d_c div(P_phi grad c)
L = c0 * s / dt * dxq
forms = [a, L]
