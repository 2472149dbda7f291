"""The project report: every case's theory, and period and damping of every finished CFD run.

``build_report`` walks ``cases/`` (folders starting with ``_`` are shared material, not cases)
and, for each case, writes into ``build/report/``:

* the linear-theory table (always, even before any CFD run),
* the comparison of :mod:`floatfoam.analysis.compare` (memoir, theory, potential flow,
  Cummins' model, each ``build/<case>/<level>/motion.csv``, the reference; Δ against Cummins'
  model and against the measurement) as ``<case>/comparison.{md,csv}``,
* one decay figure per CFD run and DoF, the record beside Cummins' model and any measurement
  (``<case>/<level>_<dof>.png``, :mod:`floatfoam.analysis.plots`), and for a roll record its
  extinction curve (``<case>/<level>_roll_extinction.png``, :mod:`floatfoam.analysis.extinction`),
* the righting arm GZ(φ) of a case released heeled (``<case>/gz.png``,
  :func:`floatfoam.hydrostatics.gz.plot_gz`) and the radiation coefficients A(ω), B(ω) of
  its potential flow (``<case>/potential.png``, :func:`floatfoam.potential.plot.plot_coefficients`),
* pictures of the flow of each run (free surface, speed, pressure near the body, a GIF of the
  decay: :mod:`floatfoam.analysis.pictures`), when asked,
* the grid and time-step study of ``floatfoam validate``, when it has been run,

and gathers them in ``index.md`` and ``index.html`` (the same content).
"""

from __future__ import annotations

import csv
import datetime
import json
import shutil
import subprocess
import sys
from pathlib import Path

import floatfoam
from floatfoam import dofs, layout
from floatfoam.analysis.compare import Comparison, compare_case, memoir_label
from floatfoam.analysis.comparison_table import comparison_table, fmt, write_comparison
from floatfoam.analysis.document import Document
from floatfoam.analysis.report_figures import case_figures, record_figures, turn_figures
from floatfoam.analysis.runs import current_runs
from floatfoam.analysis.sources import Sources
from floatfoam.errors import InputError
from floatfoam.hydrostatics.summary import TheorySummary

# (key of theory_summary, label, unit)
THEORY_ROWS = (
    ("draft", "draft T", "m"),
    ("displaced_volume", "displaced volume V", "m³"),
    ("waterplane_area", "waterplane area A_wp", "m²"),
    ("KB", "KB", "m"),
    ("KG", "KG", "m"),
    ("BM_roll", "BM (roll)", "m"),
    ("BM_pitch", "BM (pitch)", "m"),
    ("GM_roll", "GM (roll)", "m"),
    ("GM_pitch", "GM (pitch)", "m"),
    ("verdict_roll", "verdict (roll)", ""),
    ("verdict_pitch", "verdict (pitch)", ""),
    ("heave_period", "heave period (undamped)", "s"),
    ("roll_period", "roll period (undamped)", "s"),
    ("pitch_period", "pitch period (undamped)", "s"),
)
EQUILIBRIUM_ROWS = (("z_G", "equilibrium z of G", "m"), ("heel", "equilibrium heel", "deg"),
                    ("trim", "equilibrium trim", "deg"))


def _cell(value) -> str:
    if isinstance(value, str):
        return value
    return fmt(None if value is None else float(value), ".5g")


def theory_table(summary: TheorySummary) -> tuple[list[str], list[list[str]]]:
    """Header and rows of the linear theory, with the memoir's values beside where it has any."""
    theory = summary.to_dict()
    memoir = theory.get("memoir") or {}
    header = ["quantity", "exact theory"] + (
        [memoir_label(memoir.get("source")) if memoir.get("source") else "memoir"]
        if memoir else []) + ["unit"]
    rows = [[label, _cell(theory.get(key))] + ([_cell(memoir.get(key, ""))] if memoir else [])
            + [unit] for key, label, unit in THEORY_ROWS if key in theory]
    eq = theory.get("equilibrium") or {}
    rows += [[label, _cell(eq.get(key))] + ([""] if memoir else []) + [unit]
             for key, label, unit in EQUILIBRIUM_ROWS if key in eq]
    return header, rows


