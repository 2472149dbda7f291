"""The run driver without a solver run: log parsing (on a real interFoam log excerpt), the
motion CSV on resume, divergence checks, refuse/resume/force, a run continued to a later
run.end_time (on synthetic run folders), and bad [run] input."""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from conftest import DATA
from foamlib import FoamFile

from floatfoam import layout
from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.errors import InputError
from floatfoam.foam import driver, runner, timedirs
from floatfoam.foam.logwatch import LogWatcher, Step
from floatfoam.foam.motionlog import MotionWriter
from floatfoam.foam.paraview import RECONSTRUCT
from floatfoam.plan import stamps
from floatfoam.plan.runplan import resolve

EXCERPT = DATA / "log.interFoam.excerpt"


def test_log_excerpt_parses_steps_and_body_state():
    watcher = LogWatcher()
    text = EXCERPT.read_text()
    steps = watcher.feed(text[:1000]) + watcher.feed(text[1000:]) + watcher.close()
    assert [s.time for s in steps] == pytest.approx([0.355, 0.36, 0.365])
    first = steps[0]
    assert first.courant_max == pytest.approx(0.3621038547)
    assert first.delta_t == pytest.approx(0.005)
    # the last of the three outer-corrector reports of the step is kept
    assert first.centre_of_mass[2] == pytest.approx(-0.01524365457)
    assert first.velocity[2] == pytest.approx(0.03941862615)
    row = first.motion_row()
    assert len(row) == 13 and row[4:7] == pytest.approx([0.0, 0.0, 0.0])  # no rotation
    assert watcher.fatal is None


def test_a_stopped_solvers_last_step_is_kept_only_if_finished():
    """A solver stopped mid-step leaves a step without its ExecutionTime line: that step's state
    is an unfinished outer iteration's and is not recorded; a finished last step is."""
    text = EXCERPT.read_text()
    cut = text.rindex("ExecutionTime")
    watcher = LogWatcher()
    steps = watcher.feed(text[:cut]) + watcher.close_finished()
    assert [s.time for s in steps] == pytest.approx([0.355, 0.36])
    watcher = LogWatcher()
    steps = watcher.feed(text) + watcher.close_finished()
    assert [s.time for s in steps] == pytest.approx([0.355, 0.36, 0.365])
    # stopped between the write of its fields and its ExecutionTime line: a written step
    watcher = LogWatcher()
    steps = watcher.feed(text[:cut]) + watcher.close_finished(written=lambda t: t > 0.362)
    assert [s.time for s in steps] == pytest.approx([0.355, 0.36, 0.365])


def test_fatal_lines_are_caught_but_not_the_fpe_banner():
    watcher = LogWatcher()
    watcher.feed("trapFpe: Floating point exception trapping enabled (FOAM_SIGFPE).\n")
    assert watcher.fatal is None
    watcher.feed("#1  Foam::sigFpe::sigHandler(int) at ??:?\n")
    assert "sigFpe" in watcher.fatal


def test_divergence_checks():
    limits = runner.Limits(max_courant=20.0, max_body_speed=10.0)
    ok = Step(0.1, 0.4, 1e-3, np.zeros(3), np.eye(3), np.array([0.0, 0.0, 0.3]), np.zeros(3))
    assert runner.diverged([ok], limits) is None
    assert "Courant" in runner.diverged([Step(0.1, 45.0)], limits)
    assert "nan" in runner.diverged([Step(0.1, float("nan"))], limits).lower()
    fast = Step(0.1, 0.4, velocity=np.array([0.0, 0.0, 31.9]))
    assert "body speed" in runner.diverged([fast], limits)


def test_motion_writer_replaces_rows_after_restart(tmp_path):
    path = tmp_path / "motion.csv"

    def step(t):
        return Step(t, 0.1, 1e-3, np.array([0.0, 0.0, t]), np.eye(3), np.zeros(3), np.zeros(3))

    MotionWriter(path).append([step(t) for t in (0.1, 0.2, 0.3)])
    MotionWriter(path).append([step(t) for t in (0.2, 0.25)])  # resumed from 0.2
    times = np.loadtxt(path, delimiter=",", skiprows=1)[:, 0]
    assert times.tolist() == [0.1, 0.2, 0.25]


