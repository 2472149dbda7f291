"""One table of period and damping per case: memoir, linear theory, potential flow, CFD, reference.

Rows, in this order, for each degree of freedom the case releases (``[release]`` heave, heel,
trim → heave, roll, pitch) or lists a reference for:

* **memoir formula**: Le Barbier's method, corrected (``theory_summary(case).memoir``), and
  **memoir as printed** (``.memoir_printed``, errata included);
* **linear theory (exact)**: the exact hydrostatic linear theory, undamped natural period;
* **potential flow**: added mass and radiation damping (when :mod:`floatfoam.potential.radiation` is
  available for the case);
* **Cummins' model**: Cummins' equation in the CFD body's free DoFs, with the exact restoring
  force where the release is large (:mod:`floatfoam.analysis.cummins`), its series over the
  CFD record's span put through the CFD's decay analysis; where it cannot be computed, the row
  says why;
* **CFD <level>**: each ``build/<case>/<level>/motion.csv``, through :func:`analyse_decay`.
  The period is the damped period T_d of the record (what a decay test measures; the natural
  period T_n = T_d √(1 − ζ²) is in the note) with its 95 % interval;
* **CFD fine ± U_num**: the fine level's value ± its numerical uncertainty (levels, time
  step and mesh motion), with the Richardson extrapolation in the note, when ``floatfoam
  validate`` has studied it;
* **reference**: the measured value of the case's ``[reference]`` table (value ± uncertainty);
  without a period or damping ratio there, the decay fit of its measured record
  (``<dof>_record``) over the CFD's record length (:func:`record_fit`);
* **<dof>, first 3 cycles**: when the reference gives the first cycles of a measured record
  (``<dof>_first_period``, ``_first_damping_ratio``, ``_first_trough``), each CFD record
  reduced the same way (:func:`floatfoam.analysis.extrema.crossing_reduction`), and, unless
  potential flow is left out, Cummins' model with the exact restoring force
  (:func:`potential_first_cycles`) too.

Two relative differences: Δ against Cummins' model (its first cycles' row beside the first
cycles), or, where it was not computed, against the exact linear theory (periods only: the theory
has no added mass and no damping; the row's basis says so); and Δ measured, against the
reference, where the case has one. A CFD record that cannot be analysed (NaN, too short, no
signal) gives a row with the reason, never a missing row.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from floatfoam import dofs
from floatfoam.analysis.comparison_table import THEORY, optional_float, table_row
from floatfoam.analysis.cummins import MODEL, ModelFit, ModelRecord, cummins_model, fit_model
from floatfoam.analysis.decay import DecayResult, analyse_decay
from floatfoam.analysis.extrema import crossing_reduction
from floatfoam.analysis.measured import record_fit, reference_entry
from floatfoam.analysis.runs import current_runs, stale_note
from floatfoam.analysis.settled import first_cycles, settled_level, theory_equilibrium
from floatfoam.analysis.uncertainty import current_study, fine_band
from floatfoam.errors import InputError
from floatfoam.hydrostatics.summary import TheorySummary
from floatfoam.motion import dof_series, file_unit, read_motion
from floatfoam.potential.summary import PotentialSummary

#: the first cycles' model row (:func:`potential_first_cycles`), their Δ's basis
FIRST_CYCLES_MODEL = "potential flow (Cummins, exact restoring)"


@dataclass
class CfdAnalysis:
    """A decay analysis of one CFD run, kept for the plots."""

    level: str
    dof: str
    time: object
    value: object
    result: DecayResult
    settled: float | None = None  # settled_level, where the physics gives it


@dataclass
class Comparison:
    """Rows of the comparison table, notes about omitted sources, the CFD analyses and
    Cummins' model's (by DoF, for the figures)."""

    case: str
    rows: list[dict] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    analyses: list[CfdAnalysis] = field(default_factory=list)
    models: dict[str, ModelFit] = field(default_factory=dict)
    foreign: list[str] = field(default_factory=list)  # runs left out: of other settings
    foreign_study: bool = False  # the study left out: made of runs of other settings
    study: dict | None = None  # the study of floatfoam validate, when of today's settings


def excited_dofs(case, reference: dict | None = None) -> list[str]:
    """DoFs the case releases from an offset, or has a reference period or damping for."""
    release = case.release
    reference = reference if reference is not None else (case.reference or {})
    moved = {d.name for d in dofs.released(release)}
    return [dof for dof in dofs.NAMES
            if dof in moved or f"{dof}_period" in reference or f"{dof}_damping_ratio" in reference]


def potential_first_cycles(case, dof: str, theory: TheorySummary):
    """Cummins' potential-flow model with the body's exact restoring force (`floatfoam
    decay-model CASE --model cummins --nonlinear-restoring`), its record of DoF ``dof`` reduced
    as a measured record's first cycles (:func:`crossing_reduction`) about the theory's
    equilibrium, where the model settles."""
    from floatfoam.potential.models import decay_series
    from floatfoam.potential.radiation import radiation_coefficients

    series = decay_series(case, "cummins", nonlinear_restoring=True,
                          coefficients=radiation_coefficients(case))
    return crossing_reduction(*dof_series(series, dof), level=theory_equilibrium(theory, dof))


def analyse_run(path: Path, dof: str, **options) -> tuple[object, object, DecayResult]:
    """Time, value (code units) and decay analysis of one DoF of a motion CSV."""
    time, value = dof_series(read_motion(path), dof)
    return time, value, analyse_decay(time, value, units=file_unit(dof),
                                      name=dofs.dof(dof).column, **options)


def _cfd_rows(case, dof, runs, theory, options) -> tuple[list[dict], list[CfdAnalysis]]:
    rows, analyses = [], []
    eq_theory = theory_equilibrium(theory, dof)
    scale, unit = file_unit(dof)
    for level, path in runs:
        source = f"CFD {level}"
        try:
            time, value, result = analyse_run(path, dof, **options)
        except InputError as err:
            rows.append(table_row(case.name, dof, source, note=f"analysis failed: {err}"))
            continue
        analyses.append(CfdAnalysis(level, dof, time, value, result,
                                    settled_level(case, dof, path.parent, theory)))
        s = result.summary()
        note = f"T_n {s['natural_period']:.4g} s; {s['n_cycles']:.2g} cycles"
        if eq_theory is not None:
            offset = (float(result.fit.mean_level(result.t_first)) - eq_theory) * scale
            note += f"; mean level {offset:+.3g} {unit} from the theory's equilibrium"
        rows.append(table_row(case.name, dof, source, s["period_mean"], s["period_ci95"],
                              s["damping_ratio"], s["damping_ratio_ci95"], note))
    return rows, analyses


def potential_flow(case) -> dict:
    """The default potential-flow source of the comparison:
    :func:`floatfoam.potential.radiation.potential_summary` of the case."""
    from floatfoam.potential.radiation import potential_summary

    return potential_summary(case)


def _potential(case, source, notes: list[str]) -> PotentialSummary | None:
    if source is None:
        notes.append("potential flow: not requested")
        return None
    try:
        summary = source(case)
    except (ImportError, AttributeError) as err:
        notes.append(f"potential flow: not available ({err})")
        return None
    except (InputError, NotImplementedError, RuntimeError) as err:
        notes.append(f"potential flow: not computed for this case ({err})")
        return None
    notes += [f"potential flow: {note}" for note in summary.notes]
    return summary


def memoir_label(source: str | None) -> str:
    """The memoir's row as ``floatfoam theory`` names it: "memoir (corrected)" for its method
    derived again (``source == "reconstructed"``: docs/memoir.md), else the source given."""
    if not source:
        return "memoir formula"
    return "memoir (corrected)" if source == "reconstructed" else f"memoir ({source})"


def _theory_rows(case, dof, theory, potential):
    rows = []
    memoir = theory.memoir or {}
    if memoir.get(f"{dof}_period") is not None:
        label = memoir_label(memoir.get("source"))
        rows.append(table_row(case.name, dof, label, float(memoir[f"{dof}_period"])))
    printed = theory.memoir_printed or {}
    if printed.get(f"{dof}_period") is not None:
        errata = "; ".join(printed.get("errata") or [])
        rows.append(table_row(case.name, dof, "memoir as printed", float(printed[f"{dof}_period"]),
                              note=f"errata: {errata}" if errata else "formulas right as printed"))
    period = theory.period(dof)
    note = "" if period is not None else f"no oscillation ({theory.dofs[dof].verdict or ''})"
    rows.append(table_row(case.name, dof, THEORY, period, note=note.strip()))
    flow = potential.dof(dof) if potential is not None else None
    if flow is not None and flow.period is not None:
        method = ", ".join(f"{value}{label}" for value, label in
                           ((potential.method, ""), (potential.panels, " panels")) if value)
        rows.append(table_row(case.name, dof, "potential flow", float(flow.period),
                              zeta=optional_float(flow.damping_ratio), note=method))
    if flow is not None and flow.coupled_period is not None:
        partner = dofs.PARTNER[dof]
        rows.append(table_row(case.name, dof, f"potential flow, {partner} free",
                              float(flow.coupled_period),
                              zeta=optional_float(flow.coupled_damping_ratio),
                              note=f"a free body, as in the CFD ({partner} follows the {dof})"))
    return rows


def _range(entry) -> list[float] | None:
    """[value − u, value + u] of a (value, uncertainty, ...) entry; None without uncertainty."""
    return None if entry is None or entry[1] is None else [entry[0] - entry[1],
                                                            entry[0] + entry[1]]


def _band_row(case, label, dof, study, keys) -> dict | None:
    """The fine level's value ± U_num (``floatfoam validate``) of the quantities ``keys``
    (period key, damping key or None), with the Richardson extrapolation in the note."""
    period, zeta = (fine_band(study, dof, k) if study and k else None for k in keys)
    if period is None and zeta is None:
        return None
    ext = "; ".join(f"extrapolated {name} {b[2]:.5g}" for name, b in (("T", period),
                                                                       ("ζ", zeta))
                    if b is not None and b[2] is not None)
    return table_row(case.name, label, "CFD fine ± U_num", period and period[0], _range(period),
                     zeta and zeta[0], _range(zeta),
                     "; ".join(filter(None, ("grid and time-step study (floatfoam validate)",
                                             ext))))


def _first_cycle_rows(case, dof, analyses, reference, study, model: Callable | None,
                      notes: list[str]) -> list[dict]:
    """The first cycles of each CFD record reduced as the case's reference reduces its
    measurements (:func:`first_cycles`: the first period from the first trough's zero
    crossings, ζ over the first six extrema, the first trough), beside ``[reference]
    <dof>_first_period``, ``<dof>_first_damping_ratio`` and ``<dof>_first_trough`` — only
    when the reference has them — and ``model`` (case, dof → a :func:`crossing_reduction`
    result: :func:`potential_first_cycles`; None leaves it out) beside them."""
    keys = [f"{dof}_first_{k}" for k in ("period", "damping_ratio", "trough")]
    period, zeta, trough = (reference_entry(reference, k) for k in keys)
    if period is None and zeta is None:
        return []
    label, (scale, unit) = f"{dof}, first 3 cycles", file_unit(dof)
    rows = []
    if model is not None:
        try:
            r = model(case, dof)
        except (ImportError, InputError, ValueError, NotImplementedError, RuntimeError) as err:
            notes.append(f"potential flow, {label}: not computed ({err})")
        else:
            rows.append(table_row(case.name, label, FIRST_CYCLES_MODEL,
                                  r.first_period, zeta=r.damping_ratio,
                                  note=f"first trough {r.first_trough * scale:.4g} {unit}; "
                                  "decay-model --model cummins --nonlinear-restoring"))
    for run in analyses:
        try:
            r = first_cycles(run.time, run.value, run.result, run.settled)
        except ValueError as err:
            rows.append(table_row(case.name, label, f"CFD {run.level}",
                                  note=f"analysis failed: {err}"))
            continue
        rows.append(table_row(case.name, label, f"CFD {run.level}", r.first_period,
                              zeta=r.damping_ratio,
                              note=f"first trough {r.first_trough * scale:.4g} {unit}"))
    band = _band_row(case, label, dof, study, ("first_period", "first_damping_ratio"))
    rows += [band] if band else []
    notes = [f"first trough {trough[0] * scale:.4g} {unit}"
             + (f" ± {trough[1] * scale:.2g}" if trough[1] else "")] if trough else []
    sources = sorted({e[2] for e in (period, zeta, trough) if e is not None and e[2]})
    rows.append(table_row(case.name, label, "reference", period and period[0], _range(period),
                          zeta and zeta[0], _range(zeta), "; ".join(notes + sources)))
    _relative_differences(rows, FIRST_CYCLES_MODEL)
    return rows


def _reference_row(case, dof, reference, window: float | None = None,
                   options: dict | None = None):
    """The ``[reference]`` period and damping ratio of ``dof``; without them, the decay fit of
    the case's measured record (:func:`record_fit`) over ``window`` s from the release."""
    period = reference_entry(reference, f"{dof}_period")
    zeta = reference_entry(reference, f"{dof}_damping_ratio")
    if period is None and zeta is None:
        return record_fit(case, dof, window, options)

    sources = sorted({e[2] for e in (period, zeta) if e is not None and e[2]})
    return table_row(case.name, dof, "reference", period[0] if period else None, _range(period),
                     zeta[0] if zeta else None, _range(zeta), "; ".join(sources))


