"""Ursell's (1949) multipole solution for the heaving half-immersed circular cylinder.

An independent reference for the 2D panel method (:mod:`floatfoam.potential.sections`): it shares no
code and no Green-function formula with it. Deep water, time dependence e^{-iωt}, K = ω²/g,
polar coordinates about the axis with θ from the downward vertical, depth d = r cos θ and
horizontal distance x = r sin θ (Ursell 1949, Q. J. Mech. Appl. Math. 2, 218–231):

* wave-free multipoles  φ_m = cos 2mθ / r^{2m} + K cos(2m−1)θ / ((2m−1) r^{2m−1}), m ≥ 1;
* standing waves  ψ_c = π e^{−Kd} cos Kx  (regular) and
  ψ_s = π e^{−Kd} sin Kx − ∫₀^∞ e^{−kx} (k cos kd − K sin kd) / (k² + K²) dk  (the source),
  the outgoing source being ψ_s − i ψ_c (→ −iπ e^{−Kd} e^{iKx} far away).

All satisfy Laplace's equation and the free-surface condition ∂φ/∂d + Kφ = 0 on d = 0.
φ = c₀ (ψ_s − iψ_c) + Σ c_m φ_m is fitted by least squares to ∂φ/∂r = −cos θ on r = a
(heave: the outward normal's z component), and A + iB/ω = 2ρa ∫₀^{π/2} φ(a, θ) cos θ dθ.
High frequency: A → ρπa²/2 (the coefficient below → 1).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import quad

MULTIPOLES = 20


def _source_integrals(x: float, d: float, K: float):
    """I = ∫ e^{−kx}(k cos kd − K sin kd)/(k²+K²) dk and its x and d derivatives (x > 0).

    QUADPACK's Fourier-weighted rule (QAWF) is used when the oscillation matters (kd ≳ 1 over
    the decay length 1/x); otherwise, and near the free surface, the plain adaptive rule.
    """
    def integrand(kind):
        def f(k):
            base = np.exp(-k * x) / (k * k + K * K)
            c, s = np.cos(k * d), np.sin(k * d)
            if kind == 0:
                return base * (k * c - K * s)
            if kind == 1:  # ∂/∂x
                return -k * base * (k * c - K * s)
            return base * (-k * k * s - K * k * c)  # ∂/∂d
        return f

    def fourier(kind):
        def parts(k):
            base = np.exp(-k * x) / (k * k + K * K)
            if kind == 0:
                return base * k, -base * K  # × cos, × sin
            if kind == 1:
                return -base * k * k, base * K * k
            return -base * K * k, -base * k * k
        cos_part = quad(lambda k: parts(k)[0], 0, np.inf, weight="cos", wvar=d, limlst=200)[0]
        sin_part = quad(lambda k: parts(k)[1], 0, np.inf, weight="sin", wvar=d, limlst=200)[0]
        return cos_part + sin_part

    if d * 1.0 > 0.5 * x:
        return [fourier(kind) for kind in range(3)]
    return [quad(integrand(kind), 0, np.inf, limit=400, epsabs=1e-12, epsrel=1e-10)[0]
            for kind in range(3)]


def _source(r: float, theta: float, K: float):
    """Outgoing source ψ_s − iψ_c and its radial derivative at (r, θ)."""
    x, d = r * np.sin(theta), r * np.cos(theta)
    integral, i_x, i_d = _source_integrals(x, d, K)
    e = np.pi * np.exp(-K * d)
    psi_c, psi_s = e * np.cos(K * x), e * np.sin(K * x) - integral
    c_x, c_d = -K * e * np.sin(K * x), -K * psi_c
    s_x, s_d = K * e * np.cos(K * x) - i_x, -K * e * np.sin(K * x) - i_d
    value = psi_s - 1j * psi_c
    d_r = np.sin(theta) * (s_x - 1j * c_x) + np.cos(theta) * (s_d - 1j * c_d)
    return value, d_r


def _multipole(m: int, r: float, theta: float, K: float):
    value = np.cos(2 * m * theta) / r ** (2 * m) \
        + K * np.cos((2 * m - 1) * theta) / ((2 * m - 1) * r ** (2 * m - 1))
    d_r = -2 * m * np.cos(2 * m * theta) / r ** (2 * m + 1) \
        - K * np.cos((2 * m - 1) * theta) / r ** (2 * m)
    return value, d_r


def ursell_heave(omega_nd, *, radius: float = 1.0, rho: float = 1000.0, g: float = 9.81):
    """Heave added mass and damping per unit length of a half-immersed circular cylinder.

    Parameters
    ----------
    omega_nd : ω √(a/g), one value or an array.

    Returns
    -------
    (A / (ρπa²/2), B / (ρπa²ω/2)) as arrays.
    """
    a = radius
    mass = rho * np.pi * a * a / 2.0
    coef_a, coef_b = [], []
    for w in np.atleast_1d(omega_nd):
        omega = w * np.sqrt(g / a)
        K = omega * omega / g
        thetas = np.linspace(0.005, np.pi / 2, 60)
        rows, rhs = [], []
        for th in thetas:
            row = [_source(a, th, K)[1]] + [_multipole(m, a, th, K)[1]
                                            for m in range(1, MULTIPOLES + 1)]
            rows.append(row)
            rhs.append(-np.cos(th))
        coef = np.linalg.lstsq(np.array(rows), np.array(rhs, dtype=complex), rcond=None)[0]
        nodes, weights = np.polynomial.legendre.leggauss(24)
        th = 0.25 * np.pi * (nodes + 1.0)
        integral = 0.0
        for t, wt in zip(th, weights, strict=True):
            phi = coef[0] * _source(a, t, K)[0] + sum(
                coef[m] * _multipole(m, a, t, K)[0] for m in range(1, MULTIPOLES + 1))
            integral += 0.25 * np.pi * wt * phi * np.cos(t)
        force = 2.0 * rho * a * integral  # A + iB/ω
        coef_a.append(force.real / mass)
        coef_b.append(force.imag * omega / (mass * omega))
    return np.array(coef_a), np.array(coef_b)
