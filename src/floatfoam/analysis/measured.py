"""A measured decay record beside a case (``[reference] <dof>_record``): read, checked, and
put through the decay fit the CFD records go through.

The record is a CSV beside case.toml (a header line, then time from the release in s and the
DoF's offset from its equilibrium in file units: m, or degrees for an angle); how it was
obtained is in the case's README. A benchmark often reduces only the first cycles of its
records (:mod:`floatfoam.analysis.extrema`); the fit here gives their later periods and
damping, over the same span as the CFD's record so that both fit the same cycles.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from floatfoam import dofs
from floatfoam.analysis.comparison_table import optional_float, table_row
from floatfoam.analysis.decay import DecayResult, analyse_decay
from floatfoam.errors import InputError
from floatfoam.motion import file_unit


@dataclass(frozen=True)
class MeasuredRecord:
    """A measured decay record beside the case (``[reference] <dof>_record``): time from the
    release (s) and the DoF's offset from its equilibrium (m or deg), as the file gives them."""

    time: np.ndarray
    offset: np.ndarray
    source: str
    path: Path

    def after_release(self, window: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Time and offset from the release (t ≥ 0) to ``window`` s (None: the whole record)."""
        keep = (self.time >= 0.0) & (self.time <= (np.inf if window is None else window))
        return self.time[keep], self.offset[keep]


def reference_record(case, dof: str) -> MeasuredRecord | None:
    """The measured record of ``dof`` named by ``[reference] <dof>_record = { file, source }``
    (a CSV beside case.toml: a header line, then time from the release and offset from the
    equilibrium; samples before the release, at negative times, are kept); None without one.
    Raises InputError naming the key when the file is missing or not such a series."""
    key = f"{dof}_record"
    entry = (case.reference or {}).get(key)  # its table and file checked by load_case
    if entry is None:
        return None
    path = Path(case.path) / entry["file"]
    try:
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except (OSError, ValueError) as err:
        raise InputError(f"reference.{key}: {path} could not be read ({err}); valid is a CSV "
                         "with a header line and two columns: time (s), offset") from None
    if data.shape[1] != 2 or np.count_nonzero(data[:, 0] >= 0.0) < 3 \
            or not np.all(np.diff(data[:, 0]) > 0) or not np.all(np.isfinite(data)):
        raise InputError(f"reference.{key}: {path} is not a record; valid is a CSV with two "
                         "finite columns, time (s) increasing with at least 3 samples from "
                         "the release (t ≥ 0), and the offset")
    return MeasuredRecord(data[:, 0], data[:, 1], str(entry.get("source", "")), path)


def fit_record(record: MeasuredRecord, dof: str, window: float | None = None,
               **options) -> tuple[DecayResult, float]:
    """The record's decay fit (:func:`~floatfoam.analysis.decay.analyse_decay`, with the
    CFD's ``options``) from the release to ``window`` s, in code units, and the span it
    covers (s: shorter than ``window`` when the record is). Raises InputError when the span
    cannot be fitted."""
    time, offset = record.after_release(window)
    scale, _ = file_unit(dof)
    result = analyse_decay(time, offset / scale, units=file_unit(dof),
                           name=dofs.dof(dof).column, **options)
    return result, float(time[-1])


def reference_entry(reference: dict, key: str) -> tuple[float, float | None, str] | None:
    """(value, uncertainty, source) of a ``[reference]`` entry: a table or a bare number."""
    entry = reference.get(key)
    if entry is None:
        return None
    if isinstance(entry, dict):
        value = entry.get("value")
        if value is None:
            raise InputError(f"reference.{key} has no 'value'; valid is a number or a table "
                             "with value, uncertainty, source")
        return float(value), optional_float(entry.get("uncertainty")), str(entry.get("source", ""))
    return float(entry), None, ""


def record_fit(case, dof: str, window: float | None = None, options: dict | None = None
               ) -> dict | None:
    """The case's measured record of ``dof`` (:mod:`floatfoam.analysis.measured`) through the
    decay fit the CFD records go through (``options`` as theirs), from the release to
    ``window`` s (the longest CFD record, so that both fit the same cycles; None: all of it),
    as the reference row: its later periods and damping beside the first cycles'
    reduction. The interval is the fit's 95 % one on this one record, not the spread between
    repeated drops. None without a record; a row with the reason when the record cannot be
    read or fitted."""
    entry = (case.reference or {}).get(f"{dof}_record")
    if entry is None:
        return None
    what = f"decay fit of the measured record ({entry.get('source', '')})"
    try:
        record = reference_record(case, dof)
        result, span = fit_record(record, dof, window, **(options or {}))
    except InputError as err:
        return table_row(case.name, dof, "reference", note=f"{what}: not fitted ({err})")
    if window is None:
        extent = f"all of it ({span:.3g} s; no CFD record to match)"
    elif span < window - 1e-9:
        extent = f"all of it ({span:.3g} s), shorter than the CFD's {window:.3g} s"
    else:
        extent = f"its first {span:.3g} s, as the CFD's record"
    s = result.summary()
    return table_row(case.name, dof, "reference", s["period_mean"], s["period_ci95"],
                     s["damping_ratio"], s["damping_ratio_ci95"],
                     f"{what}, {extent}; {s['n_cycles']:.2g} cycles; 95 % interval of the fit "
                     "on this one record")
