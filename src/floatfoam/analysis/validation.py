"""Verification of a case's CFD: grid and time-step convergence of its period and damping.

``floatfoam validate CASE`` runs the case at the three mesh levels, once more at the medium
level with its time steps halved and once more at the coarse level with its mesh motion spread
wider (:func:`plan`; ``--no-morphing`` leaves the last out); this module analyses them. For
each DoF the release excites and each quantity (:data:`QUANTITIES`: the damped period and
damping ratio of the whole record's fit, and the first cycles as a basin reduces its records,
:func:`floatfoam.analysis.extrema.crossing_reduction` — the first period, twice the first
trough's time between zero crossings, ζ of the first six extrema and the first trough —, each
beside the case's ``[reference]`` measurement of it where there is one; the whole record's T_d
and ζ beside its measured record's decay fit over the same span where the reference gives only
the record, :func:`floatfoam.analysis.measured.record_fit`) it gives

* the study of Celik et al. (2008) on coarse, medium, fine (:mod:`floatfoam.analysis.gci`:
  observed order, Richardson extrapolation, GCI_fine — or the word for how it fails to
  converge), the cell size of each level from its cell count (their eq. 1: d = 2 for a slab or
  a wedge one cell thick, 3 in 3D). The levels keep the Courant limit and divide the largest
  time step by the level's factor, so they refine space **and** time together: a space-time
  GCI, in which spatial and temporal errors of opposite signs can cancel;
* the time-step study: the medium level against the same with its time steps halved, Roache's
  two-grid GCI of the medium level's own step with the formal order of the time scheme: 1 for
  the Euler scheme of cases/_common/system/fvSchemes, 2 for ``run.time_scheme =
  "CrankNicolson 1"`` (:func:`time_order`). It is taken for the fine level's time error, expected
  to be conservative: the fine level's steps are never longer than the medium's (same Courant
  limit on smaller cells, largest step divided by the level factor), and a first-order error
  shrinks with the step — if its constant is about the same on both meshes. Halving the
  medium level costs about a quarter of halving the fine one, which takes 62 % of a whole study
  (cylinder_heave: 1705 of 2736 s wall on 2 ranks); ``--time-level fine`` halves the fine
  level itself;
* the mesh-motion study: the coarse level once more with its mesh motion spread wider
  (``--morphing F``, :data:`DEFAULT_MORPHING` by default;
  :func:`floatfoam.plan.morphing.scaled_morphing`): the six-DoF solver's distances times F,
  the Laplacian's diffusivity 1/d instead of 1/d², or the layered motion's rows that move with
  the body over F × its height. The mesh motion is the same on every level,
  so neither GCI sees it; on the laboratory sphere the distances moved the damping more than
  the levels did. U_motion is the whole relative change of each quantity between the two
  runs: a change that does not shrink with the levels is not refined away, so it is taken
  whole;
* the numerical uncertainty of the fine level's solution, U_num = √(GCI_levels² + GCI_time² +
  U_motion²) (taken as independent, the root-sum-square of ITTC 7.5-03-01-01 (2017), the
  procedure for uncertainty analysis in CFD verification and validation; conservative, since
  the levels already hold part of the time error); without the mesh-motion run
  (``--no-morphing``, or it did not finish) U_num = √(GCI_levels² + GCI_time²) and the study
  says the mesh motion was not studied. Where the levels' observed order is beyond twice the
  schemes' second order, their GCI is flagged and U_num takes the fine pair's two-grid GCI at
  second order with F_s = 3 instead; where they have no observed order (they diverge, or
  converge without one), three times their whole spread, F_s = 3 on the largest difference
  between them (:func:`levels_gci`): the study still says how they behave.

Written to ``<build>/<case>/validation/`` by :func:`floatfoam.analysis.study_tables.write_study`:
``validation.json`` (every number), ``validation.md`` (the table) and ``convergence.png`` (each
quantity against the cell size, with the extrapolated value and the GCI band); ``floatfoam
report`` gathers them. The schemes' formal orders: :mod:`floatfoam.analysis.orders`.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from floatfoam import layout
from floatfoam.analysis import gci
from floatfoam.analysis.compare import analyse_run, excited_dofs
from floatfoam.analysis.measured import record_fit, reference_entry
from floatfoam.analysis.orders import FORMAL_ORDER, TIME_ORDER, time_order
from floatfoam.analysis.settled import first_cycles, settled_level
from floatfoam.analysis.uncertainty import STUDY_FILE
from floatfoam.errors import InputError
from floatfoam.hydrostatics.theory import theory_summary
from floatfoam.plan.record import RunRecord, record_or_none

TIME_STEP_DIVISOR = 2
#: the level whose time steps are halved by default (module docstring: why); "fine" gives the
#: fine level's own time error, for about four times that run's cost
TIME_STEP_LEVEL = "medium"
TIME_STEP_LEVELS = ("medium", "fine")


#: the level run once more with its mesh motion spread wider: the cheapest, since the mesh
#: motion's effect is to be compared with the levels', not refined
MORPHING_LEVEL = "coarse"
#: the factor of the mesh-motion run (the distances × 1.5; any factor > 1 gives the Laplacian
#: its 1/d): the one the cases' studies were made with (make validate MORPHING=1.5)
DEFAULT_MORPHING = 1.5
#: what the study says of a mesh motion it did not vary
NOT_STUDIED = "mesh motion not studied"


def plan(time_level: str = TIME_STEP_LEVEL,
         morphing: float | None = DEFAULT_MORPHING) -> tuple[tuple[str, int, float], ...]:
    """(mesh level, time-step divisor, morphing factor) of the study's runs, in the order they
    are run: the three levels, the halved time steps, and the mesh motion spread by
    ``morphing`` (None: no such run, ``--no-morphing``)."""
    if time_level not in TIME_STEP_LEVELS:
        raise InputError(f"--time-level {time_level!r} is not a level whose time steps a "
                         "study halves; valid: " + ", ".join(TIME_STEP_LEVELS))
    if morphing is not None:
        from floatfoam.plan.morphing import check_morphing

        check_morphing(morphing, study=True)
    runs = (("coarse", 1, 1.0), ("medium", 1, 1.0), ("fine", 1, 1.0),
            (time_level, TIME_STEP_DIVISOR, 1.0))
    return runs if morphing is None else (*runs, (MORPHING_LEVEL, 1, float(morphing)))


#: key, label, unit of each quantity of the study
QUANTITIES = (("period", "damped period T_d (whole record)", "s"),
              ("first_period", "first period (first trough's crossings)", "s"),
              ("damping_ratio", "damping ratio ζ", ""),
              ("first_damping_ratio", "ζ of the first 6 extrema", ""),
              ("first_trough", "first trough below the settled level", "m or rad"))


@dataclass
class RunValues:
    """One run of the study: its folder name, cells, and the quantities of one DoF."""

    name: str
    cells: int | None
    dimension: int
    divisor: int = 1  # of the level's time steps
    morphing: float = 1.0  # factor of the mesh motion (morphing.scaled_morphing)
    values: dict = field(default_factory=dict)  # key of QUANTITIES → value (None: failed)
    note: str = ""
    span: float | None = None  # s: the record's length from the release


def study_runs(case, build: Path, time_level: str = TIME_STEP_LEVEL,
               morphing: float | None = DEFAULT_MORPHING) -> list[tuple[str, int, float, Path]]:
    """(name, time-step divisor, morphing factor, run directory) of the study's runs that are
    finished. Raises InputError when one was run with other settings than ``case``'s (its case
    file and ``--set``): the study, its time order among them, is of one set of settings."""
    from floatfoam.plan.stamps import stamped_with

    out = []
    for level, divisor, factor in plan(time_level, morphing):
        run = layout.run_dir(case.name, level, build, time_step_divisor=divisor,
                             morphing=factor)
        if layout.is_finished(run) and (run / "motion.csv").is_file():
            if stamped_with(case, level, run, divisor, factor) is False:
                raise InputError(f"{run} holds a run of other settings than this command's "
                                 "(case file, --set); valid: the settings it was run with")
            out.append((layout.run_name(level, divisor, factor), divisor, factor, run))
    return out


def study_morphing(case_name: str, build: Path, given: float | None = None, *,
                   skip: bool = False) -> float | None:
    """The factor of a study's mesh-motion run: None with ``--no-morphing`` (``skip``), else
    ``given`` (``--morphing F``), else that of the study already written for the case when its
    run is still finished (:func:`finished_morphing`), else :data:`DEFAULT_MORPHING`."""
    if skip:
        return None
    if given is not None:
        return given
    written = finished_morphing(case_name, build)
    return DEFAULT_MORPHING if written is None else written


def finished_morphing(case_name: str, build: Path) -> float | None:
    """The morphing factor of the study already written for a case, when its run is still
    finished there, or None: a study made again without ``--morphing`` keeps the mesh-motion
    run it had (not whichever ``floatfoam run --morphing`` finished last)."""
    path = layout.case_build_dir(case_name, build) / "validation" / STUDY_FILE
    try:
        factor = json.loads(path.read_text()).get("morphing")
    except (OSError, ValueError):
        return None
    if not isinstance(factor, (int, float)) or isinstance(factor, bool):
        return None
    run = layout.run_dir(case_name, MORPHING_LEVEL, build, morphing=float(factor))
    return float(factor) if layout.is_finished(run) else None


def _run_values(name: str, divisor: int, run: Path, dof: str,
                morphing: float = 1.0, settled: float | None = None) -> RunValues:
    info = record_or_none(run) or RunRecord()  # what the driver recorded, when it did
    dimension = 3 if str(info.mesh or "").startswith("3d") else 2
    out = RunValues(name, info.cells, dimension, divisor, morphing)
    try:
        time, value, result = analyse_run(run / "motion.csv", dof)
    except InputError as err:
        out.note = f"analysis failed: {err}"
        out.values = dict.fromkeys(k for k, _, _ in QUANTITIES)
        return out
    s = result.summary()
    try:
        first = first_cycles(time, value, result, settled)
    except ValueError:  # fewer than six extrema
        first = None
    out.values = {"period": s["period_mean"], "damping_ratio": s["damping_ratio"],
                  "first_period": first.first_period if first else None,
                  "first_damping_ratio": first.damping_ratio if first else None,
                  "first_trough": first.first_trough if first else None}
    out.note = f"{s['n_cycles']:.1f} cycles"
    out.span = float(time[-1])
    return out


def grid_study(runs: dict[str, RunValues], key: str) -> gci.GridConvergence | str:
    """Celik et al.'s procedure on one quantity; a sentence when it cannot be applied."""
    levels = [runs.get(level) for level in ("fine", "medium", "coarse")]
    if any(r is None for r in levels):
        return "needs the three levels finished"
    values = [r.values.get(key) for r in levels]
    if any(v is None or not math.isfinite(v) for v in values):
        return "a level's record could not be analysed"
    if any(not r.cells for r in levels):
        return "a level's cell count is unknown"
    h = [gci.cell_size(r.cells, r.dimension) for r in levels]
    if not (h[0] < h[1] < h[2]):
        return f"the cell sizes do not grow from fine to coarse ({h})"
    return gci.three_grids(*values, h[1] / h[0], h[2] / h[1])


