"""The body–fluid coupling's added-mass compensation, from the body's added mass at infinite
frequency.

interFoam moves the body at each of the PIMPLE loop's outer correctors with the fluid's force
of the corrector before (docs/coupling.md). Within a step the fluid answers a change of the
body's acceleration with its added mass at infinite frequency, A∞; the body's faces take the
velocity at the step's end (floatfoam's ``bodyVelocity``), of which Newmark's scheme,
v¹ = v⁰ + Δt·(a⁰ + a¹)/2, passes half of a change of a¹ on. A corrector thus maps the body's
acceleration by the gain −½·M⁻¹·A∞ over the DoFs it is free in (M: its mass and inertia about
G), and the correctors diverge where the gain's spectral radius g exceeds 1: a body light
beside the water it moves (a flat, shallow float). And with the correctors converged, the
fluid's force answers the body's mean acceleration over the step, ½·A∞·(aⁿ + aⁿ⁺¹), where the
body's equation at the step's end wants A∞·aⁿ⁺¹. floatfoam's six-DoF restraint
``addedMassCompensation`` (src/solver/) mends both with A = ½·A∞ (:func:`compensating_mass`):
each corrector takes the acceleration (M + 2A)⁻¹·(F + A·(q_last + qⁿ)) (q_last the corrector
before's, qⁿ the step before's), whose fixed point M·q = F − A·(q − qⁿ) moves the body with
the added-mass force at the step's end, reached in one corrector where A is the fluid's answer,
whatever the body's lightness.
"""

from __future__ import annotations

import numpy as np

from floatfoam.dofs import COUPLED_NAMES

#: the share of a change of the body's acceleration that its faces' velocity at the step's end
#: passes on (Newmark's γ = ½)
VELOCITY_SHARE = 0.5

#: the index of each DoF of the potential flow's matrices in the restraint's generalized
#: coordinates: x, y, z, rotations about x, y and z (earth axes)
_AXIS = {"surge": 0, "sway": 1, "heave": 2, "roll": 3, "pitch": 4}


def infinite_frequency_added_mass(case, equilibrium, free: list[str]) -> np.ndarray:
    """A∞ over the DoFs ``free`` (names, in that order), from
    :func:`floatfoam.potential.radiation.radiation_coefficients` at infinite frequency alone
    (cached in build/potential)."""
    from floatfoam.potential.radiation import radiation_coefficients

    coefficients = radiation_coefficients(case, equilibrium, omegas=np.array([]))
    index = [COUPLED_NAMES.index(name) for name in free]
    return np.asarray(coefficients.added_mass_inf, dtype=float)[np.ix_(index, index)]


def coupling_gain(case, a_inf: np.ndarray, free: list[str]) -> float:
    """g: the spectral radius of ½·M⁻¹·A∞ over the DoFs ``free`` (``a_inf``:
    :func:`infinite_frequency_added_mass` over them): the factor by which an uncompensated
    corrector multiplies the error of the body's acceleration."""
    ixx, iyy, _ = (case.mass * k * k for k in case.gyradius)
    inertia = {"heave": case.mass, "surge": case.mass, "sway": case.mass,
               "roll": ixx, "pitch": iyy}
    gain = VELOCITY_SHARE * a_inf / np.array([inertia[name] for name in free])[:, None]
    return float(max(abs(np.linalg.eigvals(gain))))


def compensating_mass(a_inf: np.ndarray, free: list[str], share: float) -> dict:
    """The restraint's compensating mass: ½·A∞ (``a_inf``, over the DoFs ``free``:
    :func:`infinite_frequency_added_mass`), × ``share`` (the part of
    the body the domain holds, as its mass), zero in the DoFs the body is held in; a 6 × 6
    matrix over x, y, z and the rotations about x, y and z, as the restraint's four tensors
    (row by row): ``linear`` (force of a linear acceleration), ``linearAngular`` (force of an
    angular one), ``angularLinear`` and ``angular`` (the moments of each)."""
    out = np.zeros((6, 6))
    index = [_AXIS[name] for name in free]
    out[np.ix_(index, index)] = VELOCITY_SHARE * share * a_inf
    blocks = {"linear": out[:3, :3], "linearAngular": out[:3, 3:],
              "angularLinear": out[3:, :3], "angular": out[3:, 3:]}
    return {name: [float(v) for v in block.ravel()] for name, block in blocks.items()}