def _relative_differences(rows: list[dict], model: str = MODEL) -> None:
    """Fill the relative differences of ``rows`` (one DoF's): period_rel_diff and
    damping_rel_diff against the row of ``model``, else — the model not computed — the period
    against the linear theory's; period_rel_diff_measured and damping_rel_diff_measured against
    the reference. Each row's basis names what it was set against."""
    by_source = {r["source"]: r for r in rows}
    bases = (("", by_source.get(model), by_source.get(THEORY)),
             ("_measured", by_source.get("reference"), None))
    for suffix, first, fallback in bases:
        for key, what in (("period", "Δ period"), ("damping_ratio", "Δ ζ")):
            base = first if first is not None and first[key] else None
            if base is None and key == "period" and fallback is not None and fallback[key]:
                base = fallback
            if base is None:
                continue
            diff_key = ("period" if key == "period" else "damping") + "_rel_diff" + suffix
            for row in rows:
                if row is not base and row[key] is not None:
                    row[diff_key] = row[key] / base[key] - 1.0
                    row["basis"] = "; ".join(filter(None, (row["basis"],
                                                           f"{what} vs {base['source']}")))


def _model(case, model: Callable, window: float | None, notes: list[str]
           ) -> ModelRecord | str:
    """Cummins' model of ``case`` over ``window`` s (``model``: :func:`cummins_model`), or why
    it was not computed, in words."""
    try:
        return model(case, window)
    except (ImportError, InputError, NotImplementedError, RuntimeError, ValueError) as err:
        why = str(err).splitlines()[0] if str(err) else type(err).__name__
        notes.append(f"{MODEL}: not computed ({why})")
        return why