def time_study(runs: dict[str, RunValues], key: str, time_level: str = TIME_STEP_LEVEL,
               hint: str = "", order: float = TIME_ORDER) -> gci.TwoLevel | str:
    """``time_level`` against its halved time steps (two_level's "fine" is the halved run),
    at the time scheme's formal ``order``."""
    level = runs.get(time_level)
    halved = runs.get(layout.run_name(time_level, TIME_STEP_DIVISOR))
    if level is None or halved is None:
        return f"needs the {time_level} level and its halved time step finished{hint}"
    a, b = halved.values.get(key), level.values.get(key)
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
        return "a record could not be analysed"
    return gci.two_level(a, b, TIME_STEP_DIVISOR, order)


def morphing_study(runs: dict[str, RunValues], key: str, factor: float | None) -> dict:
    """The coarse level against the same with its mesh motion spread by ``factor``: both
    values and the relative change (the varied run's minus the case's, over the case's)."""
    if factor is None:
        return {"note": f"{NOT_STUDIED} (floatfoam validate --no-morphing)"}
    base = runs.get(MORPHING_LEVEL)
    name = layout.run_name(MORPHING_LEVEL, 1, factor)
    scaled = runs.get(name)
    if base is None or scaled is None:
        return {"factor": factor, "note": f"{NOT_STUDIED}: needs {MORPHING_LEVEL} and {name} "
                "finished"}
    a, b = base.values.get(key), scaled.values.get(key)
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)) or a == 0:
        return {"factor": factor, "note": "a record could not be analysed"}
    return {"factor": factor, "values": [a, b], "relative_change": (b - a) / a}


