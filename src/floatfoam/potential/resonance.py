"""Natural frequencies with frequency-dependent added mass, and equivalent damping ratios.

Pure numerics on arrays (no case, no solver): the adapters are in
:mod:`floatfoam.potential.radiation`.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq


def interpolator(omega: np.ndarray, values: np.ndarray):
    """Shape-preserving (PCHIP) interpolant of a coefficient sampled at ``omega``, held
    constant beyond the sampled range (where it is only used as a starting guess)."""
    spline = PchipInterpolator(omega, values, extrapolate=False)
    lo, hi = float(omega[0]), float(omega[-1])

    def f(w):
        return float(spline(min(max(w, lo), hi)))

    return f


def natural_frequency(mass: float, stiffness: float, omega: np.ndarray,
                      added_mass: np.ndarray) -> tuple[float | None, bool]:
    """Undamped natural frequency of one degree of freedom with added mass A(ω):

        ω_n² = C / (M + A(ω_n))

    solved by fixed-point iteration for a bracket, then Brent's method on
    f(ω) = ω² (M + A(ω)) − C over the sampled range (Newman 1977, §6.17).

    Returns
    -------
    (ω_n or None when C ≤ 0, inside) where ``inside`` tells whether ω_n lies inside the
    sampled frequencies (outside, A is held at its end value and ω_n is an extrapolation).
    """
    if not stiffness > 0.0:
        return None, True
    a_of = interpolator(omega, added_mass)

    def residual(w):
        return w * w * (mass + a_of(w)) - stiffness

    w = math.sqrt(stiffness / mass)
    for _ in range(50):  # fixed point ω ← √(C / (M + A(ω))), a good start
        new = math.sqrt(stiffness / max(mass + a_of(w), 1e-12 * mass))
        if abs(new - w) < 1e-12 * w:
            break
        w = new
    lo, hi = float(omega[0]), float(omega[-1])
    if not lo <= w <= hi:
        return w, False
    grid = np.asarray(omega, dtype=float)
    values = np.array([residual(x) for x in grid])
    crossings = np.nonzero(np.sign(values[:-1]) != np.sign(values[1:]))[0]
    if len(crossings) == 0:
        return w, True
    # the crossing nearest the fixed point (several exist only with strongly varying A)
    k = crossings[np.argmin(np.abs(grid[crossings] - w))]
    return brentq(residual, grid[k], grid[k + 1], xtol=1e-12 * hi, rtol=1e-12), True


def damping_ratio(mass: float, omega_n: float, added_mass_n: float, damping_n: float) -> float:
    """Equivalent linear damping ratio ζ = B / (2 ω_n (M + A)) at the natural frequency
    (the logarithmic decrement is δ ≈ 2πζ for small ζ)."""
    return damping_n / (2.0 * omega_n * (mass + added_mass_n))


def mass_matrix(mass: float, gyradius, rotation: np.ndarray) -> np.ndarray:
    """Rigid-body mass matrix for (heave, roll, pitch) about G in earth axes: diag(M) for
    heave and the (x, y) block of R · M diag(k_x², k_y², k_z²) · Rᵀ for roll and pitch."""
    inertia = rotation @ np.diag(mass * np.asarray(gyradius, dtype=float) ** 2) @ rotation.T
    out = np.zeros((3, 3))
    out[0, 0] = mass
    out[1:, 1:] = inertia[:2, :2]
    return out
