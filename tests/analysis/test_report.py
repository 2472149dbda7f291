"""The report on a tiny tree: cases/ folders and a build/ holding SYNTHETIC motion records.

The motion.csv files here are synthetic free decays written by the test, not OpenFOAM output
(a committed real-output test belongs with the CFD runs). The first tests replace the case
loader and the theory with stand-ins, so they check the report's assembly only; the last ones
run the real loader and theory on a small case file, and the real potential flow and Cummins'
model on it (a 2D section: its panel method takes a second).
"""

from __future__ import annotations

import argparse
import csv
import math
import types
from pathlib import Path

import numpy as np
import pytest
from conftest import ROOT

from floatfoam.analysis.cummins import MODEL
from floatfoam.analysis.decay import analyse_decay
from floatfoam.analysis.report import Sources, build_report
from floatfoam.case import load_case
from floatfoam.cli import report as report_command
from floatfoam.errors import InputError
from floatfoam.hydrostatics.gz import GZCurve
from floatfoam.hydrostatics.summary import TheorySummary
from floatfoam.layout import list_cases, mark_done
from floatfoam.motion import write_motion

PERIOD, ZETA = 0.63, 0.15  # of the synthetic heave record


def synthetic_decay(t, offset=0.0254, eq=0.0, period=PERIOD, zeta=ZETA):
    omega_d = 2 * math.pi / period
    sigma = zeta * omega_d / math.sqrt(1 - zeta**2)
    return eq + offset * np.exp(-sigma * t) * (np.cos(omega_d * t)
                                               + sigma / omega_d * np.sin(omega_d * t))


def make_tree(tmp_path):
    cases, build = tmp_path / "cases", tmp_path / "build"
    for name in ("cyl", "box", "_common", "broken"):
        (cases / name).mkdir(parents=True)
        (cases / name / "case.toml").write_text("# stand-in\n")
    t = np.arange(0.0, 3.0, 2e-3)
    write_motion(build / "cyl" / "coarse" / "motion.csv", t, z=synthetic_decay(t))
    mark_done(build / "cyl" / "coarse", "finished")
    (build / "cyl" / "notarun").mkdir()  # a folder without motion.csv is not a run
    return cases, build


def fake_sources(monkeypatch):
    """Stand-in case loader and theory (no potential flow), handed to the report; the report
    command is made to use them too."""
    def load_case(path):
        folder = Path(path)
        if folder.name == "broken":
            raise InputError("body.radius = -1: valid is a number > 0")
        release = {"heave": 0.0254, "heel": 0.0, "trim": 0.0} if folder.name == "cyl" else {
            "heave": 0.0, "heel": 10.0, "trim": 0.0}
        reference = {"heave_period": {"value": 0.63, "uncertainty": 0.01, "source": "Ito 1977"}
                     } if folder.name == "cyl" else {}
        raw = {"case": {"title": f"Stand-in {folder.name}", "description": "A test case."},
               "release": release, "reference": reference}
        return types.SimpleNamespace(name=folder.name, path=folder, raw=raw, release=release,
                                     reference=reference, **raw["case"])

    def theory_summary(case):
        return TheorySummary.from_dict({
                "draft": 0.0762, "displaced_volume": 0.00912, "waterplane_area": 0.1524,
                "KB": 0.0439, "KG": 0.0762, "BM_roll": 0.0323, "BM_pitch": 1.39,
                "GM_roll": 0.0, "GM_pitch": 1.36, "heave_period": 0.4908,
                "roll_period": 1.29 if case.name == "box" else None, "pitch_period": 0.5,
                "verdict_roll": "neutral", "verdict_pitch": "oscillates",
                "equilibrium": {"z_G": 0.0, "heel": 0.0, "trim": 0.0}, "memoir": {}})

    def gz_curve(case):  # a stand-in righting arm, drawn for the case released heeled
        angles = np.arange(0.0, 91.0)
        return GZCurve(angles, 0.03 * np.sin(np.radians(2 * angles)), 90.0, 0.03, 45.0)

    sources = Sources(load=load_case, theory=theory_summary, potential=None, gz=gz_curve)
    monkeypatch.setattr(Sources, "default", classmethod(lambda cls, **kw: sources))
    return sources


def test_case_folders_skip_underscore(tmp_path):
    cases, _ = make_tree(tmp_path)
    assert [p.name for p in list_cases(cases)] == ["box", "broken", "cyl"]