def _write_theory_csv(header, rows, path: Path) -> None:
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        writer.writerows(rows)


def _intro(doc: Document, case) -> str:
    """Heading, description and release of a case; returns its title."""
    title = case.title
    doc.heading(f"{case.name}: {title}" if title else case.name)
    description = " ".join(case.description.split())
    if description:
        doc.paragraph(description)
    release = getattr(case, "release", None) or {}
    units = {d.release_key: d.unit for d in dofs.DOFS}
    parts = [f"{k} {fmt(float(v), 'g')} {units.get(k, '')}".strip() for k, v in release.items()]
    doc.paragraph("Release: " + (", ".join(parts) or "none given"), note=True)
    return title


def _comparison_section(doc: Document, comparison: Comparison) -> None:
    doc.heading("Period and damping", 3)
    if comparison.rows:
        doc.table(*comparison_table(comparison.rows))
        doc.paragraph("Theory rows give the undamped natural period; Cummins' model and CFD "
                      "rows the damped period T_d of the record, fitted the same way over the "
                      "same span, the CFD's with its 95 % confidence interval (from the fit's "
                      "covariance: optimistic when the misfit is correlated in time); the "
                      "reference row its value ± the stated uncertainty, or, where the "
                      "reference gives only a measured record, that record's decay fit over "
                      "the CFD's span with the fit's 95 % interval. Δ vs model: relative "
                      "difference to Cummins' model (the body's free DoFs, exact restoring "
                      "where the release is large), or to the exact linear theory where the "
                      "model was not computed (the note says which); Δ vs measured: to the "
                      "reference.", note=True)
    doc.bullets(comparison.notes)


def _status(comparison: Comparison, turned: tuple = ()) -> str:
    """The summary table's CFD cell: the levels analysed, those whose analysis failed, and
    ``turned``, the levels of a body that turns over (no period to fit: their figure shows
    them)."""
    levels = sorted({run.level for run in comparison.analyses})
    failed = [r["source"] for r in comparison.rows if r["note"].startswith("analysis failed")
              and r["source"].removeprefix("CFD ") not in turned]
    status = "CFD: " + ", ".join(levels) if levels else "theory only"
    status += f"; turns over: {', '.join(turned)}" if turned else ""
    status += f"; failed: {', '.join(failed)}" if failed else ""
    left_out = comparison.foreign + (["the study"] if comparison.foreign_study else [])
    return status + (f"; left out, of other settings: {', '.join(left_out)}" if left_out else "")


def _case_section(doc: Document, folder: Path, build_dir: Path, out_dir: Path,
                  sources: Sources, pictures: bool = False) -> tuple[list[str], dict | None]:
    """Add one case's section; return its line of the summary table and its study (None
    without one of today's settings, or when the case could not be loaded)."""
    try:
        case = sources.load(folder)
        theory = sources.theory(case)
    except InputError as err:
        doc.heading(f"{folder.name}: could not be loaded")
        doc.paragraph(f"error: {err}")
        return [folder.name, "—", "—", f"error: {err}"], None
    title = _intro(doc, case)
    case_out = out_dir / case.name
    case_out.mkdir(parents=True, exist_ok=True)
    header, rows = theory_table(theory)
    _write_theory_csv(header, rows, case_out / "theory.csv")
    doc.heading("Linear hydrostatic theory", 3)
    doc.table(header, rows)
    comparison = compare_case(case, build_dir=build_dir, theory=theory,
                              potential=sources.potential, model=sources.model)
    write_comparison(comparison, case_out)
    _comparison_section(doc, comparison)
    images = record_figures(case, theory, comparison, out_dir, sources)
    if images:
        doc.heading("Decay records", 3)
        for src, alt in images:
            doc.image(src, alt)
    runs, _ = current_runs(case, build_dir)
    turns = turn_figures(case, theory, runs, out_dir)
    if turns:
        doc.heading("Turning over", 3)
        for src, alt in turns:
            doc.image(src, alt)
    case_figures(doc, case, sources, out_dir)
    if pictures:
        levels = {r.level for r in comparison.analyses}  # and a turn over's runs, unfitted
        levels |= {level for level, _ in runs if level in layout.LEVELS} if turns else set()
        _pictures_section(doc, case.name, sorted(levels, key=layout.LEVELS.index), build_dir,
                          out_dir)
    _validation_section(doc, case.name, comparison.study, build_dir, out_dir)
    turned = tuple(level for level, _ in runs) if turns else ()
    return [case.name, title or "—", _periods_cell(theory), _status(comparison, turned)], \
        comparison.study


