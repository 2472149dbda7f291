"""The tank around the body and the body's poses: what every stage places the body in.

The tank (:func:`tank`, the ``[domain]`` table, its defaults scaled by the body's span) and the
body frame's placements (:func:`pose`: the body's own frame, the theory's equilibrium, the
release) are read by the hydrostatics (the release's checks against the tank), the meshers, the
run and the analysis alike; they live here, below all of them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatfoam.case import Case
from floatfoam.errors import InputError

DOMAIN_DEFAULTS = {  # × the body's span S (its largest dimension), unless a physical value
    "half_length": 20.0,  # tank half-length (y for a 2D section, x in 3D, radius of a wedge)
    "air_height": 3.0,  # air above the free surface
    "deep_depth": 10.0,  # water depth when fluid.depth is infinite
}


@dataclass(frozen=True)
class Tank:
    """Fluid domain around the body, earth frame, free surface z = 0 (m).

    ``half_length`` is along y for a 2D section (its plane of motion is y-z), along x in 3D and
    the radius of a wedge; ``half_width`` is along y in 3D; ``band`` is the half-height of the
    free-surface band of fine cells; ``thickness`` the x-extent of a 2D mesh (default: the
    section's length L, so that forces and the case's mass are for the same length)."""

    half_length: float
    half_width: float
    depth: float
    air_height: float
    band: float
    thickness: float


@dataclass(frozen=True)
class Pose:
    """Placement of the body frame in the earth frame: z_c (m), heel and trim (radians), and
    the horizontal offsets x_c, y_c (m) of a body met on its way (a run's mesh made anew,
    :mod:`floatfoam.foam.remesh`; a case's poses keep them 0)."""

    z_c: float = 0.0
    heel: float = 0.0
    trim: float = 0.0
    x_c: float = 0.0
    y_c: float = 0.0


POSES = ("body", "equilibrium", "release")


def body_extents(body) -> np.ndarray:
    """Extents of the body that set the mesh: (y, z) for a 2D section, (x, y, z) otherwise."""
    extents = np.asarray(body.hi, dtype=float) - np.asarray(body.lo, dtype=float)
    return extents[1:] if body.is_section else extents


def tank(case: Case) -> Tank:
    """The tank of ``case``: its ``[domain]`` table, defaults scaled by the body's span."""
    values = {k: v for k, v in vars(case.settings.domain).items() if v is not None}
    extents = body_extents(case.body)
    span, length = float(extents.max()), float(extents.min())
    if math.isfinite(case.depth):
        values["depth"] = case.depth  # the case checked that domain.depth agrees
    half_length = values.get("half_length", DOMAIN_DEFAULTS["half_length"] * span)
    heave = abs(case.release["heave"])
    tilt = math.sin(math.radians(max(abs(case.release["heel"]), abs(case.release["trim"]))))
    return Tank(
        half_length=half_length,
        half_width=values.get("half_width", half_length),
        depth=values.get("depth", DOMAIN_DEFAULTS["deep_depth"] * span),
        air_height=values.get("air_height", DOMAIN_DEFAULTS["air_height"] * span),
        # the band holds the waterline over the first oscillation: release offset, the
        # waterline's shift at the body's side for the release angle, and D/4 of waves
        band=values.get("band", 0.25 * length + heave + 0.5 * span * tilt),
        thickness=values.get("thickness", case.body.length or length),
    )


def pose(case: Case, which: str = "release", equilibrium=None) -> Pose:
    """The body frame's placement: ``body`` (identity), ``equilibrium`` (the theory's) or
    ``release`` (equilibrium + the case's [release] offsets: the initial state of a decay
    test). ``equilibrium``: the case's (:func:`floatfoam.hydrostatics.theory.equilibrium`),
    needed by all but ``body``: the tank sits below the hydrostatics, which it does not call."""
    if which not in POSES:
        raise InputError(f"--pose {which!r}: valid poses are {', '.join(POSES)}")
    if which == "body":
        return Pose()
    if equilibrium is None:
        raise TypeError(f"pose(case, {which!r}) needs the case's equilibrium")
    base = Pose(equilibrium.z_c, equilibrium.heel, equilibrium.trim)
    if which == "equilibrium":
        return base
    rel = case.release
    return Pose(base.z_c + rel["heave"], base.heel + math.radians(rel["heel"]),
                base.trim + math.radians(rel["trim"]))
