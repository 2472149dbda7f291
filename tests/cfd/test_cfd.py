"""Real OpenFOAM runs of the Ito (1977) cylinder on the coarse mesh (marker ``openfoam``).

They run floatfoam's rebuilt interFoam (scripts/build_solver.sh, built by `make setup`).
"""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from cfdcases import shared_run
from procutil import SMALL_OGRID_SETTINGS, locked, processes_in

from floatfoam.analysis.decay import analyse_decay, decay_dict
from floatfoam.analysis.stillwater import currents, summary
from floatfoam.case import load_case
from floatfoam.foam.driver import run_case
from floatfoam.foam.postproc import max_speed
from floatfoam.foam.runner import RunError
from floatfoam.hydrostatics.theory import theory_summary
from floatfoam.layout import step_done
from floatfoam.motion import dof_series, read_motion
from floatfoam.potential.models import decay_series
from floatfoam.tank import tank

pytestmark = pytest.mark.openfoam


def swings(t, z, z_eq):
    """Largest |z − z_eq| between successive crossings of the equilibrium (one per half
    cycle), the first starting at the release."""
    d = z - z_eq
    crossings = np.nonzero(np.sign(d[1:]) != np.sign(d[:-1]))[0]
    bounds = [0, *crossings + 1, len(d)]
    return [float(np.abs(d[a:b]).max()) for a, b in zip(bounds[:-1], bounds[1:], strict=True)
            if b - a > 2]


# make test's heave record of the O-grid cylinder: 2.6 periods at the default step, read by two
# tests (the run made once: cfdcases.shared_run)
HEAVE_RECORD = ["run.end_time=1.6"]


def heave_record(shared_runs):
    """The coarse run of cylinder_heave on :data:`HEAVE_RECORD`, 2 ranks (made once)."""
    folder = shared_run("cylinder_heave", HEAVE_RECORD, shared_runs, 2)
    return run_case(load_case("cylinder_heave", HEAVE_RECORD), "coarse", 2, build_dir=folder)


def test_cylinder_heave_coarse_decays_with_added_mass(shared_runs):
    """2.6 heave periods (1.6 s) of the coarse run, on 2 MPI ranks (decomposePar + mpirun), at
    the default step (Courant 3 in the bulk, 0.5 at the interface, ≤ 10 ms: 193 steps), its
    mesh moved by the layered motion of a heave release (src/solver/)."""
    case = load_case("cylinder_heave", HEAVE_RECORD)
    theory = theory_summary(case).to_dict()
    result = heave_record(shared_runs)
    t, z = dof_series(read_motion(result.motion_csv), "heave")
    assert t[-1] == pytest.approx(1.6, abs=1e-6) and np.all(np.isfinite(z))
    decay = decay_dict(analyse_decay(t, z))
    # Added mass lengthens the period beyond the memoir's no-added-mass 0.491 s (potential
    # flow adds ~0.5 of the displaced mass, i.e. ~+20 %); the probes measured 0.61-0.62 s.
    assert decay["period_mean"] > theory["memoir"]["heave_period"] > 0.49
    assert decay["period_mean"] > theory["heave_period"] * 1.1
    # and by as much as potential flow says: Cummins' model with the exact restoring force (the
    # release is 33 % of the draft), reduced the same way, gives 0.6224 s on this record;
    # measured 0.6220 s (−0.06 %). On the whole 3.2 s record at Courant 0.5 and 5 ms the O-grid's
    # levels converge to 0.4 % below Cummins' period (the grid study on movingWallVelocity:
    # coarse 0.6191, fine 0.6182 s against 0.6205 s, U_num 0.77 %; the coarse level at the
    # defaults 0.6187 s: README), so 1.5 % — twice that U_num — is the mesh or the
    # coupling gone wrong, not the level (the O-grid with a 0.15 m square ran +2.8 % here:
    # docs/studies/cases/cylinder_heave.md); issue 12's criterion is 3 %.
    series = decay_series(case, "cummins", nonlinear_restoring=True, duration=1.6)
    cummins = analyse_decay(series["time"], series["z"]).summary()["period_mean"]
    assert decay["period_mean"] == pytest.approx(cummins, rel=0.015)
    # The amplitude decays every half cycle (radiated waves + viscosity; no energy source).
    z_eq = result.info.z_G_equilibrium
    amplitudes = swings(t, z, z_eq)
    assert len(amplitudes) >= 4
    assert all(b < a for a, b in zip(amplitudes, amplitudes[1:], strict=False))
    rows_move_as_one(result.run_dir, z[0], case.body.c, z[-1] - z[0])  # c: the half height
    # It returns to the equilibrium draft: the fitted mean level within 1 % of the 76.2 mm
    # draft (0.76 mm, issue 12's criterion) of the theory's; measured −0.42 mm on this record
    # (0.55 %). The sinking body raises the water of the finite tank by ~0.3 mm, and the
    # probes saw ±0.25 mm.
    assert decay["equilibrium"] == pytest.approx(z_eq, abs=0.01 * theory["draft"])