def test_report_gathers_theory_and_finished_runs(tmp_path, monkeypatch):
    cases, build = make_tree(tmp_path)
    sources = fake_sources(monkeypatch)
    html_path = build_report(cases_dir=cases, build_dir=build, sources=sources)
    # another cases folder than the project's: a report folder of its own, never build/report
    (out,) = build.glob(f"report-{cases.name}-????????")
    assert html_path == out / "index.html" and not (build / "report").exists()
    md = (out / "index.md").read_text()
    html = html_path.read_text()
    # Every case appears (theory only where no run exists), _common does not.
    assert "## box: Stand-in box" in md and "## cyl: Stand-in cyl" in md
    assert "_common" not in md
    assert "| box | Stand-in box | heave 0.4908 s, roll 1.29 s, pitch 0.5 s | theory only |" in md
    assert "| cyl | Stand-in cyl |" in md and "| CFD: coarse |" in md
    assert "broken: could not be loaded" in md and "body.radius = -1" in md
    # The synthetic run is analysed and compared with the reference (0.63 s).
    assert "| heave | CFD coarse | 0.63 |" in md
    assert "| heave | reference | 0.63 | [0.62, 0.64] |" in md
    png = out / "cyl" / "coarse_heave.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert '<img src="cyl/coarse_heave.png"' in html
    for name in ("theory.csv", "comparison.csv", "comparison.md"):
        assert (out / "cyl" / name).is_file() and (out / "box" / name).is_file()
    assert "roll period (undamped),1.29,s" in (out / "box" / "theory.csv").read_text()
    # the righting arm of the case released heeled, not of the one released in heave
    assert '<img src="box/gz.png"' in html and not (out / "cyl" / "gz.png").exists()


def test_report_html_is_self_contained(tmp_path, monkeypatch):
    cases, build = make_tree(tmp_path)
    sources = fake_sources(monkeypatch)
    html = build_report(cases_dir=cases, build_dir=build, out_dir=tmp_path / "r",
                        sources=sources).read_text()
    assert html.startswith("<!DOCTYPE html>") and html.rstrip().endswith("</html>")
    assert "<script" not in html and "http" not in html  # no external resources
    assert html.count("<table>") == html.count("</table>") == 5  # summary + 2 per loaded case


def test_report_command_and_bad_cases_dir(tmp_path, monkeypatch, capsys):
    cases, build = make_tree(tmp_path)
    sources = fake_sources(monkeypatch)
    parser = argparse.ArgumentParser()
    report_command.register(parser.add_subparsers())
    args = parser.parse_args(["report", "--cases", str(cases), "--build", str(build),
                              "--out", str(tmp_path / "out")])
    assert args.func(args) == 0
    assert str(tmp_path / "out" / "index.html") in capsys.readouterr().out
    with pytest.raises(InputError, match="^--cases .*empty: no case folder with a case.toml"):
        build_report(cases_dir=tmp_path / "empty", build_dir=build, out_dir=tmp_path / "out2",
                     sources=sources)
    assert not (tmp_path / "out2").exists()  # the error comes before anything is written


CASE_TOML = """
[case]
title = "Half-immersed cylinder"
[body]
shape = "circular_cylinder"
radius = 0.0762
length = 1.0
[mass]
density = 500.0
cog = [0.0, 0.0, 0.0]
gyradius = [0.05388, 0.29116, 0.29116]
[release]
heave = 0.0254
"""


def test_report_with_real_theory(tmp_path):
    """End to end with the real case loader and linear theory (potential flow left out)."""
    cases, build = tmp_path / "cases", tmp_path / "build"
    (cases / "cyl").mkdir(parents=True)
    (cases / "cyl" / "case.toml").write_text(CASE_TOML)
    name = load_case(str(cases / "cyl")).name  # outside cases/: cyl-<8 hex digits of its path>
    assert name.startswith("cyl-") and len(name) == 12
    t = np.arange(0.0, 3.0, 2e-3)
    write_motion(build / name / "medium" / "motion.csv", t, z=synthetic_decay(t))
    mark_done(build / name / "medium", "finished")
    md = build_report(cases_dir=cases, build_dir=build,
                      sources=Sources.default(include_potential=False)
                      ).with_suffix(".md").read_text()
    assert f"## {name}: Half-immersed cylinder" in md
    assert "| draft T | 0.0762 |" in md  # half immersed: the draft is the radius
    assert "| heave | linear theory (exact) |" in md and "| heave | CFD medium | 0.63 |" in md


