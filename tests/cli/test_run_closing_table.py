"""The closing table of ``floatfoam run`` (issue 39): the turning points of each released DoF,
refined by the parabola through their samples, between the record's first and last sample."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from floatfoam.case import load_case
from floatfoam.cli.run import TABLE_TURNS, print_summary, turning_points, turning_rows
from floatfoam.hydrostatics.theory import equilibrium
from floatfoam.motion import write_motion

# A roll decay as elliptic_cylinder_roll's coarse run gives it: 10° released, damped period
# 0.868 s, ζ 0.03, a sample every 10 ms (its largest step) over 4.5 s.
HEEL, PERIOD, ZETA, SPACING, END = 10.0, 0.868, 0.03, 0.01, 4.5
OMEGA = 2 * math.pi / PERIOD
SIGMA = ZETA * OMEGA / math.sqrt(1 - ZETA**2)


def damped_cosine(t):
    return HEEL * np.exp(-SIGMA * t) * np.cos(OMEGA * t)


def extrema(end=END):
    """The record's extrema, where its slope −σ cos ω t − ω sin ω t vanishes."""
    times = (np.arange(1, 100) * math.pi - math.atan(SIGMA / OMEGA)) / OMEGA
    times = times[times < end - SPACING]
    return times, damped_cosine(times)


def test_the_turning_points_of_a_damped_cosine_are_its_extrema():
    """The sample nearest an extremum is up to half a spacing h from it and (ω h)²/8 ≈ 7e-4
    below it; the parabola through it and its neighbours is off by a further factor of order
    (ω h)² ≈ 5e-3: within 1 % of h in time and 1e-5 of the value."""
    t = np.arange(0.0, END + SPACING / 2, SPACING)
    times, values = extrema()
    turns = np.array(turning_points(t, damped_cosine(t)))
    assert turns.shape == (len(times), 2)
    assert turns[:, 0] == pytest.approx(times, abs=0.01 * SPACING)
    assert turns[:, 1] == pytest.approx(values, rel=1e-5)


def test_noise_makes_no_turning_point():
    """Jitter of 0.01 % of the release (a turning point needs a swing of 1 % of the range) adds
    none; each is found within a sample's spacing of the extremum."""
    t = np.arange(0.0, END + SPACING / 2, SPACING)
    noisy = damped_cosine(t) + 1e-3 * np.random.default_rng(39).standard_normal(t.size)
    times, values = extrema()
    turns = np.array(turning_points(t, noisy))
    assert turns.shape == (len(times), 2)
    assert turns[:, 0] == pytest.approx(times, abs=SPACING)
    assert turns[:, 1] == pytest.approx(values, abs=2e-3)


def test_the_table_shows_the_first_turning_points_between_the_first_and_last_sample():
    end = 12.0  # 27 extrema: more than the table shows
    t = np.arange(0.0, end + SPACING / 2, SPACING)
    lines = turning_rows(t, damped_cosine(t), "roll (deg)")
    rows = [line.split() for line in lines[2:]]
    times, values = extrema(end)
    assert len(rows) == TABLE_TURNS + 3 and len(lines) <= 18  # 15 rows and a line of the rest
    assert rows[0][2:] == ["first", "sample"] and rows[-1][2:] == ["last", "sample"]
    assert float(rows[-1][0]) == pytest.approx(end)
    shown = np.array([[float(a), float(b)] for a, b in rows[1:TABLE_TURNS + 1]])
    assert shown[:, 0] == pytest.approx(times[:TABLE_TURNS], abs=1e-4)  # printed to 0.1 ms
    assert shown[:, 1] == pytest.approx(values[:TABLE_TURNS], rel=1e-5)
    assert f"{len(times) - TABLE_TURNS} more turning points" in lines[-2]


def test_the_runs_summary_prints_the_turning_points_of_the_released_dof(tmp_path, capsys):
    """A roll release: the table has the roll's turning points, not every twelfth sample (which
    showed −2.93° at 1.523 s for an extremum of −6.18° at 1.363 s), then the decay's period and
    damping."""
    case = load_case("elliptic_cylinder_roll")
    t = np.arange(0.0, END + SPACING / 2, SPACING)
    path = write_motion(tmp_path / "motion.csv", t, roll=damped_cosine(t))
    print_summary(case, SimpleNamespace(motion_csv=path, run_dir=tmp_path), equilibrium(case))
    out = capsys.readouterr().out
    lines = out.splitlines()
    start = lines.index(" time (s)     roll (deg)")
    assert lines[start - 1].startswith("turning points of roll (deg)")
    assert "heave" not in out.split("CFD")[0]
    times, values = extrema()
    assert lines[start + 1].split() == ["0.0000", "10", "first", "sample"]
    first_trough = [float(v) for v in lines[start + 2].split()]  # −9.1° at 0.430 s
    assert first_trough[0] == pytest.approx(times[0], abs=1e-4)  # printed to 0.1 ms
    assert first_trough[1] == pytest.approx(values[0], rel=1e-5)
    assert "CFD damped roll period: 0.86" in out
