"""The report on a tiny tree: cases/ folders and a build/ holding SYNTHETIC motion records.

The motion.csv files here are synthetic free decays written by the test, not OpenFOAM output
(a committed real-output test belongs with the CFD runs). The first tests replace the case
loader and the theory with stand-ins, so they check the report's assembly only; the last one
runs the real loader and theory on a small case file.
"""

from __future__ import annotations

import argparse
import math
import types
from pathlib import Path

import numpy as np
import pytest

from floatfoam.analysis.report import Sources, build_report
from floatfoam.case import load_case
from floatfoam.cli import report as report_command
from floatfoam.errors import InputError
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

    sources = Sources(load=load_case, theory=theory_summary, potential=None)
    monkeypatch.setattr(Sources, "default", classmethod(lambda cls, **kw: sources))
    return sources


def test_case_folders_skip_underscore(tmp_path):
    cases, _ = make_tree(tmp_path)
    assert [p.name for p in list_cases(cases)] == ["box", "broken", "cyl"]


def test_report_gathers_theory_and_finished_runs(tmp_path, monkeypatch):
    cases, build = make_tree(tmp_path)
    sources = fake_sources(monkeypatch)
    html_path = build_report(cases_dir=cases, build_dir=build, sources=sources)
    out = build / "report"
    assert html_path == out / "index.html"
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