def numerical_uncertainty(grid, time, motion: float | None = None) -> float | None:
    """U_num = √(GCI_grid² + GCI_time² + U_motion²) of the fine level's solution, a fraction;
    None when a GCI is unknown. GCI_time is the halved level's own step (the coarser of the
    time pair, Roache's GCI_coarse), taken for the fine level's; U_motion (``motion``,
    :func:`motion_uncertainty`) is left out when None: the mesh motion not studied (module
    docstring)."""
    g = levels_gci(grid.as_dict()) if isinstance(grid, gci.GridConvergence) else None
    t = time.gci_coarse if isinstance(time, gci.TwoLevel) else None
    if g is None or t is None:
        return None
    return math.hypot(g, t) if motion is None else math.hypot(g, t, motion)


def motion_uncertainty(morphing: dict) -> float | None:
    """U_motion of one quantity: the whole relative change with the mesh motion spread
    (:func:`morphing_study`), unsigned; None when the mesh motion was not studied."""
    change = morphing.get("relative_change")
    return None if change is None else abs(change)


def implausible_order(order: float | None) -> bool:
    """An observed order beyond twice the schemes' formal one (:data:`FORMAL_ORDER`)."""
    return order is not None and order > 2 * FORMAL_ORDER


def levels_gci(grid: dict) -> float | None:
    """The levels' GCI_fine that U_num takes: Celik et al.'s, or, for an implausible observed
    order, the fine pair's as a two-grid study at :data:`FORMAL_ORDER` with F_s = 3
    (:func:`floatfoam.analysis.gci.two_level`; always the larger there, since 1.25/(r^p − 1)
    < 3/(r² − 1) for p > 4); for levels with no observed order (:func:`spread_band`), three
    times their whole spread. None without three levels."""
    g = grid.get("gci_fine")
    if g is None:
        return spread_band(grid)
    if not implausible_order(grid.get("order")):
        return g
    fine, medium, _ = grid["values"]
    return gci.two_level(fine, medium, grid["ratios"][0], FORMAL_ORDER).gci_fine


