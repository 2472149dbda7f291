"""The memoir's "rigorous" equations: a rigid body under gravity and exact hydrostatics.

No added mass and no damping: at every instant the buoyancy ρgV acts at the centre of buoyancy B
of the exact immersed volume (:func:`~floatfoam.hydrostatics.immersion.immersed`), the weight
Mg at G.
Both forces are vertical, so G moves only vertically (its horizontal momentum stays zero) and
the body turns about G with Euler's equations:

    M z̈_G = ρ g V − M g,
    I ω̇ + ω × I ω = Rᵀ [(B − G) × (0, 0, ρ g V)]          (body axes, I = M diag(k²)),

with the attitude R = R_z(ψ) R_y(θ) R_x(φ) (docs/conventions.md extended by yaw ψ; heel φ,
trim θ) and the Euler-angle rates (φ̇, θ̇, ψ̇) = T(φ, θ) ω. Periods depend on the amplitude,
and a body released past its angle of vanishing stability capsizes. The total energy

    E = ½ M ż_G² + ½ ωᵀ I ω + M g z_G − ρ g V z_B

is conserved (the hydrostatic force derives from the potential M g z_G − ρ g V z_B).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from floatfoam.bodies.geometry import rotation
from floatfoam.hydrostatics.immersion import immersed


def yaw_matrix(psi: float) -> np.ndarray:
    c, s = np.cos(psi), np.sin(psi)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class RigidBody:
    """A body with its mass, centre of gravity (body frame, m) and radii of gyration about
    body axes through G (m), in a fluid of density ``rho`` under gravity ``g``."""

    body: object
    mass: float
    cog: np.ndarray
    gyradius: np.ndarray
    rho: float = 1000.0
    g: float = 9.81

    @classmethod
    def from_case(cls, case) -> RigidBody:
        return cls(case.body, case.mass, np.asarray(case.cog, float),
                   np.asarray(case.gyradius, float), case.rho, case.g)

    @property
    def inertia(self) -> np.ndarray:
        return self.mass * np.asarray(self.gyradius, float) ** 2  # principal, body axes

    def z_centre(self, z_g: float, heel: float, trim: float) -> float:
        """Height z_c of the body-frame origin when G is at height z_G."""
        return z_g - float((rotation(heel, trim) @ self.cog)[2])

    def hydrostatics(self, z_g: float, heel: float, trim: float, yaw: float = 0.0):
        """Net vertical force ρgV − Mg (N), the moment of buoyancy about G in earth axes
        (N·m) and the :class:`~floatfoam.hydrostatics.immersion.Immersed` part."""
        z_c = self.z_centre(z_g, heel, trim)
        imm = immersed(self.body, z_c, heel, trim)
        lever = imm.centroid - (rotation(heel, trim) @ self.cog + np.array([0.0, 0.0, z_c]))
        lever = yaw_matrix(yaw) @ lever
        buoyancy = self.rho * self.g * imm.volume
        moment = np.array([lever[1] * buoyancy, -lever[0] * buoyancy, 0.0])
        return buoyancy - self.mass * self.g, moment, imm

    def energy(self, z_g, heel, trim, w, omega_body) -> float:
        """Total energy (J); see the module docstring."""
        imm = immersed(self.body, self.z_centre(z_g, heel, trim), heel, trim)
        kinetic = 0.5 * self.mass * w * w + 0.5 * float(np.dot(self.inertia * omega_body,
                                                                omega_body))
        potential = self.mass * self.g * z_g - self.rho * self.g * imm.volume * imm.centroid[2]
        return kinetic + potential


def euler_rates(heel: float, trim: float, omega_body: np.ndarray) -> np.ndarray:
    """(φ̇, θ̇, ψ̇) from the body-axis angular velocity ω for R = R_z(ψ) R_y(θ) R_x(φ)."""
    p, q, r = omega_body
    sp, cp = np.sin(heel), np.cos(heel)
    ct, tt = np.cos(trim), np.tan(trim)
    return np.array([p + (q * sp + r * cp) * tt, q * cp - r * sp, (q * sp + r * cp) / ct])


def body_rates(heel: float, trim: float, rates: np.ndarray) -> np.ndarray:
    """Body-axis angular velocity ω from the Euler-angle rates (inverse of :func:`euler_rates`)."""
    dphi, dtheta, dpsi = rates
    sp, cp = np.sin(heel), np.cos(heel)
    st, ct = np.sin(trim), np.cos(trim)
    return np.array([dphi - dpsi * st, dtheta * cp + dpsi * ct * sp,
                     -dtheta * sp + dpsi * ct * cp])


def nonlinear_decay(rigid: RigidBody, z_g0: float, heel0: float, trim0: float, t, *,
                    w0: float = 0.0, rates0=(0.0, 0.0, 0.0), rtol: float = 1e-10,
                    atol: float = 1e-12, progress=None) -> dict:
    """Integrate the rigorous equations (module docstring) from rest or given velocities.

    Parameters
    ----------
    rigid : the body, its mass properties and the fluid
    z_g0, heel0, trim0 : initial height of G (m) and attitude (rad)
    t : output times (s), from 0
    w0, rates0 : initial heave velocity of G (m/s) and Euler-angle rates (rad/s)
    rtol, atol : tolerances of the DOP853 integrator (atol relative to the body size and 1 rad)
    progress : optional; its ``update(t)`` hears the time the integrator has reached (s)

    Returns
    -------
    dict of arrays: time, z (of G), heel, trim, yaw (rad), w (m/s), omega_body (n, 3) and
    omega_earth (n, 3) (rad/s).
    """
    inertia = rigid.inertia
    size = float(getattr(rigid.body, "size", 1.0))

    def rhs(time, y):
        if progress is not None:
            progress.update(time)
        z_g, heel, trim, yaw, w = y[:5]
        omega = y[5:]
        force, moment, _ = rigid.hydrostatics(z_g, heel, trim, yaw)
        moment_body = (yaw_matrix(yaw) @ rotation(heel, trim)).T @ moment
        domega = (moment_body - np.cross(omega, inertia * omega)) / inertia
        return np.concatenate([[w], euler_rates(heel, trim, omega), [force / rigid.mass],
                               domega])

    omega0 = body_rates(heel0, trim0, np.asarray(rates0, dtype=float))
    y0 = np.concatenate([[z_g0, heel0, trim0, 0.0, w0], omega0])
    t = np.asarray(t, dtype=float)
    scale = np.array([size, 1, 1, 1, size, 1, 1, 1], dtype=float)
    sol = solve_ivp(rhs, (t[0], t[-1]), y0, method="DOP853", t_eval=t, rtol=rtol,
                    atol=atol * scale)
    if not sol.success:
        raise RuntimeError(f"nonlinear decay: the integrator failed ({sol.message})")
    y = sol.y.T
    omega_body = y[:, 5:]
    omega_earth = _to_earth(y[:, 1], y[:, 2], y[:, 3], omega_body)
    return {"time": sol.t, "z": y[:, 0], "heel": y[:, 1], "trim": y[:, 2], "yaw": y[:, 3],
            "w": y[:, 4], "omega_body": omega_body, "omega_earth": omega_earth}


def _to_earth(heel, trim, yaw, vectors) -> np.ndarray:
    """Body-axis vectors (n, 3) in earth axes, R_z(ψ) R_y(θ) R_x(φ) v sample by sample, with
    arrays (a long series in one pass, not a Python loop)."""
    p, q, r = np.asarray(vectors, dtype=float).T
    cp, sp = np.cos(heel), np.sin(heel)
    ct, st = np.cos(trim), np.sin(trim)
    cy, sy = np.cos(yaw), np.sin(yaw)
    y1, z1 = cp * q - sp * r, sp * q + cp * r  # R_x(φ)
    x2, z2 = ct * p + st * z1, -st * p + ct * z1  # R_y(θ)
    return np.column_stack([cy * x2 - sy * y1, sy * x2 + cy * y1, z2])  # R_z(ψ)


def restoring_force(rigid: RigidBody, z_g0: float, heel0: float, trim0: float):
    """Nonlinear restoring force F(x) of the generalised coordinates x = (Δz_G, Δφ, Δθ) about
    an equilibrium, for the Cummins equation (M + A∞)ẍ + ∫Kẋ + F(x) = 0:

        F(x) = −(ρgV − Mg, M_x, M_y)  at (z_G0 + Δz_G, φ0 + Δφ, θ0 + Δθ),

    whose Jacobian at x = 0 is the hydrostatic stiffness C (earth-axis moments; exact for
    rotation about one axis, the gyroscopic terms of the rigorous model are left out)."""
    def force(x):
        f, moment, _ = rigid.hydrostatics(z_g0 + x[0], heel0 + x[1], trim0 + x[2])
        return -np.array([f, moment[0], moment[1]])

    return force
