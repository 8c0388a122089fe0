# Allen-Cahn equation (2.24) and its volume-conserving non-local form (2.26)-(2.27):
#   d_t phi = -gamma ( -eps Lap phi + W'(phi)/eps + lambda_volume ),
# lambda_volume is explicit (computed from phi^n in C++, zero for plain Allen-Cahn).
from ufl import (Coefficient, FunctionSpace, TestFunction, TrialFunction, dx, grad, inner)

from cellphase_ufl import P2, QDEG, W, bdf2_constants, constants, dW, ddW, domain, extrapolate

V = FunctionSpace(domain, P2)
phi, psi = TrialFunction(V), TestFunction(V)
u0 = Coefficient(V)  # phi^n
dt, eps, gamma, S, lam_v = constants("dt", "eps", "gamma", "S", "lam_v")
dxq = dx(metadata={"quadrature_degree": QDEG})

# `now` is the trial part of the time derivative (phi, or c0 phi for BDF2).
def linear_part(now):
    return (now * psi / dt + gamma * eps * inner(grad(phi), grad(psi))) * dx


# Taylor linearisation (section 5.3): W'(phi) ~ W'(phi^n) + W''(phi^n)(phi - phi^n)
a = linear_part(phi) + gamma / eps * ddW(u0) * phi * psi * dxq
L = u0 * psi / dt * dx - gamma * (dW(u0) - ddW(u0) * u0) / eps * psi * dxq \
    - gamma * lam_v * psi * dx

# BDF2 (numerics.time_scheme: bdf2; cellphase_ufl.bdf2_constants), linearised about the
# extrapolation phi*; plain Allen-Cahn only (the multiplier of (2.27) is explicit).
u1 = Coefficient(V)  # phi^{n-1}
bdf_c0, bdf_c1, bdf_c2, bdf_w = bdf2_constants()
phi_x = extrapolate(u0, u1, bdf_w)
a_bdf2 = linear_part(bdf_c0 * phi) + gamma / eps * ddW(phi_x) * phi * psi * dxq
L_bdf2 = (bdf_c1 * u0 - bdf_c2 * u1) * psi / dt * dx \
    - gamma * (dW(phi_x) - ddW(phi_x) * phi_x) / eps * psi * dxq

# Stabilised: W'(phi) ~ W'(phi^n) + S (phi - phi^n); the matrix does not depend on phi^n
a_stab = (phi * psi / dt + gamma * eps * inner(grad(phi), grad(psi))
          + gamma * S / eps * phi * psi) * dx
L_stab = u0 * psi / dt * dx - gamma * (dW(u0) - S * u0) / eps * psi * dxq \
    - gamma * lam_v * psi * dx

# Integral of W'(phi^n)/eps for lambda_volume (2.27)
dW_integral = dW(u0) / eps * dxq
energy = (eps / 2 * inner(grad(u0), grad(u0)) + W(u0) / eps) * dxq

forms = [a, L, a_stab, L_stab, dW_integral, energy, a_bdf2, L_bdf2]
