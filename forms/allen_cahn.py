# Allen-Cahn equation (2.24) and its volume-conserving non-local form (2.26)-(2.27):
#   d_t phi = -gamma ( -eps Lap phi + W'(phi)/eps + lambda_volume ),
# lambda_volume is explicit (computed from phi^n in C++, zero for plain Allen-Cahn).
from ufl import (Coefficient, FunctionSpace, TestFunction, TrialFunction, dx, grad, inner)

from cellphase_ufl import P2, QDEG, W, constants, dW, ddW, domain

V = FunctionSpace(domain, P2)
phi, psi = TrialFunction(V), TestFunction(V)
u0 = Coefficient(V)  # phi^n
dt, eps, gamma, S, lam_v = constants("dt", "eps", "gamma", "S", "lam_v")
dxq = dx(metadata={"quadrature_degree": QDEG})

# Taylor linearisation (section 5.3): W'(phi) ~ W'(phi^n) + W''(phi^n)(phi - phi^n)
a = (phi * psi / dt + gamma * eps * inner(grad(phi), grad(psi))) * dx \
    + gamma / eps * ddW(u0) * phi * psi * dxq
L = u0 * psi / dt * dx - gamma * (dW(u0) - ddW(u0) * u0) / eps * psi * dxq \
    - gamma * lam_v * psi * dx

# Stabilised: W'(phi) ~ W'(phi^n) + S (phi - phi^n); the matrix does not depend on phi^n
a_stab = (phi * psi / dt + gamma * eps * inner(grad(phi), grad(psi))
          + gamma * S / eps * phi * psi) * dx
L_stab = u0 * psi / dt * dx - gamma * (dW(u0) - S * u0) / eps * psi * dxq \
    - gamma * lam_v * psi * dx

# Integral of W'(phi^n)/eps for lambda_volume (2.27)
dW_integral = dW(u0) / eps * dxq
energy = (eps / 2 * inner(grad(u0), grad(u0)) + W(u0) / eps) * dxq

forms = [a, L, a_stab, L_stab, dW_integral, energy]