def test_the_roll_of_a_body_that_turns_over_runs_on_through_180_degrees(tmp_path):
    """Heeled 170°, 178°, 186°, 194°: the record says 186° and 194° (not −174°, −166°), in
    one solver run and across a resume (the resumed writer continues from the kept rows)."""
    from floatfoam.bodies.geometry import rotation

    path = tmp_path / "motion.csv"

    def step(t, heel):
        return Step(t, 0.1, 0.01, np.zeros(3), rotation(math.radians(heel), 0.0), np.zeros(3),
                    np.zeros(3))

    MotionWriter(path).append([step(0.01, 170.0), step(0.02, 178.0), step(0.03, 186.0)])
    MotionWriter(path).append([step(0.03, 186.0), step(0.04, 194.0)])  # resumed from 0.02
    roll = np.loadtxt(path, delimiter=",", skiprows=1)[:, 4]
    assert roll.tolist() == pytest.approx([170.0, 178.0, 186.0, 194.0], abs=1e-9)


def test_a_restart_with_another_step_drops_the_interrupted_runs_later_rows(tmp_path):
    """Written at 0.06, stopped after 0.0633 (Δt 1/300 s); the restart from 0.06 steps 0.004
    s (measured on cylinder_heave): the stale 0.0633 row must not stay between 0.06 and 0.064."""
    path = tmp_path / "motion.csv"

    def step(t, dt):
        return Step(t, 0.1, dt, np.array([0.0, 0.0, t]), np.eye(3), np.zeros(3), np.zeros(3))

    MotionWriter(path).append([step(0.04, 0.004), step(0.06, 0.004), step(0.063333333, 1 / 300)])
    MotionWriter(path).append([step(0.064, 0.004), step(0.068, 0.004)])
    times = np.loadtxt(path, delimiter=",", skiprows=1)[:, 0]
    assert times.tolist() == [0.04, 0.06, 0.064, 0.068]
    # a restart from 0.06 whose first step the log rounds (time to 8 digits, Δt to 10): the
    # 0.06 row stays
    MotionWriter(path).append([step(0.063333333, 0.0033333333)])
    times = np.loadtxt(path, delimiter=",", skiprows=1)[:, 0]
    assert times.tolist() == [0.04, 0.06, 0.063333333]


def test_progress_line():
    """One line, under 120 characters for a long case name, five-digit step count and runs of
    hours: time, step count, Δt, Courant number, wall time and ETA."""
    step = Step(1.234, 0.412, 0.0025)
    line = runner.progress_line("elliptic_cylinder_roll/coarse", step, 12345, 4.5, 3671.0,
                                3725.0)
    assert line == ("[elliptic_cylinder_roll/coarse] t = 1.234/4.5 s (27.4 %)  step 12345  "
                    "Δt 2.5 ms  Co 0.412  wall 1:01:11  ETA 1:02:05")
    assert "\n" not in line and len(line) < 120
    bare = runner.progress_line("c/coarse", Step(0.01), 1, 3.2, 2.0, float("nan"))
    assert bare.endswith("step 1  wall 0:02  ETA --:--")  # no Δt, Co or rate yet


def wall_and_time(rates, every=10.0):
    """(wall, simulated time) at each progress line for piecewise-constant step rates
    ``rates`` = [(until wall s, simulated s per wall s), …]."""
    samples, wall, sim = [(0.0, 0.0)], 0.0, 0.0
    for until, rate in rates:
        while wall < until:
            wall, sim = wall + every, sim + every * rate
            samples.append((wall, sim))
    return samples


def test_the_eta_follows_the_recent_step_rate():
    """A run whose first two minutes go at a tenth of its later rate (start-up, small Δt), then
    twice as fast again (issue 39: an ETA from the whole run's average swung from 1:26:55 to
    10:40 for a run of 15:30): a window after each change, the ETA is the time left at the
    new rate, where the whole run's average is still far off."""
    end_time = 5.0
    rate = runner.StepRate()
    samples = wall_and_time([(120.0, 0.001), (300.0, 0.01), (420.0, 0.02)])
    eta = {}
    for wall, sim in samples:
        rate.add(wall, sim)
        eta[wall] = (rate.eta(end_time), sim)
    assert np.isnan(eta[0.0][0])  # one sample: no rate yet
    left = end_time - eta[300.0][1]
    assert eta[300.0][0] == pytest.approx(left / 0.01)
    assert left / (eta[300.0][1] / 300.0) > 1.5 * eta[300.0][0]  # the whole run's average
    assert eta[420.0][0] == pytest.approx((end_time - eta[420.0][1]) / 0.02)
    # within a window of a change, the rate is between the old one and the new
    mixed = runner.StepRate()
    for wall, sim in samples:
        if wall <= 330.0:
            mixed.add(wall, sim)
    assert 0.01 < mixed.rate() < 0.02