def test_heave_period_moves_little_with_the_step(shared_runs, tmp_path):
    """The heave's fitted period carries a first-order step error no larger than the time-step
    study's: cylinder_heave's coarse 1.6 s at the default step (Courant 3, 0.5 at the
    interface, ≤ 10 ms; the run of test_cylinder_heave_coarse_decays_with_added_mass) and at
    half of it (run_case's time_step_divisor 2), 2 ranks, at the defaults (the interface on
    Crank–Nicolson, the body's faces at the step's end, the correctors compensated). And the
    interface's flux keeps the geometric conservation law on the moving mesh
    (scripts/build_solver.sh): no cell fills beyond α = 1."""
    case = load_case("cylinder_heave", HEAVE_RECORD)
    runs = [heave_record(shared_runs),
            run_case(case, "coarse", 2, build_dir=tmp_path, time_step_divisor=2)]
    periods = [decay_dict(analyse_decay(*dof_series(read_motion(run.motion_csv), "heave")))
               ["period_mean"] for run in runs]
    # measured 0.62202 → 0.62181 s (−0.03 %; the whole record's step study:
    # docs/studies/time-step.md). 0.15 %: at first order the period at the halved step is then
    # within 0.15 % of the step's limit, inside the 0.2 % issue 41 asks of the coarse record
    assert periods[1] == pytest.approx(periods[0], rel=1.5e-3)
    for run in runs:
        # interFoam's "Max(alpha.water) = …" after each α solve; measured ≤ 1 + 7.2e-6, where
        # v1912's own blend of the fluxes overfills cells to 1.0005 over the 3.2 s record
        filled = [float(line.rsplit("=", 1)[1]) for line in
                  (run.run_dir / "log.interFoam").read_text().splitlines()
                  if line.startswith("Phase-1 volume fraction")]
        assert len(filled) > 300 and max(filled) < 1 + 2e-5


def rows_move_as_one(run_dir, axis, radius, heave):
    """The layered motion (src/solver/) at the run's last time: every point moved vertically,
    by an amount that depends on its initial height alone (each row of the O-grid's outer
    blocks moves as one, so the free surface's faces there stay horizontal), and the points
    across the body's height (``axis`` ± ``radius`` at the release, m) by the body's own
    ``heave`` (m, since the release)."""
    from foamlib import FoamFile

    from floatfoam.layout import time_folders

    last = time_folders(run_dir)[-1][1]  # the reconstructed run's last time
    start = np.asarray(FoamFile(run_dir / "constant" / "polyMesh" / "points")[None])
    moved = np.asarray(FoamFile(last / "polyMesh" / "points")[None]) - start
    assert np.abs(moved[:, :2]).max() < 1e-12  # vertical
    rows = {}
    for z0, dz in zip(np.round(start[:, 2], 9), moved[:, 2], strict=True):
        rows.setdefault(z0, []).append(dz)
    # the same displacement along each row, to the points' written precision
    assert max(np.ptp(row) for row in rows.values()) < 1e-9
    body = np.abs(start[:, 2] - axis) < radius - 1e-6
    assert body.sum() > 100 and np.allclose(moved[body, 2], heave, atol=1e-6)