def _model_row(case, dof: str, record: ModelRecord | str, options: dict,
               window: float | None, models: dict[str, ModelFit]) -> dict:
    """The row of Cummins' model in ``dof``, its fit kept in ``models`` for the figure; a row
    with the reason when the model was not computed or its series cannot be analysed.
    ``window``: the CFD record's span the model was computed over (None: no CFD record)."""
    if isinstance(record, str):
        return table_row(case.name, dof, MODEL, note=f"not computed: {record}")
    try:
        fit = fit_model(record, case, dof, **options)
    except InputError as err:
        return table_row(case.name, dof, MODEL, note=f"analysis failed: {err}; {record.note()}")
    models[dof] = fit
    s = fit.result.summary()
    span = f"{float(fit.time[-1]):.3g} s"
    span = f"fitted over {span}, as the CFD's record" if window else \
        f"fitted over {span} (no CFD record to match)"
    return table_row(case.name, dof, MODEL, s["period_mean"], zeta=s["damping_ratio"],
                     note=f"T_n {s['natural_period']:.4g} s; {span}; {record.note()}")


def compare_case(case, *, build_dir: str | Path, theory: TheorySummary | None = None,
                 potential: Callable | None = potential_flow,
                 potential_cycles: Callable | None = potential_first_cycles,
                 model: Callable | None = cummins_model,
                 analysis_options: dict | None = None) -> Comparison:
    """The comparison table of one case (see the module docstring for the rows).

    ``theory`` is :func:`~floatfoam.hydrostatics.theory.theory_summary` of the case
    (computed when None); ``potential`` gives the potential-flow summary of a case (default
    :func:`potential_flow`; None leaves potential flow out, and its first cycles and Cummins'
    model with it); ``potential_cycles`` (case, dof, theory) the potential flow's first cycles
    beside a reference's (default :func:`potential_first_cycles`; None leaves them out);
    ``model`` (case, duration → :class:`~floatfoam.analysis.cummins.ModelRecord`) Cummins'
    model over the CFD record's span, the Δ columns' basis (default
    :func:`~floatfoam.analysis.cummins.cummins_model`; None leaves it out);
    ``analysis_options`` go to :func:`analyse_decay` (e.g. ``{"drift": True}``).
    """
    if theory is None:
        from floatfoam.hydrostatics.theory import theory_summary

        theory = theory_summary(case)
    reference = case.reference or {}
    comparison = Comparison(case.name)
    cycles_wanted = potential is not None and potential_cycles is not None
    model_wanted = potential is not None and model is not None
    potential = _potential(case, potential, comparison.notes)
    record = None if potential is not None else "no potential flow (the notes say why)"
    runs, comparison.foreign = current_runs(case, build_dir)
    if comparison.foreign:
        comparison.notes.append(stale_note(case.name, comparison.foreign))
    elif not runs:
        comparison.notes.append(f"CFD: no run yet (no {Path(build_dir, case.name)}/*/motion.csv)")
    study, stale = current_study(case, Path(build_dir))
    comparison.study, comparison.foreign_study = study, bool(stale)
    if stale:
        comparison.notes.append(stale_note(case.name, stale, study=True))
    for dof in excited_dofs(case, reference):
        rows = _theory_rows(case, dof, theory, potential)
        cfd_rows, analyses = _cfd_rows(case, dof, runs, theory, analysis_options or {})
        rows += cfd_rows
        band = _band_row(case, dof, dof, study, ("period", "damping_ratio"))
        rows += [band] if band else []
        comparison.analyses += analyses
        window = max((float(a.time[-1]) for a in analyses), default=None)
        if model_wanted:  # once, over the first DoF's CFD span (every DoF's is the same)
            record = record or _model(case, model, window, comparison.notes)
            rows.insert(len(rows) - len(cfd_rows) - bool(band),
                        _model_row(case, dof, record, analysis_options or {}, window,
                                   comparison.models))
        ref_row = _reference_row(case, dof, reference, window, analysis_options)
        if ref_row is not None:
            rows.append(ref_row)
        _relative_differences(rows)
        comparison.rows += rows
        cycles = (lambda c, d: potential_cycles(c, d, theory)) if cycles_wanted else None
        comparison.rows += _first_cycle_rows(case, dof, analyses, reference, study, cycles,
                                             comparison.notes)
    return comparison