def spread_band(grid: dict) -> float | None:
    """For three levels with no observed order (diverging, oscillating apart, converging
    without a fixed point of the order's equation, or unchanged): F_s = 3 (Roache's safety
    factor of a study that cannot observe its order) times their largest difference, relative
    to the fine level's value. Levels that differ by less than their noise diverge as often as
    they converge; the band then still says how large the difference is. None without three
    levels' values."""
    values = grid.get("values")
    if not values or len(values) != 3 or not values[0]:
        return None
    return gci.SAFETY_TWO_GRIDS * (max(values) - min(values)) / abs(values[0])


def validate_case(case, build: Path | None = None, time_level: str = TIME_STEP_LEVEL,
                  morphing: float | None = DEFAULT_MORPHING) -> dict:
    """The study of ``case`` from its finished runs under ``build``: a JSON-ready dict.
    ``morphing``: the factor of its mesh-motion run (:func:`study_morphing`), None for a study
    without one."""
    from floatfoam.plan.stamps import stamp_of

    build = Path(build or layout.build_dir())
    found = study_runs(case, build, time_level, morphing)
    other = [level for level in TIME_STEP_LEVELS if level != time_level and layout.is_finished(
        layout.run_dir(case.name, level, build, time_step_divisor=TIME_STEP_DIVISOR))]
    hint = (f" ({layout.run_name(other[0], TIME_STEP_DIVISOR)} is: --time-level {other[0]})"
            if other else "")
    theory = theory_summary(case)
    order = time_order(case)
    out = {"case": case.name, "runs": [name for name, _, _, _ in found],
           "stamps": {name: stamp_of(run) for name, _, _, run in found}, "dofs": {},
           "time_order": order, "time_step_divisor": TIME_STEP_DIVISOR,
           "time_step_level": time_level, "morphing": morphing,
           "mesh_motion": mesh_motion_record(case, found, morphing)}
    for dof in excited_dofs(case, {}):
        runs = {name: _run_values(name, k, run, dof, f, settled_level(case, dof, run, theory))
                for name, k, f, run in found}
        entry = {"runs": {name: {"cells": r.cells, "dimension": r.dimension,
                                 "divisor": r.divisor, "morphing": r.morphing, **r.values,
                                 "note": r.note}
                          for name, r in runs.items()},
                 "quantities": {}}
        for key, _, _ in QUANTITIES:
            grid, time = grid_study(runs, key), time_study(runs, key, time_level, hint, order)
            motion = morphing_study(runs, key, morphing)
            u_motion = motion_uncertainty(motion)
            entry["quantities"][key] = {
                "grid": grid.as_dict() if not isinstance(grid, str) else {"note": grid},
                "time": time.as_dict() if not isinstance(time, str) else {"note": time},
                "motion_uncertainty": u_motion,
                "uncertainty": numerical_uncertainty(grid, time, u_motion),
                "morphing": motion}
        spans = [r.span for r in runs.values() if r.span is not None]
        entry["reference"] = measured(case, dof, max(spans, default=None))
        out["dofs"][dof] = entry
    return out


