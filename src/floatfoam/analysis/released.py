"""Which degrees of freedom a motion record is analysed in, and which hold no motion to fit.

A run folder of ``floatfoam run`` records its release (``.floatfoam/info.json``: ``release``,
the case's ``[release]`` table as run, ``--set`` included, and ``body_size``, the body's
largest dimension in m): its DoFs are the ones that release displaces
(:func:`floatfoam.dofs.released`). A run recorded before its release was gives its heel and
trim (radians): roll and pitch where they are not 0, else heave, the one release left. Any
other motion CSV (a decay model's series, a measurement) is analysed in the DoF that moves
most relative to its scale (:func:`relative_motion`), and the output says so.

A DoF whose range over the record is below :data:`NOISE_FRACTION` of its scale is refused: the
fit of such a record is a fit of noise (a roll release's heave is the coupled motion of the
roll, not a decay; a Cummins roll series holds 1e-17 m of heave).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from floatfoam import dofs
from floatfoam.errors import InputError
from floatfoam.plan.record import RunRecord, has_record, read_record

#: Below this fraction of its scale (1 rad, or the body's size) a DoF's range is noise: four
#: orders below the smallest release of any case (2° = 0.035 rad, elliptic_cylinder_capsize;
#: a heave release is ≥ 1 % of the body's size) and four above the rounding of motion.csv's
#: ten significant digits (1e-10 of the value; of ≤ 180° an angle, 3e-10 rad).
NOISE_FRACTION = 1e-6

#: the scale of an angle: 1 rad, the arc the body's edge turns through over its half size (a
#: range of 1e-6 rad moves the edge by 1e-6 of the body's half size), in degrees
RADIAN_DEG = 180.0 / math.pi

#: the least a body's size is taken to be where a record does not give it (m): free-decay
#: tests are made on bodies of 0.1 m and more (this project's cases: 0.1–1 m), so a heave range
#: below 1e-8 m is noise on any of them, though G sits at the waterline (|z| ~ 0)
SMALLEST_BODY = 0.01


@dataclass(frozen=True)
class Choice:
    """The DoFs to analyse (names), why, in words for the output, and the DoFs the run
    released (None for a CSV that is no run's)."""

    dofs: tuple[str, ...]
    reason: str
    released: tuple[str, ...] | None = None


def run_folder(source: str | Path) -> Path | None:
    """The run folder of a source (a run folder, or the ``motion.csv`` in one): the folder
    holding ``.floatfoam/info.json``; None for any other CSV."""
    path = Path(source)
    folder = path if path.is_dir() else path.parent
    return folder if has_record(folder) else None


def released_by_run(record: RunRecord) -> tuple[str, ...]:
    """The DoFs a run released, from its record (see the module docstring)."""
    if isinstance(record.release, dict):
        names = tuple(d.name for d in dofs.released(record.release))
        if names:
            return names
    angles = tuple(name for name, angle in (("roll", record.heel), ("pitch", record.trim))
                   if float(angle or 0.0) != 0.0)
    return angles or ("heave",)


def scale(dof: str, motion: dict, info: RunRecord | None = None) -> tuple[float, str]:
    """The scale a DoF's motion is measured against, in file units (m, deg), and its words: 1
    rad for an angle; for heave the body's size (the run's ``body_size``), or, where the
    record does not give it, the largest height of G from the still water in the record (G
    lies within the body, which the waterline crosses), at least :data:`SMALLEST_BODY`."""
    if dofs.dof(dof).is_angle:
        return RADIAN_DEG, "1 rad"
    size = info.body_size if info is not None else None
    if size:
        return float(size), f"the body's size ({float(size):.3g} m)"
    z = np.asarray(motion.get(dofs.dof(dof).column, []), dtype=float)
    z = z[np.isfinite(z)]
    largest = max(float(np.max(np.abs(z))) if z.size else 0.0, SMALLEST_BODY)
    return largest, (f"the body's size, taken as {largest:.3g} m (the largest |z| of G in "
                     f"the record, at least {SMALLEST_BODY:g} m)")


def motion_range(dof: str, motion: dict) -> float:
    """max − min of a DoF's column (file units), NaN left out (the analysis refuses it)."""
    values = np.asarray(motion.get(dofs.dof(dof).column, []), dtype=float)
    finite = values[np.isfinite(values)]
    return float(finite.max() - finite.min()) if finite.size else 0.0


def relative_motion(dof: str, motion: dict, info: RunRecord | None = None) -> float:
    """A DoF's range over the record divided by its :func:`scale` (0 for a zero scale)."""
    size, _ = scale(dof, motion, info)
    return motion_range(dof, motion) / size if size > 0 else 0.0


def check_motion(dof: str, motion: dict, info: RunRecord | None, source: Path, option: str,
                 moving: tuple[str, ...] = ()) -> None:
    """Refuse (InputError, one line) a DoF whose range is below :data:`NOISE_FRACTION` of its
    :func:`scale`; ``option`` names how it was chosen (``--dof heave``), ``moving`` the DoFs
    the record does move in, for the message."""
    size, words = scale(dof, motion, info)
    span = motion_range(dof, motion)
    if span > NOISE_FRACTION * size:
        return
    unit = dofs.dof(dof).unit
    valid = (f"a DoF the record moves in: {', '.join(moving)}" if moving else
             "a record of a free decay")
    raise InputError(f"{option}: its motion in {source} spans {span:.2g} {unit}, below "
                     f"{NOISE_FRACTION:g} of {words}: noise, not a decay to fit; valid is "
                     f"{valid}")


def moving_dofs(motion: dict, info: RunRecord | None = None) -> tuple[str, ...]:
    """The DoFs of the record's columns above the noise (:func:`check_motion`'s rule)."""
    return tuple(name for name in dofs.NAMES if dofs.dof(name).column in motion
                 and relative_motion(name, motion, info) > NOISE_FRACTION)


def choose(source: str | Path, motion: dict, requested: str | None = None) -> Choice:
    """The DoFs ``floatfoam analyse`` fits in a record: ``requested`` (``--dof``), else the
    ones the run released, else the one that moves most relative to its scale; each checked
    to move above the noise (:func:`check_motion`)."""
    run = run_folder(source)
    info = read_record(run) if run is not None else None
    moving = moving_dofs(motion, info)
    released = released_by_run(info) if info is not None else None
    if requested is not None:
        choice = Choice((requested,), "--dof", released)
    elif released is not None:
        choice = Choice(released, "released by the run", released)
    else:
        present = [n for n in dofs.NAMES if dofs.dof(n).column in motion]
        if not present:
            raise InputError(f"motion series: {source} has none of the columns "
                             f"{', '.join(dofs.dof(n).column for n in dofs.NAMES)}")
        best = max(present, key=lambda n: relative_motion(n, motion))
        choice = Choice((best,), "the largest motion in the file relative to its scale; "
                                 "--dof names another")
    for name in choice.dofs:
        option = f"--dof {name}" if requested else f"dof {name} ({choice.reason})"
        check_motion(name, motion, info, Path(source), option,
                     tuple(n for n in moving if n != name))
    return choice
