"""A grid, time-step and mesh-motion study (:func:`floatfoam.analysis.validation.validate_case`)
as text: its method in words (:func:`method`), its tables (:func:`study_tables`,
:func:`morphing_rows`, :func:`summary_row`), ``validation.md`` with ``validation.json`` and
the convergence figure (:func:`study_markdown`, :func:`write_study`)."""

from __future__ import annotations

from pathlib import Path

from floatfoam.analysis.orders import FORMAL_ORDER, TIME_ORDER
from floatfoam.analysis.uncertainty import STUDY_FILE
from floatfoam.analysis.validation import (
    MORPHING_LEVEL,
    QUANTITIES,
    TIME_STEP_LEVEL,
    implausible_order,
    levels_gci,
)
from floatfoam.jsonfile import dump_json


def _num(value, spec=".5g") -> str:
    return "—" if value is None else format(value, spec)


def _measured_cell(entry) -> str:
    if entry is None:
        return "—"
    value, uncertainty, _ = entry
    return _num(value) + (f" ± {uncertainty:.2g}" if uncertainty is not None else "")


def _pct(value) -> str:
    return "—" if value is None else f"{100 * value:.2g} %"


#: the row of a quantity that a study written by an earlier floatfoam does not hold
OLDER_STUDY = "not in this study (written before it was added: floatfoam validate --no-run)"


RUNS_HEADER = ("run", "cells", *(label for _, label, _ in QUANTITIES), "note")


GCI_HEADER = ("quantity", "convergence", "order p", "extrapolated", "e_a21",
              "GCI_fine (levels)", "Δ with dt/2", "GCI (time)", "U_motion", "U_num",
              "measured")


def method(time_level: str = TIME_STEP_LEVEL, motion: dict | None = None,
           order: float = TIME_ORDER) -> str:
    """How the study's numbers are made, for the foot of its table (``motion``: its
    :func:`mesh_motion_record`, None for a study written before U_motion joined U_num;
    ``order``: the time scheme's, :func:`time_order`)."""
    bound = ("" if time_level == "fine" else
             ", taken for the fine level's, whose steps are no longer (conservative if the "
             "time error's constant is about the same on both meshes)")
    return ("Levels: Celik et al. (2008), J. Fluids Eng. 130:078001 (cell size from the cell "
            "count, safety factor 1.25); the levels refine space and time together (the "
            "Courant limit is the same, the largest step shrinks with the cell), so this is a "
            f"space-time GCI. Time alone: the {time_level} level against its time steps "
            f"halved, Roache's two-grid GCI of the {time_level} level's own step (F_s = 3, "
            f"{'first' if order == 1 else 'second' if order == 2 else f'{order:g}'} order)"
            f"{bound}. {_motion_method(motion)} Where the levels' order p is beyond twice the "
            f"schemes' {FORMAL_ORDER:g}, GCI_levels is the fine pair's at order "
            f"{FORMAL_ORDER:g} with F_s = 3 (Roache); where they have no order, 3 × their "
            "whole spread.")


def _motion_method(motion: dict | None) -> str:
    """The mesh motion's part of :func:`method`: how the runs moved their mesh, U_motion and
    U_num."""
    if motion is None:
        return ("U_num = √(GCI_levels² + GCI_time²), the band around the fine level's value "
                "(a study written before the mesh motion joined U_num).")
    how = {"layered": "rows that move with the body by their height alone (over "
                      f"{motion.get('band', 1.0):g} × its height)",
           "laplacian": f"the Laplacian (diffusivity {motion.get('diffusivity', '1/d²')})",
           "distances": "the six-DoF solver's distances"}.get(motion.get("motion"),
                                                              "a motion no run recorded")
    runs = f"The runs' mesh follows the body by {how}."
    if not motion.get("studied"):
        return (f"{runs} U_num = √(GCI_levels² + GCI_time²), the band around the fine "
                f"level's value, without an error of the mesh motion: {motion['note']}.")
    return (f"{runs} Mesh motion: the {MORPHING_LEVEL} level against the same with "
            f"{motion['variant']} ({motion['run']}); the mesh motion is the same on every "
            "level, so neither GCI sees it, and U_motion is the whole relative change, which "
            "does not shrink with the levels. U_num = √(GCI_levels² + GCI_time² + U_motion²), "
            "the band around the fine level's value.")


def study_tables(study: dict) -> list[tuple[str, list[list[str]], list[list[str]]]]:
    """Per DoF: the rows of the runs table (RUNS_HEADER) and of the GCI table (GCI_HEADER)."""
    out = []
    for dof, entry in study["dofs"].items():
        runs = [[name, str(run["cells"] or "—"), *(_num(run.get(k)) for k, _, _ in QUANTITIES),
                 run["note"]] for name, run in entry["runs"].items()]
        rows = []
        for key, label, _ in QUANTITIES:
            q = entry["quantities"].get(key)
            if q is None:  # a study written before the quantity joined it
                rows.append([label, OLDER_STUDY, *("—",) * (len(GCI_HEADER) - 2)])
                continue
            g, t = q["grid"], q["time"]
            rows.append([label, _convergence(g), _num(g.get("order"), ".3g"),
                         _num(g.get("extrapolated")), _pct(g.get("relative_error")),
                         _pct(g.get("gci_fine")),
                         _pct(t.get("relative_error")) if "values" in t else t.get("note", ""),
                         _pct(t.get("gci_coarse")), _pct(q.get("motion_uncertainty")),
                         _pct(q["uncertainty"]),
                         _measured_cell(entry.get("reference", {}).get(key))])
        out.append((dof, runs, rows))
    return out


