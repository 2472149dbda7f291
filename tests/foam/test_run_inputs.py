"""What the run driver refuses, and how, before any solver runs: typed settings, one-line
errors, the run lock, incomplete time folders, decomposition, the Slurm batch script.

The processes here are real (a second lock holder, the floatfoam console script) but no
OpenFOAM application runs; tests/foam/test_run_reliability.py runs the solver.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import DATA, ROOT

from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.errors import InputError
from floatfoam.foam import render, runlock, timedirs
from floatfoam.foam.driver import check_ranks
from floatfoam.foam.logwatch import LogWatcher, fatal_block
from floatfoam.foam.motionlog import RESUMED, rebuild_motion
from floatfoam.foam.runner import check_path
from floatfoam.motion import read_motion

HOLD_LOCK = """
import sys, time
from floatfoam.foam.runlock import RunLock
with RunLock(sys.argv[1], "c/coarse"):
    print("locked", flush=True)
    time.sleep(60)
"""
FLOATFOAM = Path(sys.executable).with_name("floatfoam")


@pytest.mark.parametrize("setting, words", [
    ("mesh.cells_sid=10", ["mesh.cells_sid", "did you mean mesh.cells_side"]),
    ('run.static_body="no"', ["run.static_body", "true or false"]),
    ("run.acceleration_relaxation=5", ["run.acceleration_relaxation", "≤ 1"]),
    ("run.outer_correctors=0", ["run.outer_correctors", "≥ 1"]),
    ("mesh.gmsh.curvature_refinement=0.5", ["mesh.gmsh.curvature_refinement", "≥ 1"]),
    ("run.inner_distance=0.8", ["inner_distance", "outer_distance"]),  # outer 0.7 m, below
    ('run.mesh_motion="rigid"', ["run.mesh_motion", "layered", "laplacian", "distances"]),
    ("run.layer_band=0.5", ["run.layer_band", "≥ 1"]),
    ('run.motion_diffusivity="cubic"', ["run.motion_diffusivity", "quadratic", "linear"]),
    ("run.write_interval=5", ["run.write_interval", "end_time"]),
    ("potential.omega_min=5", ["omega_min", "omega_max"]),
    ("mesh.cells_side=1e9", ["mesh.cells_side", "20000"]),
    ("body.bilge_radius=\"abc\"", ["body.bilge_radius", "valid"]),
    ("release.heel=200", ["release.heel = 200", "−180 < heel ≤ 180"]),
    ("release.trim=-95", ["release.trim = -95", "−90 ≤ trim ≤ 90"]),
])
def test_settings_are_checked_when_the_case_loads(setting, words):
    overrides = [setting]
    if setting.startswith("potential.omega_min"):
        overrides.append("potential.omega_max=1")
    if "distance" in setting:
        overrides.append("run.outer_distance=0.7")
    case_name = "box_bilge" if "bilge" in setting else \
        "elliptic_cylinder_capsize" if "distance" in setting else "cylinder_heave"
    with pytest.raises(InputError) as err:
        load_case(case_name, overrides)
    message = str(err.value)
    assert "\n" not in message and all(w in message for w in words), message


def test_unknown_key_in_a_case_file_names_the_nearest(tmp_path):
    text = (ROOT / "cases" / "cylinder_heave" / "case.toml").read_text()
    (tmp_path / "case.toml").write_text(text.replace("cells_side =", "cells_sid ="))
    with pytest.raises(InputError, match=r"mesh.cells_sid is unknown \(did you mean "
                                         r"mesh.cells_side\?\)"):
        load_case(str(tmp_path))


def test_settings_are_typed_and_read_by_the_stages():
    case = load_case("cylinder_heave", ["run.static_body=true", "mesh.cells_side=20"])
    assert case.settings.run.static_body is True and case.settings.mesh.cells_side == 20
    assert case.settings.run.end_time == 3.2 and case.settings.potential.panels is None
    with pytest.raises(AttributeError):  # frozen: no stage changes them
        case.settings.run.end_time = 1.0


def test_body_resolution_bound_names_the_memory():
    with pytest.raises(InputError, match=r"body.resolution = 1000000000.0: .* ~[0-9.e+]+ GiB"):
        load_case("superellipsoid_buoy", ["body.resolution=1e9"])


@pytest.mark.parametrize("args, words", [
    (["theory", "{nobody}"], ["no [body] table"]),
    (["theory", "stl_pontoon", "--set", "body.scale=-1"], ["body.scale = -1"]),
    (["theory", "superellipsoid_buoy", "--set", "body.bounds=\"x\""], ["body.bounds"]),
    (["run", "cylinder_heave", "--np", "0"], ["--np 0"]),
    (["run", "cylinder_heave", "--hostfile", "/nonexistent"], ["--hostfile"]),
    (["run", "box_bilge", "--set", 'run.time_scheme="CrankNicolson 2"'],
     ["run.time_scheme", "0 ≤ ψ ≤ 1"]),
    (["run", "box_bilge", "--set", 'run.time_scheme="backward"'], ["run.time_scheme", "Euler"]),
    (["run", "box_bilge", "--set", 'run.interface_time_scheme="CrankNicolson 1.5"'],
     ["run.interface_time_scheme", "0 ≤ ψ ≤ 1"]),
    (["validate", "cylinder_heave", "--set", 'run.motion_diffusivity="cubic"'],
     ["run.motion_diffusivity = 'cubic'", "valid is one of quadratic, linear"]),
    (["run", "sphere", "--set", "mesh.gmsh.layers_3d=3"],  # its heave meshes a wedge
     ["mesh.gmsh.layers_3d = 3", "3D domains only", "valid is 0"]),
    (["run", "superellipsoid_buoy", "--set", "mesh.gmsh.layers_3d=21"],
     ["mesh.gmsh.layers_3d = 21", "whole number 0 ≤ x ≤ 20"]),
])
def test_errors_are_one_line_exit_2(tmp_path, capsys, args, words):
    (tmp_path / "case.toml").write_text("[fluid]\nrho = 1000.0\n")
    args = [a.replace("{nobody}", str(tmp_path)) for a in args]
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err and all(w in err for w in words), err


def test_unwritable_build_folder_is_one_line(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    env = {**os.environ, "FLOATFOAM_BUILD": str(blocker / "build")}  # under a file
    proc = subprocess.run([str(FLOATFOAM), "gz", "cylinder_heave"], capture_output=True,
                          text=True, env=env)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "FLOATFOAM_BUILD" in proc.stderr


def test_output_into_a_closed_pipe_is_quiet():
    proc = subprocess.run(f"{FLOATFOAM} theory cylinder_heave | head -1; "
                          "echo \"exit ${PIPESTATUS[0]}\"", shell=True, capture_output=True,
                          text=True, executable="/bin/bash")
    assert proc.stdout.startswith("cylinder_heave:") and proc.stderr == ""
    # 141 (128 + SIGPIPE) when the reader left early; 0 when the output fitted in the pipe
    assert proc.stdout.split()[-1] in ("141", "0")


def test_paths_openfoam_cannot_take_are_refused():
    with pytest.raises(InputError, match="without spaces"):
        check_path(Path("/tmp/my runs/cylinder_heave/coarse"))
    check_path(Path("/tmp/runs/cylinder_heave/coarse"))


def test_lock_refuses_a_second_holder_and_takes_over_a_dead_one(tmp_path):
    path = tmp_path / ".coarse.lock"
    with runlock.RunLock(path, "c/coarse") as first:
        assert first.stale_holder() is None
        with pytest.raises(runlock.RunLockedError, match=rf"PID {os.getpid()}, started "):
            runlock.RunLock(path, "c/coarse").__enter__()
    # A holder killed while it holds the lock: the kernel frees the lock, its PID stays in
    # the file, and the next run takes over (and says whose place it takes).
    holder = subprocess.Popen([sys.executable, "-c", HOLD_LOCK, str(path)],
                              stdout=subprocess.PIPE, text=True)
    assert holder.stdout.readline().strip() == "locked"
    with pytest.raises(runlock.RunLockedError, match=rf"PID {holder.pid}, started "):
        runlock.RunLock(path, "c/coarse").__enter__()
    holder.kill()
    holder.wait()
    with runlock.RunLock(path, "c/coarse") as lock:
        assert lock.stale_holder() == str(holder.pid)


def _time_folder(root: Path, name: str, files=("U", "p_rgh", "uniform/time"), cut=()):
    for f in files:
        path = root / name / f
        path.parent.mkdir(parents=True, exist_ok=True)
        body = b"FoamFile {}\n" + b"x" * 100 + b"\n" + timedirs.FOOTER + b"\n"
        path.write_bytes(body[: len(body) // 2] if f in cut else body)


def test_incomplete_time_folders_are_set_aside(tmp_path):
    (tmp_path / "0.orig").mkdir()
    for f in ("U", "p_rgh"):
        (tmp_path / "0.orig" / f).write_text("")
    _time_folder(tmp_path, "0.1")
    _time_folder(tmp_path, "0.2", cut=("U",))  # a write cut short
    _time_folder(tmp_path, "0.3", files=("U",))  # files missing
    moved = timedirs.set_aside_incomplete(tmp_path, moving=False)
    assert [p.name[:3] for p in moved] == ["0.3", "0.2"]  # newest first, down to 0.1
    assert sorted(p.name for p in tmp_path.iterdir() if p.name[0].isdigit()) == ["0.1",
                                                                                 "0.orig"]
    assert all(p.parent == tmp_path / ".floatfoam" / "incomplete" for p in moved)
    assert timedirs.set_aside_incomplete(tmp_path, moving=False) == []  # 0.1 is complete


def test_fatal_error_lines_from_a_real_log():
    """decomposePar of Debian's v1912 with method scotch (a stub): the cause is on the lines
    after the FATAL ERROR line, and both reach the message."""
    lines = (DATA / "log.decomposePar.scotch-stub").read_text().splitlines()
    block = fatal_block(lines)
    assert block.startswith("--> FOAM FATAL ERROR:")
    assert "without the scotchDecomp library loaded" in block and "\n" not in block
    watcher = LogWatcher()
    watcher.feed("\n".join(lines) + "\n")
    assert "scotchDecomp library" in watcher.fatal_message()


def test_decomposition_for_any_rank_count():
    """A simple split of the tank, never across a direction one cell thick (x of a 2D mesh,
    y of a wedge), into blocks as near square as the tank allows."""
    tank = (0.0, 12.0, 1.6692)  # the 2D O-grid tank of cylinder_heave: x, y, z extents
    assert not render.scotch_available()  # Debian's v1912: a stub
    for ranks in (1, 2, 3, 7, 64):
        coeffs = render.decomposition(ranks, tank)["coeffs"]["n"]
        assert coeffs[0] == 1 and coeffs[1] * coeffs[2] == ranks
    assert render.decomposition(64, tank)["coeffs"]["n"] == [1, 16, 4]  # 12 m × 1.67 m
    assert render.decomposition(2, (6.0, 0.0, 1.67))["coeffs"]["n"] == [2, 1, 1]  # a wedge
    assert render.decomposition(4, (12.0, 12.0, 1.67))["coeffs"]["n"] == [2, 2, 1]  # 3D


def test_write_interval_divides_end_time():
    assert render.write_interval(3.2, 0.1) == pytest.approx(0.1)
    assert render.write_interval(0.25, 0.1) == pytest.approx(0.25 / 3)
    assert render.write_interval(1.0, 1.0) == 1.0


def test_batch_refuses_bad_input_and_never_overwrites(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / "build"))
    out = tmp_path / "sweep.sh"
    assert main(["batch", "cylinder_heave", "--levels", "ultrafine", "--out", str(out)]) == 2
    assert main(["batch", "cylinder_heave", "--time", "soon", "--out", str(out)]) == 2
    assert not out.exists()
    # no run.end_time, and no period to set it from: the released roll capsizes (the body of
    # ellipsoid_printed_verdict, which has a record of its own)
    assert main(["batch", "ellipsoid", "--set", "mass.cog=[0,0,0.08]", "--out", str(out)]) == 2
    assert main(["batch", "cylinder_heave", "--levels", "coarse", "medium", "fine",
                 "--np", "2", "--out", str(out)]) == 0
    text = out.read_text()
    assert "#SBATCH --array=0-2" in text and "#SBATCH --ntasks=2" in text
    assert [text.count(f"  {i})  # cylinder_heave {level}\n") for i, level in
            enumerate(("coarse", "medium", "fine"))] == [1, 1, 1]  # a branch per task
    assert text.count('--np "${SLURM_NTASKS:-2}"') == 3  # Slurm's allocation, else --np
    for check in (["bash", "-n"], ["shellcheck"]):  # valid bash, no quoting slip
        proc = subprocess.run([*check, str(out)], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout + proc.stderr
    assert main(["batch", "cylinder_heave", "--out", str(out)]) == 2  # exists: refused
    assert "nothing is overwritten" in capsys.readouterr().err


def test_more_ranks_than_cores_is_warned(capsys, tmp_path):
    check_ranks(1, None)
    assert capsys.readouterr().err == ""
    check_ranks((os.cpu_count() or 1) + 1, None)
    assert "more than the" in capsys.readouterr().err
    hosts = tmp_path / "hosts"
    hosts.write_text("node1 slots=64\n")
    check_ranks(64, hosts)  # the cores are elsewhere: no warning
    assert capsys.readouterr().err == ""


def test_motion_series_rebuilt_from_a_resumed_log(tmp_path):
    """The real log excerpt, cut in two with a resume from its middle step: the rebuilt series
    has every step once, in order (a resumed part replaces the rows from its restart on)."""
    text = (DATA / "log.interFoam.excerpt").read_text()
    steps = [i for i, line in enumerate(text.splitlines()) if line.startswith("Time = ")]
    lines = text.splitlines()
    middle = steps[len(steps) // 2]
    resumed = "\n".join(lines[:steps[-2]] + [f"{RESUMED} at now"] + lines[middle:]) + "\n"
    log = tmp_path / "log.interFoam"
    log.write_text(resumed)
    csv = tmp_path / "motion.csv"
    rebuild_motion(log, csv)
    t = read_motion(csv)["time"]
    full = LogWatcher()
    expected = [s.time for s in full.feed(text) + full.close() if s.motion_row()]
    assert list(t) == pytest.approx(expected) and len(t) >= 3