def prepare(case, level, np_, force, build, divisor=1, morphing=1.0):
    """The run folder of ``case``'s plan and :func:`floatfoam.foam.driver.prepare`'s
    (resumed, finished) for it."""
    plan = resolve(case, level, np_, build_dir=build, divisor=divisor, morphing=morphing)
    return (plan.run_dir, *driver.prepare(plan, force))


#: Debian's interFoam (nothing is run with it here), which lacks floatfoam's layered motion
#: (src/solver/): the Laplacian moves the mesh
STOCK = ['run.solver="/usr/bin/interFoam"', 'run.mesh_motion="laplacian"']


@pytest.fixture
def case():
    # Debian's interFoam exists on every machine with the apt package; nothing is run here.
    return load_case("cylinder_heave", STOCK)


def test_prepare_refuses_resumes_and_forces(tmp_path, case):
    run_dir, resumed, finished = prepare(case, "coarse", 1, False, tmp_path)
    assert not resumed and not finished
    assert prepare(case, "coarse", 1, False, tmp_path)[1]  # unfinished: resume
    with pytest.raises(InputError, match="--force"):
        prepare(case, "coarse", 2, False, tmp_path)  # other --np
    layout.mark_done(run_dir, "finished")
    assert prepare(case, "coarse", 1, False, tmp_path)[2]  # finished: reuse, no run
    other = load_case("cylinder_heave", [*STOCK,
                                         "run.write_interval=0.2"])
    with pytest.raises(InputError, match="finished run"):
        prepare(other, "coarse", 1, False, tmp_path)
    prepare(other, "coarse", 1, True, tmp_path)  # --force moves the old run aside
    prepare(other, "coarse", 1, True, tmp_path)  # twice in the same second
    moved = sorted(p.name for p in (tmp_path / "cylinder_heave").iterdir())
    assert len(moved) == 3 and moved[0] == "coarse"
    assert all(name.startswith("coarse.old-") for name in moved[1:])


def test_a_solver_without_the_gravity_at_the_surface_is_refused_before_anything_is_written(
        tmp_path):
    """run.interface_gravity asks for floatfoam's interFoam (src/solver/interfaceGravity.H):
    Debian's would ignore PIMPLE's switch. One line naming the setting, nothing written."""
    case = load_case("cylinder_heave", [*STOCK, "run.interface_gravity=true"])
    with pytest.raises(InputError) as err:
        resolve(case, "coarse", 1, build_dir=tmp_path)
    message = str(err.value)
    assert "\n" not in message and "run.interface_gravity" in message
    assert "/usr/bin/interFoam" in message
    assert not any(tmp_path.iterdir())
    resolve(load_case("cylinder_heave", ["run.interface_gravity=true"]), "coarse", 1,
            build_dir=tmp_path)  # floatfoam's own has it




def heave(end_time: float, interval: float = 0.05):
    """cylinder_heave run to ``end_time`` s, writing every ``interval`` s (nothing is run)."""
    return load_case("cylinder_heave", [*STOCK, f"run.end_time={end_time}",
                                        f"run.write_interval={interval}"])