def _pictures_section(doc: Document, case_name: str, levels: list[str], build_dir: Path,
                      out_dir: Path) -> None:
    """Pictures of the flow of each finished run (:mod:`floatfoam.analysis.pictures`), drawn
    once per run (again when the run is newer than its pictures, or they were drawn in another
    :data:`~floatfoam.analysis.pictures.STYLE`) and copied beside the page."""
    from floatfoam.analysis.pictures import STYLE, case_pictures

    shown = []
    for level in levels:
        folder = layout.case_build_dir(case_name, build_dir) / "pictures" / level
        done = folder / ".drawn"
        finished = layout.marker(layout.run_dir(case_name, level, build_dir), layout.FINISHED)
        drawn = json.loads(done.read_text()) if done.is_file() \
            and done.stat().st_mtime >= finished.stat().st_mtime else {}
        pairs = drawn.get("pictures", []) if isinstance(drawn, dict) \
            and drawn.get("style") == STYLE else []
        if not pairs or not all((folder / name).is_file() for name, _ in pairs):
            print(f"report: drawing the flow of {case_name}/{level} (pyvista)", file=sys.stderr)
            try:
                pairs = [(p.name, alt) for p, alt in case_pictures(case_name, level, build_dir)]
            except Exception as err:  # noqa: BLE001 - a picture must not cost the report
                why = err if isinstance(err, InputError) else f"{type(err).__name__}: {err}"
                doc.paragraph(f"{level}: no pictures of the flow ({why})", note=True)
                continue
            done.write_text(json.dumps({"style": STYLE, "pictures": pairs}))
        for name, alt in pairs:
            target = f"{case_name}/pictures_{level}_{name}"
            shutil.copyfile(folder / name, out_dir / target)
            shown.append((target, alt))
    if shown:
        doc.heading("Pictures of the flow", 3)
        for src, alt in shown:
            doc.image(src, alt)


def _validation_section(doc: Document, case_name: str, study: dict | None, build_dir: Path,
                        out_dir: Path) -> None:
    """The grid and time-step study of ``floatfoam validate``, when it has been run with the
    case's settings of today (the comparison's, which says in its notes when it was not)."""
    from floatfoam.analysis.orders import TIME_ORDER
    from floatfoam.analysis.study_tables import (
        GCI_HEADER,
        MORPHING_HEADER,
        RUNS_HEADER,
        method,
        morphing_rows,
        motion_heading,
        study_tables,
    )

    if study is None:
        return
    doc.heading("Grid and time-step convergence", 3)
    for dof, runs, rows in study_tables(study):
        doc.paragraph(f"{dof}:")
        doc.table(RUNS_HEADER, runs)
        doc.table(GCI_HEADER, rows)
        morphing = morphing_rows(study, dof)
        if morphing:
            doc.paragraph(f"{dof}, mesh motion: {motion_heading(study)}:")
            doc.table(MORPHING_HEADER, morphing)
    doc.paragraph(method(study.get("time_step_level", "fine"), study.get("mesh_motion"),
                         study.get("time_order", TIME_ORDER)), note=True)
    figure = layout.case_build_dir(case_name, build_dir) / "validation" / "convergence.png"
    if figure.is_file():
        name = f"{case_name}/convergence.png"
        shutil.copyfile(figure, out_dir / name)
        doc.image(name, f"{case_name} grid and time-step convergence")