def test_report_sets_the_cfd_against_cummins_model(tmp_path):
    """The decay figure and the Δ columns are against Cummins' model: its row's period is the
    decay fit of the model's series over the CFD record's span (computed here from
    decay_series, as `floatfoam decay-model --model cummins` does), and the CFD's Δ period is
    the relative difference from it; the linear theory keeps its row, the reference its own
    Δ columns. The release of a third of the radius is large (the linear force is 1.9 % off
    the exact one at the release): the model takes the exact restoring force."""
    from PIL import Image

    from floatfoam.potential.models import LARGE_RELEASE, decay_series, linear_restoring_error

    cases, build = tmp_path / "cases", tmp_path / "build"
    (cases / "cyl").mkdir(parents=True)
    (cases / "cyl" / "case.toml").write_text(
        CASE_TOML + '[reference]\nheave_period = { value = 0.6, uncertainty = 0.01 }\n')
    case = load_case(str(cases / "cyl"))
    t = np.arange(0.0, 3.0, 2e-3)
    write_motion(build / case.name / "medium" / "motion.csv", t, z=synthetic_decay(t))
    mark_done(build / case.name / "medium", "finished")
    html_path = build_report(cases_dir=cases, build_dir=build, sources=Sources.default())
    html = html_path.read_text()
    out = html_path.parent / case.name

    assert linear_restoring_error(case) > LARGE_RELEASE
    series = decay_series(case, "cummins", duration=float(t[-1]), nonlinear_restoring=True)
    model_period = analyse_decay(series["time"], series["z"]).summary()["period_mean"]
    rows = {r["source"]: r for r in csv.DictReader((out / "comparison.csv").open())}
    assert float(rows[MODEL]["period"]) == pytest.approx(model_period, rel=1e-9)
    cfd = rows["CFD medium"]
    assert float(cfd["period_rel_diff"]) == pytest.approx(
        float(cfd["period"]) / model_period - 1, rel=1e-9)
    assert float(cfd["period_rel_diff_measured"]) == pytest.approx(
        float(cfd["period"]) / 0.6 - 1, rel=1e-9)
    assert "Δ period vs Cummins' model" in cfd["basis"]
    assert rows["linear theory (exact)"]["period"]  # the theory keeps its row
    md = html_path.with_suffix(".md").read_text()
    delta = f"{100 * (float(cfd['period']) / model_period - 1):+.2f} %"
    assert "| heave | CFD medium | 0.63 |" in md and f"| {delta} |" in md
    assert "| Δ period vs model |" in md and "| Δ period vs measured |" in md
    # the figure: the record beside the model, named in its legend (the PNG's Description)
    legend = Image.open(out / "medium_heave.png").text["Description"].splitlines()
    assert any(line.startswith(f"{MODEL} (heave free; exact restoring): T_d = "
                               f"{model_period:.4g} s") for line in legend)
    assert any(line.startswith("linear theory, no added mass") for line in legend)
    # A(ω), B(ω) of its potential flow; no GZ curve for a heave release
    assert f'<img src="{case.name}/potential.png"' in html and not (out / "gz.png").exists()


def test_analyse_plot_draws_a_run_beside_cummins_model(tmp_path, capsys):
    """`floatfoam analyse RUN --plot` on a run of a case of cases/ (here elliptic_cylinder_roll,
    a run folder written by hand: no stamp, so taken as the case's) draws Cummins' model in the
    body's free DoFs, with the exact restoring force (its 10° heel is large: C x is 3.8 % off
    at the release), as the report does; a CSV of no run has no case, and no model."""
    from PIL import Image

    from floatfoam import layout
    from floatfoam.cli import main

    t = np.arange(0.0, 4.5, 0.005)
    run = tmp_path / "elliptic_cylinder_roll" / "coarse"
    (run / layout.MARKERS).mkdir(parents=True)
    (run / layout.MARKERS / "info.json").write_text(
        '{"mesh": "2d", "release": {"heave": 0.0, "heel": 10.0, "trim": 0.0}}')
    write_motion(run / "motion.csv", t, roll=synthetic_decay(t, 10.0, 0.0, 0.868, 0.0265))
    mark_done(run, "finished")
    assert main(["analyse", str(run), "--plot", str(tmp_path / "roll.png")]) == 0
    legend = Image.open(tmp_path / "roll.png").text["Description"]
    assert f"{MODEL} (heave, roll, sway free; exact restoring): T_d = 0.8" in legend
    assert "no model" not in capsys.readouterr().err
    assert main(["analyse", str(run / "motion.csv"), "--plot", str(tmp_path / "csv.png")]) == 0
    assert MODEL in Image.open(tmp_path / "csv.png").text["Description"]  # its run's, too
    (tmp_path / "lone.csv").write_bytes((run / "motion.csv").read_bytes())
    assert main(["analyse", str(tmp_path / "lone.csv"), "--plot", str(tmp_path / "lone.png")]) == 0
    assert MODEL not in Image.open(tmp_path / "lone.png").text["Description"]


