"""The run driver without a solver run: log parsing (on a real interFoam log excerpt), the
motion CSV on resume, divergence checks, refuse/resume/force, and bad [run] input."""

from pathlib import Path

import numpy as np
import pytest

from floatfoam import layout
from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.errors import InputError
from floatfoam.foam import driver, runner
from floatfoam.foam.logwatch import LogWatcher, Step
from floatfoam.foam.motionlog import MotionWriter

EXCERPT = Path(__file__).parent / "data" / "log.interFoam.excerpt"


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


@pytest.fixture
def case():
    # Debian's interFoam exists on every machine with the apt package; nothing is run here.
    return load_case("cylinder_heave", ['run.solver="/usr/bin/interFoam"'])


def test_prepare_refuses_resumes_and_forces(tmp_path, case):
    run_dir, resumed, finished = driver.prepare(case, "coarse", 1, False, tmp_path)
    assert not resumed and not finished
    assert driver.prepare(case, "coarse", 1, False, tmp_path)[1]  # unfinished: resume
    with pytest.raises(InputError, match="--force"):
        driver.prepare(case, "coarse", 2, False, tmp_path)  # other --np
    layout.mark_done(run_dir, "finished")
    assert driver.prepare(case, "coarse", 1, False, tmp_path)[2]  # finished: reuse, no run
    other = load_case("cylinder_heave", ['run.solver="/usr/bin/interFoam"', "run.end_time=2.0"])
    with pytest.raises(InputError, match="finished run"):
        driver.prepare(other, "coarse", 1, False, tmp_path)
    driver.prepare(other, "coarse", 1, True, tmp_path)  # --force moves the old run aside
    driver.prepare(other, "coarse", 1, True, tmp_path)  # twice in the same second
    moved = sorted(p.name for p in (tmp_path / "cylinder_heave").iterdir())
    assert len(moved) == 3 and moved[0] == "coarse"
    assert all(name.startswith("coarse.old-") for name in moved[1:])


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
            'run.solver="/usr/bin/interFoam"']
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and key in err and "valid" in err
    assert not (tmp_path / "build").exists()
