"""The degrees of freedom, in one table (as Capytaine's ``bodies/dofs.py``).

Each rigid-body DoF the suite analyses has a name (heave, roll, pitch), the key of the case's
``[release]`` table that displaces it (heave in m, heel and trim in degrees), the column of
``motion.csv`` that records it, the unit of that column and of the release, the key of the
theory's equilibrium that it decays to, and its index in the (heave, roll, pitch) matrices of
the theory and potential flow. Angles are degrees in files and radians in code
(docs/conventions.md).

Surge and sway have no hydrostatic restoring and are never released, but a free body moves in
them when it rolls or pitches: the fluid's inertia couples them to the rotation about G
(``HORIZONTAL``, indices 3 and 4 of the potential-flow matrices, after heave, roll and pitch;
:func:`free_dofs` names the DoFs a body released in a fluid moves in).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from floatfoam.errors import InputError


@dataclass(frozen=True)
class Dof:
    """One degree of freedom (see the module docstring)."""

    name: str
    release_key: str
    column: str
    unit: str  # in files: m or deg
    equilibrium_key: str
    index: int  # in the (heave, roll, pitch) matrices
    inertia_unit: str  # of added mass
    damping_unit: str  # of radiation damping

    @property
    def is_angle(self) -> bool:
        return self.unit == "deg"

    @property
    def file_scale(self) -> float:
        """Code units → file units: 180/π for angles, 1 for lengths."""
        return 180.0 / math.pi if self.is_angle else 1.0


DOFS = (
    Dof("heave", "heave", "z", "m", "z_G", 0, "kg", "N·s/m"),
    Dof("roll", "heel", "roll", "deg", "heel", 1, "kg·m²", "N·m·s"),
    Dof("pitch", "trim", "pitch", "deg", "trim", 2, "kg·m²", "N·m·s"),
)
HORIZONTAL = (
    Dof("surge", "", "x", "m", "x_G", 3, "kg", "N·s/m"),
    Dof("sway", "", "y", "m", "y_G", 4, "kg", "N·s/m"),
)
COUPLED = DOFS + HORIZONTAL  # the order of the potential-flow matrices (heave … sway)
PARTNER = {"roll": "sway", "pitch": "surge"}  # the horizontal DoF that follows each rotation
NAMES = tuple(d.name for d in DOFS)
COUPLED_NAMES = tuple(d.name for d in COUPLED)
RELEASE_KEYS = tuple(d.release_key for d in DOFS)
_BY_NAME = {d.name: d for d in COUPLED}


def dof(name: str) -> Dof:
    """The DoF called ``name``; an InputError naming the valid ones otherwise."""
    try:
        return _BY_NAME[name]
    except KeyError:
        raise InputError(f"dof = {name!r}: valid are {', '.join(COUPLED_NAMES)}") from None


def released(release: dict) -> list[Dof]:
    """The DoFs a ``[release]`` table displaces (a non-zero heave, heel or trim)."""
    return [d for d in DOFS if float(release.get(d.release_key, 0.0) or 0.0) != 0.0]


def free_dofs(release: dict, *, axisymmetric: bool = False, chosen=None) -> list[Dof]:
    """The DoFs the body is free in, in the CFD (:func:`floatfoam.foam.render.constraints`) and
    the models alike: ``chosen`` (names, ``[motion] free``: as a rig holds a model) when given,
    else those a body released in a fluid moves in: heave always; sway and roll after a heel;
    surge and pitch after a trim; heave alone for a body of revolution in heave (a wedge)."""
    if chosen is not None:
        return sorted((_BY_NAME[n] for n in chosen), key=lambda d: d.index)
    heel = float(release.get("heel", 0.0) or 0.0) != 0.0
    trim = float(release.get("trim", 0.0) or 0.0) != 0.0
    names = ["heave"]
    if not axisymmetric:
        names += ["roll", PARTNER["roll"]] * heel + ["pitch", PARTNER["pitch"]] * trim
    return sorted((_BY_NAME[n] for n in names), key=lambda d: d.index)


def check_free(chosen, release: dict) -> None:
    """An InputError naming ``motion.free`` when it holds a DoF the release displaces."""
    if chosen is None:
        return
    held = [d.name for d in released(release) if d.name not in chosen]
    if held:
        raise InputError(f"motion.free = {list(chosen)!r}: the release displaces "
                         f"{', '.join(held)}, which it holds; valid lists include "
                         f"{', '.join(d.name for d in released(release))}")


def parse_dofs(text: str) -> list[Dof]:
    """DoFs from a comma-separated list of names (``--dofs roll,sway``), in matrix order; an
    InputError naming the valid ones otherwise."""
    names = [n.strip() for n in text.split(",") if n.strip()]
    if not names:
        raise InputError(f"--dofs {text!r}: valid is a comma-separated list of "
                         f"{', '.join(COUPLED_NAMES)}")
    chosen = {}
    for name in names:
        if name not in _BY_NAME:
            raise InputError(f"--dofs {text!r}: {name!r} is not a DoF; valid are "
                             f"{', '.join(COUPLED_NAMES)}")
        chosen[name] = _BY_NAME[name]
    return sorted(chosen.values(), key=lambda d: d.index)
