"""What a decay figure sets beside a CFD record (:class:`floatfoam.analysis.plots.Overlay`):
Cummins' model (:mod:`floatfoam.analysis.cummins`), the case's measured record and reference,
and the linear theory — for the report's figures and for ``floatfoam analyse --plot`` on a
run folder.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from floatfoam import dofs, layout
from floatfoam.analysis.cummins import ModelFit, cummins_model, fit_model
from floatfoam.analysis.measured import reference_entry, reference_record
from floatfoam.analysis.plots import Overlay
from floatfoam.analysis.settled import theory_equilibrium
from floatfoam.errors import InputError
from floatfoam.hydrostatics.summary import TheorySummary
from floatfoam.motion import file_unit


def decay_overlay(case, theory: TheorySummary, dof: str, model: ModelFit | None = None
                  ) -> Overlay:
    """The overlay of DoF ``dof`` of ``case``: Cummins' model's fit ``model`` (None: not
    drawn), the measured record and reference of its ``[reference]``, its release and the
    linear theory's period and equilibrium."""
    scale, _ = file_unit(dof)
    eq = theory_equilibrium(theory, dof)
    release = (getattr(case, "release", None) or {}).get(dofs.dof(dof).release_key)
    reference = case.reference or {}
    period = reference_entry(reference, f"{dof}_period")
    zeta = reference_entry(reference, f"{dof}_damping_ratio")
    sources = sorted({e[2] for e in (period, zeta) if e and e[2]})
    measured = reference_record(case, dof)
    label = ""
    if measured is not None:
        first = measured.offset[np.searchsorted(measured.time, 0.0)]  # file units already
        label = f"measured ({measured.source}; released {first:.4g} {file_unit(dof)[1]})"
    summary = model.result.summary() if model is not None else {}
    return Overlay(theory_period=theory.period(dof),
                   equilibrium=None if eq is None else eq * scale,
                   release=None if release is None else float(release),
                   reference_period=period[0] if period else None,
                   reference_damping=zeta[0] if zeta else None,
                   reference_source=f"({'; '.join(sources)})" if sources else "",
                   measured_time=None if measured is None else measured.time,
                   measured_offset=None if measured is None else measured.offset,
                   measured_label=label,
                   model_time=None if model is None else model.time,
                   model_offset=None if model is None else model.offset,
                   model_label="" if model is None else model.label,
                   model_period=summary.get("period_mean"),
                   model_damping=summary.get("damping_ratio"))


def _case_folder(run: Path) -> Path:
    """The folder of the case a run was made of: the one its info.json names (any case's),
    else cases/<the run's case folder name> (a run recorded before info.json named it, or
    a case folder that has moved since)."""
    from floatfoam.plan.record import RunRecord, record_or_none

    named = (record_or_none(run) or RunRecord()).case_path
    if named and (Path(named) / "case.toml").is_file():
        return Path(named)
    return layout.CASES_DIR / run.parent.name  # a moved folder, or a built-in case's run


def run_overlay(run: Path, dof: str, duration: float, **options) -> tuple[Overlay | None, str]:
    """The overlay of a run folder ``<build>/<case>/<run>`` of a case (the folder its
    info.json names, else cases/), as the report draws it, with Cummins' model over
    ``duration`` s analysed with ``options`` (the record's), and "" — or (None, why) where
    there is none: a folder of no case on this machine, a run made with other settings than
    the case's today (its model would be another body's); the overlay without the model, and
    why, where the model cannot be computed."""
    from floatfoam.case import load_case
    from floatfoam.hydrostatics.theory import theory_summary
    from floatfoam.plan.stamps import stamped_with

    folder = _case_folder(run)
    if not (folder / "case.toml").is_file():
        return None, (f"{run} is no run of a case this machine has (no {folder / 'case.toml'})")
    try:
        case = load_case(str(folder))
        level, divisor, morphing = layout.parse_run_name(run.name)
    except InputError as err:
        return None, f"{folder.name} could not be loaded ({err})"
    except ValueError:
        level = ""
    if level not in layout.LEVELS:
        return None, f"{run} is no run folder of floatfoam's (<level>[-dtK][-morphF])"
    if stamped_with(case, level, run, divisor, morphing) is False:
        return None, (f"{run} was made with other settings than {case.name}'s today (its case "
                      "file, a --set or a default)")
    theory = theory_summary(case)
    try:
        model = fit_model(cummins_model(case, duration), case, dof, **options)
    except (ImportError, InputError, NotImplementedError, RuntimeError, ValueError) as err:
        return decay_overlay(case, theory, dof), \
            f"Cummins' model not computed ({str(err).splitlines()[0]})"
    return decay_overlay(case, theory, dof, model), ""
