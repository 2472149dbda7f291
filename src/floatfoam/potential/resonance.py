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


def mass_matrix(mass: float, gyradius, rotation: np.ndarray, *,
                horizontal: bool = False) -> np.ndarray:
    """Rigid-body mass matrix for (heave, roll, pitch) about G in earth axes: diag(M) for
    heave and the (x, y) block of R · M diag(k_x², k_y², k_z²) · Rᵀ for roll and pitch;
    with ``horizontal``, (heave, roll, pitch, surge, sway) (5 × 5, M for surge and sway: about
    G, translation and rotation are not coupled by the body's own inertia)."""
    inertia = rotation @ np.diag(mass * np.asarray(gyradius, dtype=float) ** 2) @ rotation.T
    out = np.zeros((5, 5) if horizontal else (3, 3))
    out[0, 0] = mass
    out[1:3, 1:3] = inertia[:2, :2]
    if horizontal:
        out[3, 3] = out[4, 4] = mass
    return out


def condensed(omega: np.ndarray, mass: np.ndarray, added_mass: np.ndarray,
              damping: np.ndarray, keep: int, free: list[int]):
    """Added mass and damping of DoF ``keep`` when the DoFs ``free`` (no restoring: surge,
    sway) follow it freely — the impedance Z = −ω²(M + A) − iωB (e^{−iωt}) condensed onto
    ``keep`` (Schur complement):

        Z_eff = Z_kk − Z_kf Z_ff⁻¹ Z_fk = −ω² (M_kk + A_eff) − iω B_eff.

    A free body rolling at frequency ω sways so that the fluid's force on it in sway is
    balanced by its own inertia; the roll it sees has another inertia and damping (lighter at
    high frequency: A_eff ≤ A_kk at ω = ∞, B = 0). For a
    circle with G a distance d below its axis A_kk = d²A_22, and at ω = ∞ (no damping)
    A_eff = d²A_22 M/(M + A_22).
    ``omega = inf`` rows (A∞, B = 0) are condensed with the inertia alone.

    Shapes: omega (n,), mass (d, d), added_mass and damping (n, d, d) → A_eff, B_eff (n,).
    """
    omega = np.asarray(omega, dtype=float)
    added_mass = np.asarray(added_mass, dtype=float).reshape(len(omega), *mass.shape)
    damping = np.asarray(damping, dtype=float).reshape(added_mass.shape)
    a_eff = np.empty(len(omega))
    b_eff = np.empty(len(omega))
    k, f = [keep], list(free)
    for n, w in enumerate(omega):
        if np.isinf(w):
            inertia = mass + added_mass[n]
            z = -(inertia - 0.0j)
            scale = 1.0
        else:
            z = -(w * w) * (mass + added_mass[n]) - 1j * w * damping[n]
            scale = w * w
        z_eff = z[np.ix_(k, k)] - z[np.ix_(k, f)] @ np.linalg.solve(z[np.ix_(f, f)],
                                                                     z[np.ix_(f, k)])
        a_eff[n] = -z_eff[0, 0].real / scale - mass[keep, keep]
        b_eff[n] = 0.0 if np.isinf(w) else -z_eff[0, 0].imag / w
    return a_eff, b_eff