def synthetic_run(build: Path, end_time: float, interval: float, *, finished: bool = True,
                  times=None) -> Path:
    """A run folder of cylinder_heave at the coarse level as the driver leaves it: stamped,
    controlDict and info.json of ``end_time``, complete time folders every ``interval`` up to
    it (or ``times``), and when ``finished`` its reconstructPar and finished markers. Nothing
    in it came from a solver."""
    run_dir, _, _ = prepare(heave(end_time, interval), "coarse", 1, False, build)
    (run_dir / "system").mkdir()
    shutil.copy(layout.COMMON_DIR / "system" / "controlDict", run_dir / "system")
    control = FoamFile(run_dir / "system" / "controlDict")
    control["endTime"] = end_time
    control["writeInterval"] = interval
    (run_dir / layout.MARKERS / "info.json").write_text(json.dumps({"end_time": end_time,
                                                                   "cells": 11280}))
    steps = round(end_time / interval)
    for t in times or [round(interval * k, 9) for k in range(1, steps + 1)]:
        for name in ("U", "uniform/time", "polyMesh/points"):  # complete: timedirs' rule
            path = run_dir / f"{t:g}" / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(b"FoamFile {}\n" + timedirs.FOOTER + b"\n")
    if finished:
        layout.mark_done(run_dir, RECONSTRUCT)
        layout.mark_done(run_dir, layout.FINISHED)
    return run_dir


def control_times(run_dir: Path) -> tuple[float, float]:
    control = FoamFile(run_dir / "system" / "controlDict")
    return control["endTime"], control["writeInterval"]


def info_end_time(run_dir: Path) -> float:
    return json.loads((run_dir / layout.MARKERS / "info.json").read_text())["end_time"]


def test_the_stamp_leaves_out_how_far_the_run_goes():
    """run.end_time says how far a run goes, not what it computes: out of the stamp (the case
    file's 3.2 s, or any other); run.write_interval sets the written times the adjustable time
    step lands on: in it."""
    digest = stamps.settings_digest(heave(0.1), "coarse")
    assert stamps.settings_digest(heave(0.2), "coarse") == digest
    own = load_case("cylinder_heave", [*STOCK, "run.write_interval=0.05"])  # 3.2 s
    assert stamps.settings_digest(own, "coarse") == digest
    assert stamps.settings_digest(heave(0.2, 0.1), "coarse") != digest


def test_a_finished_run_continues_to_a_later_end_time(tmp_path, capsys):
    """Issue 39: a finished run asked for a longer run.end_time is resumed, not refused: its
    finished and reconstructPar markers are cleared, controlDict and info.json go to the new
    end time, and every written time stays for the solver to restart from the last."""
    run_dir = synthetic_run(tmp_path, 0.1, 0.05)
    assert driver.existing_run(heave(0.2), "coarse", 1, tmp_path) == (run_dir, False)
    assert layout.is_finished(run_dir)  # existing_run writes nothing
    assert prepare(heave(0.2), "coarse", 1, False, tmp_path) == (run_dir, True, False)
    assert not layout.is_finished(run_dir) and not layout.step_done(run_dir, RECONSTRUCT)
    assert control_times(run_dir) == (0.2, 0.05) and info_end_time(run_dir) == 0.2
    assert [t for t, _ in layout.time_folders(run_dir)] == [0.05, 0.1]
    assert "it continues to 0.2 s" in capsys.readouterr().err


def test_the_write_interval_of_a_continued_run_divides_the_time_left(tmp_path):
    """Continued from 0.1 s to 0.25 s with run.write_interval 0.1 s: OpenFOAM counts write
    times from the time it restarts from, so it writes every 0.075 s and the last falls on
    0.25 s (as a new run's interval divides its end time)."""
    run_dir = synthetic_run(tmp_path, 0.1, 0.1)
    assert prepare(heave(0.25, 0.1), "coarse", 1, False, tmp_path)[1]
    end, interval = control_times(run_dir)
    assert end == 0.25 and interval == pytest.approx(0.075)


def test_a_run_finished_past_the_end_time_asked_is_kept(tmp_path, capsys):
    """A shorter run.end_time than a finished run's: it is reused as it is (nothing cut, one
    line saying its record is longer than asked and how to run it anew)."""
    run_dir = synthetic_run(tmp_path, 0.1, 0.05)
    capsys.readouterr()
    assert prepare(heave(0.05), "coarse", 1, False, tmp_path) == (run_dir, False, True)
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "kept as it is" in err and "motion.csv" in err
    assert "longer than asked" in err and "--force" in err
    assert layout.is_finished(run_dir) and layout.step_done(run_dir, RECONSTRUCT)
    assert control_times(run_dir) == (0.1, 0.05) and info_end_time(run_dir) == 0.1
    assert [t for t, _ in layout.time_folders(run_dir)] == [0.05, 0.1]