def test_still_water_stays_at_rest(tmp_path):
    """Body held at equilibrium, water and air at rest: max |U| < 1 mm/s over 1 s."""
    case = load_case("cylinder_heave", ["run.end_time=1.0", "run.static_body=true",
                                        "release.heave=0.0"])
    result = run_case(case, "coarse", 1, build_dir=tmp_path)
    rows = max_speed(result.run_dir)
    # 1 mm/s (the criterion) is 0.4 % of the body's peak heave speed after release
    # (ω·A ≈ 12.8 rad/s × 25.4 mm ≈ 0.33 m/s): spurious currents below it do not move the body.
    assert rows[-1, 0] == pytest.approx(1.0, abs=1e-6)
    assert np.all(np.isfinite(rows[:, 1]))
    assert rows[:, 1].max() < 1e-3
    # the same from the written fields, by where the water is (what `floatfoam run` prints
    # for a held body): the waterline lies along a horizontal face of the O-grid (an even count
    # of cells a side), so the gravity term balances there too (held at the release, 25.4 mm
    # higher across the ring's tilted rows, the water moves at 0.08 m/s; with an odd count, the
    # surface along a row's middle, 0.17 m/s: docs/studies/cases/cylinder_heave.md)
    band = tank(case).band
    written = currents(result.run_dir, band)
    assert [round(c.time, 6) for c in written] == pytest.approx([0.1 * k for k in range(1, 11)])
    assert max(max(c.interface, c.water, c.air) for c in written) < 1e-3
    assert "held still for 1 s" in summary(written, band)


@pytest.mark.parametrize("surface, smoothing", [(False, 0), (True, 0), (True, 2)],
                         ids=["face_centre", "surface_height", "surface_height_averaged"])
def test_still_water_across_tilted_cells_with_the_gravity_at_the_surface(tmp_path, surface,
                                                                         smoothing):
    """Body held at its release, 25.4 mm above equilibrium, in still water: the free surface
    crosses the O-grid's tilted rows. With the gravity term's density jump at the face's
    centre (interFoam's own) the water there moves; with it at the free surface's height
    (``run.interface_gravity``, src/solver/interfaceGravity.H) it stays still.

    The largest of the written times' (0.1 to 1 s; measured on 2 ranks,
    docs/studies/interface-gravity.md, and the same at the surface on 1): at the face's centre
    385 mm/s in the interface cells and 3.5 mm/s below the free-surface band; at the surface
    4.5 mm/s and 0.017 mm/s (rest to round-off until 0.3 s, then a grid-scale mode near the
    body's wall grows and settles below 1 mm/s). The bounds lie between the two: 20 mm/s in
    the interface cells (4.4 × the one, a nineteenth of the other), 0.2 mm/s below the band
    (12 × and a seventeenth). The surface cells' heights averaged over their neighbours
    (``run.interface_gravity_smoothing``) keep the flat surface's height, so the still water
    stays as still."""
    case = load_case("cylinder_heave", ["run.end_time=1.0", "run.static_body=true",
                                        f"run.interface_gravity={str(surface).lower()}",
                                        f"run.interface_gravity_smoothing={smoothing}"])
    result = run_case(case, "coarse", 1, build_dir=tmp_path)
    written = currents(result.run_dir, tank(case).band)
    interface = max(c.interface for c in written)
    below = max(c.below_band for c in written)
    if surface:
        assert interface < 20e-3 and below < 2e-4
    else:
        assert interface > 20e-3 and below > 2e-4


# the small O-grid's first 0.2 s, one rank: ~3 s of solver a run
COUPLED_RUN = ["run.end_time=0.2", *SMALL_OGRID_SETTINGS]


def test_the_coupling_ends_when_the_body_has_converged(tmp_path):
    """run.coupling_tolerance ε (src/solver/couplingConvergence.H): a step's coupling
    iterations end after the second when the contraction ρ times its change of the body's
    velocity is at most ε × the velocity's change over the step, that iteration solved as the
    final one. At an ε every step meets the run is the run of two iterations to the last digit,
    and the log counts every step as converged; at 0 (a 2D section's default) it is the run of
    three, which differs."""
    runs = {}
    for name, extra in {"tolerance": ["run.coupling_tolerance=1000"],
                        "two": ["run.outer_correctors=2"], "three": []}.items():
        case = load_case("cylinder_heave", [*COUPLED_RUN, *extra])
        result = run_case(case, "coarse", 1, build_dir=tmp_path / name)
        runs[name] = (read_motion(result.motion_csv),
                      (result.run_dir / "log.interFoam").read_text())
    motion, log = runs["tolerance"]
    steps = log.count("\nTime = ")
    assert steps > 20 and f"Coupling: {steps} of {steps} steps converged" in log
    assert log.count("PIMPLE: converged in 2 iterations") == steps
    for column in ("time", "z"):
        np.testing.assert_array_equal(motion[column], runs["two"][0][column])
    assert "Coupling:" not in runs["three"][1]
    assert not np.array_equal(runs["three"][0]["z"], runs["two"][0]["z"])