def mesh_motion_record(case, found, morphing: float | None) -> dict:
    """How the study's runs moved their mesh (:func:`floatfoam.plan.zone.motion_in` the
    domain of its runs), and what its mesh-motion run varied: ``motion``
    ("layered", "laplacian", "distances"; None without a run's record), ``diffusivity`` (the
    Laplacian's, in words), ``band`` (the layered motion's run.layer_band), ``factor``,
    ``run`` (its folder), ``variant`` (in words,
    :func:`floatfoam.plan.morphing.morphing_variant`), ``studied`` (its run finished: U_motion
    joins U_num) and ``note``. ``found``: :func:`study_runs`."""
    from floatfoam.plan.morphing import morphing_variant
    from floatfoam.plan.zone import motion_in
    from floatfoam.settings import MOTION_DIFFUSIVITIES

    kinds = [(record_or_none(run) or RunRecord()).mesh for _, _, factor, run in found
             if factor == 1]
    kind = next((k for k in kinds if k), None)
    motion = None if kind is None else motion_in(case, kind)
    record = {"motion": motion}
    if motion == "laplacian":
        record["diffusivity"] = MOTION_DIFFUSIVITIES[case.settings.run.motion_diffusivity]
    if motion == "layered":
        record["band"] = case.settings.run.layer_band
    if morphing is None:
        return record | {"studied": False,
                         "note": f"{NOT_STUDIED} (floatfoam validate --no-morphing)"}
    name = layout.run_name(MORPHING_LEVEL, 1, morphing)
    done = {run_name for run_name, _, _, _ in found}
    studied = {MORPHING_LEVEL, name} <= done
    variant = morphing_variant(case, motion, morphing) if motion else \
        f"mesh motion spread × {morphing:g}"
    return record | {"factor": morphing, "run": name, "variant": variant, "studied": studied,
                     "note": "" if studied else f"{NOT_STUDIED}: needs {MORPHING_LEVEL} and {name} "
                     "finished"}


def measured(case, dof: str, window: float | None = None) -> dict:
    """The case's ``[reference]`` values of the study's quantities, ``<dof>_<key>`` (code
    units): key → [value, uncertainty or None, source]. Without a period and damping ratio
    there, those of its measured record's decay fit over ``window`` s, the runs' record
    (:func:`~floatfoam.analysis.measured.record_fit`; the uncertainty is half the fit's 95 %
    interval)."""
    out = {}
    for key, _, _ in QUANTITIES:
        entry = reference_entry(case.reference or {}, f"{dof}_{key}")
        if entry is not None:
            out[key] = list(entry)
    if "period" not in out and "damping_ratio" not in out:
        fit = record_fit(case, dof, window)
        source = ((case.reference or {}).get(f"{dof}_record") or {}).get("source", "")
        for key, ci in (("period", "period_ci"), ("damping_ratio", "damping_ci")):
            if fit is not None and fit[key] is not None:
                half = (fit[ci][1] - fit[ci][0]) / 2 if fit[ci] else None
                out[key] = [fit[key], half, f"{source}: decay fit over the runs' record"]
    return out


