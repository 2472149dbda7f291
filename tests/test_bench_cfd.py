"""scripts/bench_cfd.py's baseline: a revision's files beside this tree's, and a bad revision
refused in one line before anything is written."""

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "bench_cfd.py"


def _bench():
    spec = importlib.util.spec_from_file_location("bench_cfd", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_unknown_baseline_is_refused_before_anything_is_written(tmp_path):
    env = {**os.environ, "FLOATFOAM_BUILD": str(tmp_path / "build")}
    done = subprocess.run([sys.executable, str(SCRIPT), "--cases", "cylinder_heave",
                           "--baseline", "no-such-revision"], cwd=ROOT, env=env,
                          capture_output=True, text=True)
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1 and "--baseline" in done.stderr
    assert not (tmp_path / "build").exists()


def test_baseline_tree_holds_the_revision_and_shares_the_solver(tmp_path, monkeypatch):
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / "build"))
    bench = _bench()
    tree = bench.baseline_tree("HEAD")
    sha = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout.strip()
    assert tree == tmp_path / "build" / "bench" / "baseline" / sha
    shown = subprocess.run(["git", "show", "HEAD:scripts/bench_cfd.py"], cwd=ROOT,
                           capture_output=True, text=True, check=True).stdout
    assert (tree / "scripts" / "bench_cfd.py").read_text() == shown
    assert (tree / "build" / "solver").resolve() == (ROOT / "build" / "solver").resolve()
    (tree / "marker").touch()  # made once: a second call keeps the folder as it is
    assert bench.baseline_tree("HEAD") == tree and (tree / "marker").is_file()


def test_a_record_too_short_for_a_fit_prints_its_row(tmp_path):
    """A short benchmark record (stl_pontoon's 0.2 s, a quarter of a roll period) has no decay
    fit: its row prints its wall and steps with "—" for the period and its errors, beside the
    baseline's, instead of stopping the benchmark after its runs."""
    from floatfoam.case import load_case

    bench = _bench()
    case = load_case("stl_pontoon", ["run.end_time=0.2"])
    t = [0.002 * k for k in range(101)]  # 0.2 s of the first swing down from 8°
    rows = ["time,x,y,z,roll,pitch,yaw,u,v,w,p,q,r"]
    rows += [f"{s},0,0,-0.008,{8.0 - 2.5 * (s / 0.1) ** 2},0,0,0,0,0,0,0,0" for s in t]
    (tmp_path / "motion.csv").write_text("\n".join(rows) + "\n")
    found = bench.accuracy(case, tmp_path)
    assert found["period"] is None and found["converged_period"] is None
    row = {"case": "stl_pontoon", "level": "coarse", "ranks": 2, "mesh": "3d-half",
           "cells": 86539, "steps": 82, "wall_s": 101.0, "wall_per_simulated_s": 505.0,
           "record_s": 3.6, **found}
    line = bench._line(row)
    assert line.split()[:6] == ["stl_pontoon", "coarse", "2", "3d-half", "86539", "82"]
    assert line.count("—") == 4  # T_d, ζ and both errors
    row["baseline"] = {"wall_s": 150.0, "steps": 120, **found}
    assert bench._baseline_line(row).split()[4] == f"{101.0 / 150.0:.2f}"
