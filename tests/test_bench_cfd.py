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
