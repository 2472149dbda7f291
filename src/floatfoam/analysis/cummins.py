"""Cummins' model beside the CFD: the best model of a free decay the project has.

Cummins (1962) with the potential flow's A∞ and radiation memory
(:func:`floatfoam.potential.models.decay_series`, ``floatfoam decay-model --model cummins``),
solved in the DoFs the CFD body is free in (:func:`floatfoam.dofs.free_dofs`: the case's
``[motion] free``, else sway follows a roll, surge a pitch), with the exact hydrostatic restoring
force where the release is large (:data:`~floatfoam.potential.models.LARGE_RELEASE`), else C x. Its
series is analysed as a CFD record is (:func:`~floatfoam.analysis.decay.analyse_decay`, the same
options, over the CFD record's span), so that its T_d and ζ are the ones the CFD's are set against:
the comparison's Δ columns (:mod:`floatfoam.analysis.compare`) and the decay figure
(:mod:`floatfoam.analysis.plots`). The linear theory (no added mass, no damping) stays beside them
as a row and a thin line.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from floatfoam import dofs
from floatfoam.analysis.decay import DecayResult, analyse_decay
from floatfoam.motion import dof_series, file_unit

#: the model's source in the comparison table and its name in the decay figure's legend
MODEL = "Cummins' model"


@dataclass(frozen=True)
class ModelRecord:
    """Cummins' model of a case: its series (motion-CSV columns, file units), the DoFs it
    solved, whether its restoring force is the exact one, and how far the linear one is off
    at the release (:func:`~floatfoam.potential.models.linear_restoring_error`)."""

    series: dict
    solved: tuple[str, ...]
    exact_restoring: bool
    restoring_error: float

    @property
    def label(self) -> str:
        """E.g. "Cummins' model (heave, roll, sway free; exact restoring)"."""
        restoring = "exact restoring" if self.exact_restoring else "linear restoring"
        return f"{MODEL} ({', '.join(self.solved)} free; {restoring})"

    def note(self) -> str:
        """How the model was made, in words for the comparison table."""
        error = f"{100 * self.restoring_error:.2g} %"
        restoring = f"exact restoring (C x is {error} off it at the release)" \
            if self.exact_restoring else f"restoring C x (within {error} of the exact)"
        return (f"A∞ and radiation memory of the potential flow; {', '.join(self.solved)} free, "
                f"as the CFD body; {restoring}; decay-model --model cummins")


@dataclass(frozen=True)
class ModelFit:
    """One DoF of a :class:`ModelRecord` analysed as the CFD records are: time (s), value
    (code units, as a CFD record's), offset from the model's equilibrium (file units, as a
    measured record's), its decay analysis and its legend label."""

    dof: str
    time: np.ndarray
    value: np.ndarray
    offset: np.ndarray
    result: DecayResult
    label: str


def cummins_model(case, duration: float | None = None, *, coefficients=None) -> ModelRecord:
    """Cummins' model of ``case`` in the DoFs its CFD body is free in, ``duration`` s long
    (None: :func:`~floatfoam.potential.models.decay_series`'s ten longest periods), with the
    exact restoring force where :func:`~floatfoam.potential.models.linear_restoring_error`
    exceeds :data:`~floatfoam.potential.models.LARGE_RELEASE`.

    ``coefficients``: the radiation coefficients (computed, or read from build/potential,
    when None). Raises InputError (a release that capsizes, a DoF the potential flow does not
    solve, a duration out of bounds), ImportError without Capytaine for a 3D body, and what
    the potential flow raises for a body it cannot solve.
    """
    from floatfoam.potential.models import LARGE_RELEASE, decay_series, linear_restoring_error

    error = linear_restoring_error(case)
    exact = error > LARGE_RELEASE
    series = decay_series(case, "cummins", duration=duration, nonlinear_restoring=exact,
                          coefficients=coefficients)
    return ModelRecord(series, tuple(series["dofs"]), exact, error)


def fit_model(record: ModelRecord, case, dof: str, **options) -> ModelFit:
    """DoF ``dof`` of ``record`` through the decay analysis the CFD records go through
    (``options`` as theirs, e.g. ``drift``). Its offset is taken from the model's equilibrium:
    the first sample less the release (the model starts from rest at the release). Raises
    InputError when the series cannot be analysed (too few cycles, a DoF that does not move)."""
    time, value = dof_series(record.series, dof)
    scale, _ = file_unit(dof)
    entry = dofs.dof(dof)
    release = float((case.release or {}).get(entry.release_key, 0.0) or 0.0)
    offset = value * scale - (value[0] * scale - release)
    result = analyse_decay(time, value, units=file_unit(dof), name=entry.column, **options)
    return ModelFit(dof, time, value, offset, result, record.label)
