"""Read a motion series (``motion.csv``, format in docs/conventions.md) for the decay analysis.

The file stores angles in degrees; :func:`dof_series` returns them in radians (code units).
Nothing is dropped or repaired here: a NaN or inf is passed on and refused by
:func:`floatfoam.analysis.decay.validate_series`, which names the offending sample.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from floatfoam.dofs import dof as dof_named
from floatfoam.errors import InputError

MOTION_COLUMNS = ("time", "x", "y", "z", "roll", "pitch", "yaw", "u", "v", "w", "p", "q", "r")


def motion_path(run_dir_or_csv: str | Path) -> Path:
    """The motion CSV of a run directory (``<dir>/motion.csv``) or the CSV file itself."""
    path = Path(run_dir_or_csv)
    if path.is_dir():
        path = path / "motion.csv"
    if not path.is_file():
        raise InputError(f"motion series: {run_dir_or_csv!s} is neither a motion CSV nor a "
                         "directory holding motion.csv")
    return path


def read_motion(path: str | Path) -> dict[str, np.ndarray]:
    """Columns of a motion CSV as float arrays, keyed by the header's names.

    Non-numeric cells raise :class:`InputError`; ``nan``/``inf`` parse as floats and are left
    for the analysis to refuse (never silently dropped).
    """
    path = Path(path)
    with path.open(newline="") as handle:
        rows = [row for row in csv.reader(handle) if row and not row[0].lstrip().startswith("#")]
    if not rows:
        raise InputError(f"motion series: {path} is empty; expected the header "
                         f"{','.join(MOTION_COLUMNS)}")
    header = [name.strip() for name in rows[0]]
    if "time" not in header:
        raise InputError(f"motion series: {path} header {','.join(header)} has no 'time' "
                         f"column; expected {','.join(MOTION_COLUMNS)}")
    columns: dict[str, list[float]] = {name: [] for name in header}
    for line, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise InputError(f"motion series: {path} line {line} has {len(row)} fields, "
                             f"the header has {len(header)}")
        for name, cell in zip(header, row, strict=True):
            try:
                columns[name].append(float(cell))
            except ValueError:
                raise InputError(f"motion series: {path} line {line} column {name} = "
                                 f"{cell!r} is not a number") from None
    return {name: np.asarray(values, dtype=float) for name, values in columns.items()}


def dof_series(motion: dict[str, np.ndarray], dof: str) -> tuple[np.ndarray, np.ndarray]:
    """Time (s) and one degree of freedom (m for heave, radians for roll and pitch)."""
    entry = dof_named(dof)
    column = entry.column
    if column not in motion:
        raise InputError(f"motion series: no column {column!r} for dof {dof}; "
                         f"columns: {','.join(motion)}")
    return motion["time"], motion[column] * (math.pi / 180.0 if entry.is_angle else 1.0)


def file_unit(dof: str) -> tuple[float, str]:
    """Scale from code units to file units and the unit's name: (180/π, 'deg') for angles."""
    entry = dof_named(dof)
    return entry.file_scale, entry.unit


def write_motion(path: str | Path, time, **columns) -> Path:
    """Write a motion CSV with the standard header; missing columns are written as 0.

    Angles are given in degrees, as in the file (docs/conventions.md).
    """
    path = Path(path)
    time = np.asarray(time, dtype=float)
    table = np.zeros((time.size, len(MOTION_COLUMNS)))
    table[:, 0] = time
    for name, values in columns.items():
        if name not in MOTION_COLUMNS:
            raise InputError(f"motion column {name!r}; valid: {','.join(MOTION_COLUMNS)}")
        table[:, MOTION_COLUMNS.index(name)] = values
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savetxt(path, table, delimiter=",", header=",".join(MOTION_COLUMNS), comments="",
               fmt="%.10g")
    return path