def test_divergence_detector_stops_a_broken_run(tmp_path):
    """Debian's stock interFoam (miscompiled fvc::reconstruct, docs/openfoam-v1912.md)
    blows up on the O-grid within a few dozen steps: the driver stops it with one line that
    names the log. (It lacks floatfoam's layered motion: the Laplacian moves the mesh.)"""
    case = load_case("cylinder_heave", ["run.end_time=1.0", 'run.solver="/usr/bin/interFoam"',
                                        'run.mesh_motion="laplacian"'])
    with pytest.raises(RunError) as err:
        run_case(case, "coarse", 1, build_dir=tmp_path)
    message = str(err.value)
    assert "\n" not in message and "log.interFoam" in message
    assert "diverged" in message or "stopped" in message
    log = (tmp_path / "cylinder_heave" / "coarse" / "log.interFoam").read_text()
    assert log.count("\nTime = ") < 2000  # stopped early, not at the end time


RUN_IN_CHILD = """
import sys
from pathlib import Path
from floatfoam.case import load_case
from floatfoam.foam.driver import run_case
case = load_case("cylinder_heave", sys.argv[2:])
run_case(case, "coarse", 1, build_dir=Path(sys.argv[1]))
"""
# on the small O-grid (the check is of the driver, not the motion) to 0.8 s: ~6 s of solver
# after the 0.2 s it is killed at
RESUMED_RUN = ["run.end_time=0.8", *SMALL_OGRID_SETTINGS]


def test_interrupted_run_resumes(tmp_path):
    """Kill a run (driver and solver) after it wrote t = 0.2 s; the same command resumes from
    the last written time and the motion series stays continuous."""
    run_dir = tmp_path / "cylinder_heave" / "coarse"
    child = subprocess.Popen([sys.executable, "-c", RUN_IN_CHILD, str(tmp_path), *RESUMED_RUN],
                             start_new_session=True, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL,  # its scratch folder in tmp_path:
                             env={**os.environ, "TMPDIR": str(tmp_path)})  # it is SIGKILLed
    deadline = time.monotonic() + 300
    while not (run_dir / "0.2" / "U").exists():
        assert child.poll() is None and time.monotonic() < deadline
        time.sleep(0.2)
    time.sleep(1.0)  # let the solver finish writing 0.2
    assert processes_in(run_dir)  # interFoam runs there, in a process group of its own
    os.killpg(child.pid, signal.SIGKILL)  # the driver only: its solver must follow it
    child.wait()
    assert not step_done(run_dir, "finished")
    deadline = time.monotonic() + 15  # the watchdog stops it: SIGTERM, SIGKILL after 5 s
    while processes_in(run_dir) or locked(tmp_path / "cylinder_heave" / ".coarse.lock"):
        assert time.monotonic() < deadline, "the solver outlived its SIGKILLed driver"
        time.sleep(0.2)

    result = run_case(load_case("cylinder_heave", RESUMED_RUN), "coarse", 1, build_dir=tmp_path)
    assert result.resumed
    log = (run_dir / "log.interFoam").read_text()
    resumed_part = log.split("floatfoam: resumed")[1]
    first = next(line for line in resumed_part.splitlines() if line.startswith("Time = "))
    assert float(first.split("=")[1]) > 0.19  # restarted from the written 0.2 s, not from 0
    t = read_motion(result.motion_csv)["time"]
    assert t[0] < 1e-3 and t[-1] == pytest.approx(0.8, abs=1e-6)
    # no overlap, no gap: a lost row leaves two steps; steps of up to 10.3 ms were measured at
    # the 10 ms limit (the adjustable step landing on a written time)
    largest = load_case("cylinder_heave", RESUMED_RUN).settings.run.max_delta_t
    assert np.all(np.diff(t) > 0) and np.diff(t).max() < 1.5 * largest