def _convergence(grid: dict, brief: bool = False) -> str:
    """How the levels converge; flagged when the observed order is beyond twice the formal
    one (:data:`FORMAL_ORDER`), ``brief``ly for the report's summary line."""
    kind = grid.get("kind", grid.get("note", ""))
    order = grid.get("order")
    if implausible_order(order) and brief:
        return f"{kind} (p = {order:.3g}: flagged)"
    if implausible_order(order):
        kind += (f" — p = {order:.3g}, beyond twice the schemes' order {FORMAL_ORDER:g}: "
                 "its GCI is no bound; U_num takes the fine pair's at that order, F_s = 3, "
                 f"{_pct(levels_gci(grid))}")
    elif grid.get("gci_fine") is None and levels_gci(grid) is not None and not brief:
        kind += (" — no observed order: U_num takes 3 × the levels' spread, "
                 f"{_pct(levels_gci(grid))}")
    return kind


MORPHING_HEADER = ("quantity", MORPHING_LEVEL, "mesh motion varied", "change",
                   "GCI_fine (levels)")


def motion_variant(study: dict) -> str | None:
    """What the study's mesh-motion run varied, in words ("distances × 1.5", "diffusivity 1/d
    instead of 1/d²"); None without one. A study written before the study recorded it had
    scaled the distances: the Laplacian had no such run then."""
    factor = study.get("morphing")
    if factor is None:
        return None
    return (study.get("mesh_motion") or {}).get("variant") or f"distances × {factor:g}"


def motion_heading(study: dict) -> str:
    """The line above a DoF's mesh-motion table (:func:`morphing_rows`)."""
    record = study.get("mesh_motion")
    if record is None:
        return (f"the {MORPHING_LEVEL} level with {motion_variant(study)} (a study written "
                "before U_motion joined U_num)")
    return (f"the {MORPHING_LEVEL} level with {record['variant']} ({record['run']}); "
            "U_motion = |change|")


def morphing_rows(study: dict, dof: str) -> list[list[str]]:
    """Rows of the mesh-motion study's table (MORPHING_HEADER) of one DoF; none when it was
    not studied (:func:`method` says why)."""
    record = study.get("mesh_motion")
    if study.get("morphing") is None or (record is not None and not record.get("studied")):
        return []
    rows = []
    for key, label, _ in QUANTITIES:
        q = study["dofs"][dof]["quantities"].get(key)
        if q is None:
            continue
        m = q.get("morphing", {})
        a, b = m.get("values", (None, None))
        rows.append([label, _num(a), _num(b), _signed_pct(m.get("relative_change"))
                     if "values" in m else m.get("note", ""), _pct(q["grid"].get("gci_fine"))])
    return rows


def _signed_pct(value) -> str:
    return "—" if value is None else f"{100 * value:+.2g} %"


SUMMARY_HEADER = ("case", "DoF", "runs", "T_d fine (s)", "levels", "GCI_fine levels",
                  "dt/2 at", "GCI time", "U_num of T_d", "ζ fine", "U_num of ζ",
                  "ζ with the mesh motion varied")


def summary_row(study: dict, dof: str) -> list[str]:
    """One line of the report's verification summary: the damped period's and the damping
    ratio's fine value, how the levels converge, the GCIs and U_num (SUMMARY_HEADER)."""
    entry = study["dofs"][dof]
    period, zeta = entry["quantities"]["period"], entry["quantities"]["damping_ratio"]
    fine = entry["runs"].get("fine", {})
    return [study["case"], dof, str(len(study["runs"])), _num(fine.get("period")),
            _convergence(period["grid"], brief=True),
            _pct(period["grid"].get("gci_fine")), study.get("time_step_level", "fine"),
            _pct(period["time"].get("gci_coarse")),
            _pct(period["uncertainty"]), _num(fine.get("damping_ratio"), ".3g"),
            _pct(zeta["uncertainty"]), _morphing_cell(study, zeta.get("morphing", {}))]


def _morphing_cell(study: dict, morphing: dict) -> str:
    if "values" not in morphing:
        return "—"
    return f"{_signed_pct(morphing['relative_change'])} ({motion_variant(study)})"


def study_markdown(study: dict) -> str:
    """The study as Markdown: per DoF, the runs, then one row per quantity."""
    def table(header, rows):
        return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
                *("| " + " | ".join(rows_) + " |" for rows_ in rows), ""]

    lines = [f"# {study['case']}: grid and time-step convergence", ""]
    for dof, runs, rows in study_tables(study):
        lines += [f"## {dof}", "", *table(RUNS_HEADER, runs), *table(GCI_HEADER, rows)]
        morphing = morphing_rows(study, dof)
        if morphing:
            lines += [f"Mesh motion: {motion_heading(study)}:", "",
                      *table(MORPHING_HEADER, morphing)]
    return "\n".join([*lines, method(study.get("time_step_level", "fine"),
                                     study.get("mesh_motion"),
                                     study.get("time_order", TIME_ORDER)), ""])


def write_study(study: dict, out_dir: Path) -> list[Path]:
    """``validation.json``, ``validation.md`` and ``convergence.png`` in ``out_dir``."""
    from floatfoam.analysis.plots import plot_convergence

    out_dir.mkdir(parents=True, exist_ok=True)
    paths = [out_dir / STUDY_FILE, out_dir / "validation.md", out_dir / "convergence.png"]
    paths[0].write_text(dump_json(study) + "\n")
    paths[1].write_text(study_markdown(study))
    plot_convergence(study, QUANTITIES, paths[2])
    return paths
