# The interface force of several cells on the flow, (7.12): sum_i phi_i^natural grad phi_i,
# with one phase field per cell. The flow's forms take one (mu, phi) pair, so the sum is
# given to them as the free force f_membrane, its L2 projection onto vector P2: the mass
# matrix a is factorised once per mesh, and L is assembled for each cell and summed.
# `capillary` is the flow's prefactor of mu grad phi (1 for the Helfrich models).
from ufl import Coefficient, FunctionSpace, TestFunction, TrialFunction, dx, grad, inner

from cellphase_ufl import P2, P2vec, QDEG, constants, domain

Vvec = FunctionSpace(domain, P2vec)
V = FunctionSpace(domain, P2)
u, w = TrialFunction(Vvec), TestFunction(Vvec)
phi, mu = Coefficient(V), Coefficient(V)
(capillary,) = constants("capillary")

a = inner(u, w) * dx
L = capillary * mu * inner(grad(phi), w) * dx(metadata={"quadrature_degree": QDEG})

forms = [a, L]