def _verification_summary(doc: Document, studies: list[dict]) -> None:
    """One line per case and DoF that ``floatfoam validate`` has studied with the case's
    settings of today: its damped period and damping ratio at the fine level with their
    numerical uncertainty."""
    from floatfoam.analysis.study_tables import SUMMARY_HEADER, summary_row

    rows = [summary_row(study, dof) for study in studies for dof in study.get("dofs", {})]
    if not rows:
        return
    doc.heading("Verification: grid and time-step convergence")
    doc.table(SUMMARY_HEADER, rows)
    doc.paragraph("From `floatfoam validate CASE` (each case's section has its tables and "
                  "figure). GCI_fine of the levels: Celik et al. (2008); GCI time: Roache's "
                  "two-grid GCI of the halved level's own step; U_motion: the whole relative "
                  "change with the mesh motion varied at the coarse level (the six-DoF "
                  "distances × F, the Laplacian's diffusivity 1/d instead of 1/d², or the "
                  "layered motion's rows moving with the body over F × its height), which "
                  "neither GCI sees; U_num = √(GCI_levels² + GCI_time² + U_motion²), the band "
                  "around the fine level's value (without U_motion where the mesh motion was "
                  "not studied: the case's section says so). ζ with the mesh motion varied: "
                  "the coarse level's damping ratio's change.", note=True)


def _periods_cell(theory: TheorySummary) -> str:
    parts = [f"{dof} {theory.period(dof):.4g} s" for dof in dofs.NAMES
             if theory.period(dof) is not None]
    return ", ".join(parts) or "—"


def _provenance() -> str:
    try:
        sha = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                             text=True, check=True, cwd=Path(__file__).parent).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        sha = "unknown"
    stamp = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    return f"floatfoam {floatfoam.__version__}, git {sha}, generated {stamp}."


def build_report(*, cases_dir: str | Path | None = None, build_dir: str | Path | None = None,
                 out_dir: str | Path | None = None, sources: Sources | None = None,
                 pictures: bool = False) -> Path:
    """Write ``index.md``, ``index.html`` and the per-case files; return the HTML's path.

    Defaults: the repository's ``cases/`` and ``build/``, and ``<build_dir>/report`` — for
    another cases folder ``<build_dir>/report-<its name>-<8 hex digits of its path>``, so that
    the report of one folder never replaces another's.
    ``pictures`` adds the pictures of the flow of every finished run (``floatfoam report``
    does by default; drawn once per run).
    """
    sources = sources or Sources.default()
    cases_dir = Path(cases_dir or layout.CASES_DIR)
    build_dir = Path(build_dir or layout.build_dir())
    if out_dir is None:
        own = cases_dir.resolve() == layout.CASES_DIR.resolve()
        out_dir = build_dir / ("report" if own else f"report-{_folder_name(cases_dir)}")
    out_dir = Path(out_dir)
    folders = layout.list_cases(cases_dir)
    if not folders:
        raise InputError(f"--cases {cases_dir}: no case folder with a case.toml in it; valid is "
                         "a folder of case folders, as the project's cases/")
    out_dir.mkdir(parents=True, exist_ok=True)
    body = Document("")
    sections = [_case_section(body, folder, build_dir, out_dir, sources, pictures)
                for folder in folders]
    doc = Document("floatfoam report")
    doc.paragraph(_provenance(), note=True)
    doc.heading("Cases")
    doc.table(("case", "title", "linear theory periods", "status"),
              [row for row, _ in sections])
    _verification_summary(doc, [study for _, study in sections if study is not None])
    doc.blocks += body.blocks
    (out_dir / "index.md").write_text(doc.markdown())
    html_path = out_dir / "index.html"
    html_path.write_text(doc.html())
    return html_path


def _folder_name(folder: Path) -> str:
    """A cases folder's name with 8 hex digits of its absolute path."""
    import hashlib
    import os

    path = os.path.abspath(folder)
    return f"{Path(path).name}-{hashlib.sha256(path.encode()).hexdigest()[:8]}"