def test_a_measured_period_alone_is_not_drawn_as_no_damping(tmp_path):
    """A reference with a period and no damping (the flume's decay tests) is drawn at the
    record's fitted ζ and says so; with a measured ζ, at that one."""
    from PIL import Image

    from floatfoam.analysis.plots import Overlay, plot_decay

    t = np.linspace(0.0, 6.0, 1201)
    x = 0.1 * np.exp(-0.3 * t) * np.cos(2 * math.pi * t / 1.2)
    result = analyse_decay(t, x)
    for damping, says in ((None, "ζ not measured (the fit's"), (0.05, "ζ = 0.05")):
        overlay = Overlay(reference_period=1.2, reference_damping=damping,
                          reference_source="flume")
        path = plot_decay(tmp_path / f"{damping}.png", t, x, result, overlay=overlay)
        legend = Image.open(path).text["Description"]
        assert "reference flume: T = 1.2 s, " + says in legend, legend


def test_report_sets_a_roll_record_beside_ikeda_and_potential_flow(tmp_path):
    """A 2D section's roll record (SYNTHETIC: a linear decay of ζ 0.012 from 10°) gets its
    extinction figure with Ikeda's components (friction + eddy + wave, about a fixed axis) and
    potential flow's wave damping beside the fit, and the caption says so."""
    from floatfoam.damping.ikeda import roll_damping
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.potential.radiation import potential_summary

    cases, build = tmp_path / "cases", tmp_path / "build"
    (cases / "box").mkdir(parents=True)
    (cases / "box" / "case.toml").write_text(
        (ROOT / "cases" / "box_bilge" / "case.toml").read_text())
    case = load_case(str(cases / "box"))
    t = np.arange(0.0, 7.0, 2e-3)
    roll = synthetic_decay(t, offset=10.0, period=1.44, zeta=0.012)  # degrees
    write_motion(build / case.name / "coarse" / "motion.csv", t, roll=roll)
    mark_done(build / case.name / "coarse", "finished")
    html_path = build_report(cases_dir=cases, build_dir=build, sources=Sources.default())
    md = html_path.with_suffix(".md").read_text()
    figure = html_path.parent / case.name / "coarse_roll_extinction.png"
    assert figure.stat().st_size > 0
    assert "roll extinction curve: decrement per half swing and equivalent damping ratio " \
           "against amplitude; beside Ikeda's components and potential flow" in md
    ikeda = roll_damping(case, equilibrium(case), potential_summary(case), 10.0)
    assert ikeda.eddy > ikeda.wave > 0  # the box's bilges separate: eddies, not waves


def test_report_draws_a_body_that_turns_over_beside_the_nonlinear_model(tmp_path):
    """A record of a body the theory says capsizes (SYNTHETIC: the roll of
    ellipsoid_printed_verdict's nonlinear inviscid model itself, 5° to past 180°, as the CFD
    would write it) has no period to fit: the report draws its attitude beside the nonlinear
    model under "Turning over", and the summary says it turns over instead of a failed
    analysis."""
    from floatfoam.potential.models import decay_series

    cases, build = tmp_path / "cases", tmp_path / "build"
    (cases / "over").mkdir(parents=True)
    (cases / "over" / "case.toml").write_text(
        (ROOT / "cases" / "ellipsoid_printed_verdict" / "case.toml").read_text())
    case = load_case(str(cases / "over"))
    series = decay_series(case, "nonlinear", duration=0.7)
    assert series["roll"].max() > 180.0  # the record runs on through 180°
    write_motion(build / case.name / "coarse" / "motion.csv", series["time"],
                 roll=series["roll"])
    mark_done(build / case.name / "coarse", "finished")
    html_path = build_report(cases_dir=cases, build_dir=build,
                             sources=Sources.default(include_potential=False))
    md = html_path.with_suffix(".md").read_text()
    figure = html_path.parent / case.name / "coarse_roll_turn.png"
    assert figure.stat().st_size > 0
    assert "### Turning over" in md
    assert f"{case.name} coarse: roll of a body that turns over, beside the nonlinear " \
           "inviscid model" in md
    assert "turns over: coarse" in md and "failed: CFD coarse" not in md
