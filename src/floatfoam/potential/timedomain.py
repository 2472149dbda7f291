"""Time-domain free-decay models on plain arrays: linear, and Cummins (1962) with memory.

Generalised coordinates x = (heave of G, roll, pitch) measured from equilibrium (m, rad); the
case-level adapters are in :mod:`floatfoam.potential.models`, the nonlinear rigid body in
:mod:`floatfoam.potential.rigid_body`.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import PchipInterpolator


def linear_decay(mass: np.ndarray, stiffness: np.ndarray, x0, t, v0=None):
    """Exact solution of the memoir's linear model M ẍ + C x = 0 (no added mass, no damping).

    With M = L Lᵀ (Cholesky) the modal coordinates q = Qᵀ Lᵀ x of the symmetric matrix
    L⁻¹ C L⁻ᵀ = Q Λ Qᵀ obey q̈_k + λ_k q_k = 0: cos ω t, sin ω t / ω for λ = ω² > 0 (it
    oscillates), cosh κ t, sinh κ t / κ for λ = −κ² < 0 (it capsizes, exponentially), 1 and t
    for λ = 0 (neutral).

    Returns (x, v), each (len(t), n).
    """
    mass, stiffness = np.atleast_2d(mass), np.atleast_2d(stiffness)
    x0 = np.atleast_1d(np.asarray(x0, dtype=float))
    v0 = np.zeros_like(x0) if v0 is None else np.atleast_1d(np.asarray(v0, dtype=float))
    t = np.asarray(t, dtype=float)[:, None]
    chol = np.linalg.cholesky(mass)
    inv = np.linalg.inv(chol)
    lam, q = np.linalg.eigh(inv @ (0.5 * (stiffness + stiffness.T)) @ inv.T)
    to_modal = q.T @ chol.T
    from_modal = inv.T @ q
    q0, qd0 = to_modal @ x0, to_modal @ v0
    scale = np.sqrt(np.abs(lam))[None, :]
    tol = 1e-12 * max(np.abs(lam).max(), 1e-300)
    pos, neg = lam > tol, lam < -tol
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        c = np.where(pos, np.cos(scale * t), np.where(neg, np.cosh(scale * t), 1.0))
        s = np.where(pos, np.sin(scale * t) / scale, np.where(neg, np.sinh(scale * t) / scale, t))
        cd = np.where(pos, -scale * np.sin(scale * t), np.where(neg, scale * np.sinh(scale * t),
                                                                  0.0))
        sd = np.where(pos | neg, np.where(pos, np.cos(scale * t), np.cosh(scale * t)), 1.0)
    qt = c * q0 + s * qd0
    qdt = cd * q0 + sd * qd0
    return qt @ from_modal.T, qdt @ from_modal.T


def retardation_kernel(omega, damping, t, *, refine: int = 16, tail: float = 2.0):
    """Radiation retardation (memory) kernel of Cummins (1962) from the damping:

        K(t) = (2/π) ∫₀^∞ B(ω) cos ωt dω     (Ogilvie 1964)

    B is interpolated (PCHIP, B(0) = 0) onto a grid ``refine`` times finer than ``omega`` and
    continued past the last frequency ω_max by B(ω_max)·(ω_max/ω)⁴ up to ``tail``·ω_max (a
    smooth end; radiation damping falls steeply at high frequency), then integrated by the
    trapezoidal rule. Shapes: omega (n,), damping (n, d, d) or (n,), t (m,) → (m, d, d).
    """
    omega = np.asarray(omega, dtype=float)
    damping = np.asarray(damping, dtype=float)
    flat = damping.reshape(len(omega), -1)
    w = np.concatenate([[0.0], omega])
    b = np.concatenate([np.zeros((1, flat.shape[1])), flat])
    step = (omega[-1] - omega[0]) / max(len(omega) - 1, 1) / refine
    fine = np.arange(0.0, omega[-1] + 0.5 * step, step)
    values = PchipInterpolator(w, b, axis=0)(fine)
    if tail > 1.0:
        extra = np.arange(fine[-1] + step, tail * omega[-1], step)
        values = np.concatenate([values, b[-1] * (omega[-1] / extra[:, None]) ** 4])
        fine = np.concatenate([fine, extra])
    weights = np.full(len(fine), step)
    weights[[0, -1]] *= 0.5
    t = np.asarray(t, dtype=float)
    kernel = (2.0 / np.pi) * np.cos(np.outer(t, fine)) @ (weights[:, None] * values)
    return kernel.reshape((len(t), *damping.shape[1:]))


def ogilvie_added_mass_inf(omega, added_mass, t, kernel):
    """A∞ recovered from A(ω) and K(t) by Ogilvie's (1964) relation, at every ω:

        A∞ = A(ω) + (1/ω) ∫₀^∞ K(t) sin ωt dt.

    A consistent (A, B, A∞) gives the same value at every frequency: the spread is a check
    of the kernel. Returns (n, d, d) (or (n,)).
    """
    t = np.asarray(t, dtype=float)
    kernel = np.asarray(kernel, dtype=float)
    flat = kernel.reshape(len(t), -1)
    weights = np.gradient(t)
    weights[[0, -1]] = 0.5 * (t[1] - t[0]), 0.5 * (t[-1] - t[-2])
    sine = np.sin(np.outer(omega, t)) * weights[None, :]
    correction = (sine @ flat) / np.asarray(omega)[:, None]
    added_mass = np.asarray(added_mass, dtype=float)
    return (added_mass.reshape(len(omega), -1) + correction).reshape(added_mass.shape)


def cummins_decay(mass, stiffness, a_inf, kernel_t, kernel, x0, t, *, v0=None,
                  restoring=None, max_iterations: int = 30, tolerance: float = 1e-12,
                  progress=None):
    """Free decay by the Cummins (1962) equation

        (M + A∞) ẍ + ∫₀^t K(t − τ) ẋ(τ) dτ + F(x) = 0,   F(x) = C x unless ``restoring``,

    integrated on the uniform times ``t`` by the trapezoidal (Newmark average-acceleration)
    rule, the convolution by the trapezoidal rule over the stored velocities; the unknown
    acceleration of each step solves the implicit equations by Newton iterations with the
    tangent (M + A∞) + h²/4 (C + K(0)) (exact in one step when F is linear). Without
    memory and with F = Cx the scheme conserves the energy ½ẋᵀMẋ + ½xᵀCx exactly.

    Parameters
    ----------
    mass, stiffness, a_inf : (d, d) rigid-body mass, hydrostatic stiffness, A∞
    kernel_t, kernel : the kernel's sample times (from 0) and values (m, d, d); it is
        interpolated onto the step of ``t`` and taken as zero after ``kernel_t[-1]``.
    x0, v0 : initial displacement and velocity (d,)
    t : uniform times from 0
    restoring : optional callable x ↦ F(x) (nonlinear restoring force, e.g. from
        :mod:`floatfoam.potential.rigid_body`)
    progress : optional; its ``update(t)`` hears the time reached (s) at every step

    Returns (x, v), each (len(t), d).
    """
    t = np.asarray(t, dtype=float)
    h = float(t[1] - t[0])
    if not np.allclose(np.diff(t), h, rtol=1e-9, atol=0.0):
        raise ValueError("cummins_decay needs equally spaced times")
    mass_total = np.atleast_2d(mass) + np.atleast_2d(a_inf)
    stiffness = np.atleast_2d(stiffness)
    d = mass_total.shape[0]
    kernel = np.asarray(kernel, dtype=float).reshape(len(kernel_t), d, d)
    lags = np.arange(0.0, kernel_t[-1] + 0.5 * h, h)
    lags = lags[lags <= kernel_t[-1]][: len(t)]
    k_h = np.stack([[np.interp(lags, kernel_t, kernel[:, i, j]) for j in range(d)]
                    for i in range(d)], axis=-1).transpose(1, 0, 2)  # (L, d, d)
    force = restoring or (lambda x: stiffness @ x)
    x = np.zeros((len(t), d))
    v = np.zeros((len(t), d))
    x[0] = np.asarray(x0, dtype=float)
    v[0] = np.zeros(d) if v0 is None else np.asarray(v0, dtype=float)
    a = np.linalg.solve(mass_total, -force(x[0]))
    tangent = mass_total + 0.25 * h * h * (stiffness + k_h[0])  # ∂residual/∂a
    lu_inverse = np.linalg.inv(tangent)
    n_lag = len(k_h)
    for n in range(len(t) - 1):
        m = n + 1
        # history part of μ_m = h Σ_j w_j K(t_m − t_j) v_j (all j < m; j = 0 has weight ½)
        j0 = max(0, m - n_lag + 1)
        lag_index = m - np.arange(j0, m)
        weights = np.full(m - j0, h)
        if j0 == 0:
            weights[0] = 0.5 * h
        history = np.einsum("k,kij,kj->i", weights, k_h[lag_index], v[j0:m]) if m - j0 else 0.0
        x_pred = x[n] + h * v[n] + 0.25 * h * h * a
        v_pred = v[n] + 0.5 * h * a
        a_new = a.copy()
        for _ in range(1 if restoring is None else max_iterations):  # linear: exact in one
            x_new = x_pred + 0.25 * h * h * a_new
            v_new = v_pred + 0.5 * h * a_new
            residual = mass_total @ a_new + history + 0.5 * h * k_h[0] @ v_new + force(x_new)
            delta = lu_inverse @ residual
            a_new -= delta
            if np.abs(delta).max() <= tolerance * (np.abs(a_new).max() + 1e-300):
                break
        x[m] = x_pred + 0.25 * h * h * a_new
        v[m] = v_pred + 0.5 * h * a_new
        a = a_new
        if progress is not None:
            progress.update(t[m])
    return x, v


def energy(mass, stiffness, x, v) -> np.ndarray:
    """Mechanical energy ½ ẋᵀ M ẋ + ½ xᵀ C x of a series (x, v: (m, d))."""
    mass, stiffness = np.atleast_2d(mass), np.atleast_2d(stiffness)
    return 0.5 * np.einsum("ti,ij,tj->t", v, mass, v) + 0.5 * np.einsum("ti,ij,tj->t", x,
                                                                         stiffness, x)