def test_an_unfinished_run_goes_to_the_end_time_asked_past_its_written_times(tmp_path):
    """An unfinished run (written to 0.1 s of 0.3 s) resumes to whatever end time lies past
    its written times; one asked for no further than what it has written is refused, in one
    line, before anything is written (its folder as it was)."""
    run_dir = synthetic_run(tmp_path, 0.3, 0.05, finished=False, times=[0.05, 0.1])
    assert prepare(heave(0.3), "coarse", 1, False, tmp_path) == (run_dir, True, False)
    assert control_times(run_dir) == (0.3, 0.05)  # its own end time: as it was
    assert prepare(heave(0.2), "coarse", 1, False, tmp_path) == (run_dir, True, False)
    assert control_times(run_dir) == (0.2, 0.05) and info_end_time(run_dir) == 0.2
    before = sorted(p.relative_to(run_dir) for p in run_dir.rglob("*"))
    for asked in (0.1, 0.05):
        with pytest.raises(InputError, match=r"already written to 0.1 s.*valid: run.end_time "
                                             r"> 0.1 s.*--force"):
            driver.existing_run(heave(asked), "coarse", 1, tmp_path)
        with pytest.raises(InputError, match="already written"):
            prepare(heave(asked), "coarse", 1, False, tmp_path)
    assert sorted(p.relative_to(run_dir) for p in run_dir.rglob("*")) == before
    assert control_times(run_dir) == (0.2, 0.05)


def test_a_refused_end_time_exits_2_with_one_line(tmp_path, monkeypatch, capsys):
    run_dir = synthetic_run(tmp_path, 0.3, 0.05, finished=False, times=[0.05, 0.1])
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path))
    before = sorted(p.relative_to(run_dir) for p in run_dir.rglob("*"))
    assert main(["run", "cylinder_heave", "--np", "1", "--set", STOCK[0], "--set", STOCK[1],
                 "--set", "run.end_time=0.1", "--set", "run.write_interval=0.05"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "run.end_time = 0.1 s" in err and "valid" in err
    assert sorted(p.relative_to(run_dir) for p in run_dir.rglob("*")) == before


@pytest.mark.parametrize("setting, key", [("run.end_time=-1", "run.end_time"),
                                          ("run.end_time=\"abc\"", "run.end_time"),
                                          ("mesh.cells_side=2.5", "mesh.cells_side"),
                                          ("mesh.refinement_ratio=0", "mesh.refinement_ratio"),
                                          ("domain.thickness=0", "domain.thickness"),
                                          ("mesh.square_half_size=0.05", "mesh.square_half_size")])
def test_bad_run_input_exit_2_before_anything_is_written(capsys, monkeypatch, tmp_path,
                                                         setting, key):
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / "build"))
    args = ["run", "cylinder_heave", "--level", "medium", "--set", setting, "--set",
            STOCK[0], "--set", STOCK[1]]
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and key in err and "valid" in err
    assert not (tmp_path / "build").exists()


@pytest.mark.parametrize("where", ["no/such/folder/turns.lock", "."])
def test_a_solver_lock_that_cannot_be_used_exits_2_before_anything_is_written(
        capsys, monkeypatch, tmp_path, where):
    """FLOATFOAM_SOLVER_LOCK names a file in an existing folder, or the command stops."""
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / "build"))
    monkeypatch.setenv("FLOATFOAM_SOLVER_LOCK", str(tmp_path / where))
    assert main(["run", "cylinder_heave", "--set", STOCK[0], "--set", STOCK[1]]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "FLOATFOAM_SOLVER_LOCK" in err and "valid" in err
    assert not (tmp_path / "build").exists()


def test_a_solver_without_the_layered_motion_exits_2_before_anything_is_written(
        capsys, monkeypatch, tmp_path):
    """A heave release moves its mesh by floatfoam's layered motion, which only floatfoam's
    interFoam has (src/solver/): Debian's is refused in one line that names both ways out."""
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / "build"))
    assert main(["run", "cylinder_heave", "--set", STOCK[0]]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "run.solver" in err and "layered" in err
    assert "make setup" in err and "laplacian" in err
    assert not (tmp_path / "build").exists()
