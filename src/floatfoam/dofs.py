"""The degrees of freedom, in one table (as Capytaine's ``bodies/dofs.py``).

Each rigid-body DoF the suite analyses has a name (heave, roll, pitch), the key of the case's
``[release]`` table that displaces it (heave in m, heel and trim in degrees), the column of
``motion.csv`` that records it, the unit of that column and of the release, the key of the
theory's equilibrium that it decays to, and its index in the (heave, roll, pitch) matrices of
the theory and potential flow. Angles are degrees in files and radians in code
(docs/conventions.md).
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
NAMES = tuple(d.name for d in DOFS)
RELEASE_KEYS = tuple(d.release_key for d in DOFS)
_BY_NAME = {d.name: d for d in DOFS}


def dof(name: str) -> Dof:
    """The DoF called ``name``; an InputError naming the valid ones otherwise."""
    try:
        return _BY_NAME[name]
    except KeyError:
        raise InputError(f"dof = {name!r}: valid are {', '.join(NAMES)}") from None


def released(release: dict) -> list[Dof]:
    """The DoFs a ``[release]`` table displaces (a non-zero heave, heel or trim)."""
    return [d for d in DOFS if float(release.get(d.release_key, 0.0) or 0.0) != 0.0]
