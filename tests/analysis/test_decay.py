"""Decay analysis on synthetic records with known answers (no solver).

The records are the exact free decay of a linear oscillator released from rest,
x(t) = x_eq + x₀ e^{−σt} (cos ω_d t + σ/ω_d sin ω_d t), σ = ζω_n, written out here
independently of the package.
"""

from __future__ import annotations

import argparse
import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from floatfoam.analysis.decay import analyse_decay, decay_dict, log_decrement_damping
from floatfoam.cli import analyse as analyse_command
from floatfoam.errors import InputError
from floatfoam.motion import write_motion

PERIOD = 0.63  # s, damped period of Ito's half-immersed cylinder in heave
ZETA = 0.15  # strongly damped: only 3–4 usable cycles
OFFSET = 0.0254  # m, release offset
EQ = -0.0006  # m, equilibrium level


def free_decay(t, period=PERIOD, zeta=ZETA, offset=OFFSET, eq=EQ, drift=0.0):
    omega_d = 2 * math.pi / period
    sigma = zeta * omega_d / math.sqrt(1 - zeta**2)
    t = np.asarray(t, dtype=float)
    return eq + drift * t + offset * np.exp(-sigma * t) * (
        np.cos(omega_d * t) + sigma / omega_d * np.sin(omega_d * t))


def rel(a, b):
    return abs(a / b - 1)


# Clean records: the fit is exact to round-off; the per-cycle values carry the O((ωΔt)²)
# error of linear crossing interpolation and parabolic vertices (~1e-5 at 1 ms steps),
# so 0.1 % is a loose bound for both.
CLEAN_TOL = 1e-3


@pytest.mark.parametrize("zeta", [0.02, 0.1, 0.2])
def test_clean_record_recovers_period_and_damping(zeta):
    t = np.arange(0.0, 4 * PERIOD, 1e-3)
    result = analyse_decay(t, free_decay(t, zeta=zeta))
    summary = result.summary()
    assert rel(summary["period_mean"], PERIOD) < CLEAN_TOL
    assert rel(summary["damping_ratio"], zeta) < CLEAN_TOL
    assert rel(summary["natural_period"], PERIOD * math.sqrt(1 - zeta**2)) < CLEAN_TOL
    assert summary["n_cycles"] >= 3.5
    assert np.all(np.abs(result.periods(1) / PERIOD - 1) < CLEAN_TOL)
    assert np.all(np.abs(result.peak_periods() / PERIOD - 1) < CLEAN_TOL)
    deltas, _ = result.cycle_decrements()
    assert deltas.size >= 5
    assert np.all(np.abs(log_decrement_damping(deltas) / zeta - 1) < CLEAN_TOL)
    half, _ = result.half_cycle_decrements()
    assert np.all(np.abs(log_decrement_damping(2 * half) / zeta - 1) < CLEAN_TOL)
    assert rel(result.fit.mean_level(0.0), EQ) < CLEAN_TOL


def test_release_from_rest_counts_as_first_extremum():
    t = np.arange(0.0, 3 * PERIOD, 1e-3)
    result = analyse_decay(t, free_decay(t))
    first_t, first_a, _ = result.extrema[0]
    assert first_t == pytest.approx(0.0, abs=1e-3 * PERIOD)
    assert rel(first_a, OFFSET) < CLEAN_TOL


def test_log_decrement_relation():
    zeta = np.array([0.01, 0.1, 0.3])
    delta = 2 * math.pi * zeta / np.sqrt(1 - zeta**2)
    np.testing.assert_allclose(log_decrement_damping(delta), zeta, rtol=1e-14)


def _noisy(seed, noise=0.02 * OFFSET):
    t = np.arange(0.0, 4 * PERIOD, 2e-3)
    rng = np.random.default_rng(seed)
    return t, free_decay(t) + rng.normal(0.0, noise, t.size)


def test_noisy_record_truth_within_ci():
    # One fixed record; any single record misses a 95 % interval 1 time in 20, which is what
    # the coverage test below checks.
    t, x = _noisy(seed=0)
    s = analyse_decay(t, x).summary()
    assert s["period_ci95"][0] <= PERIOD <= s["period_ci95"][1]
    assert s["damping_ratio_ci95"][0] <= ZETA <= s["damping_ratio_ci95"][1]
    # The interval is informative, not just wide: 2 % noise gives ~0.5 % on ζ.
    assert s["damping_ratio_ci95"][1] - s["damping_ratio_ci95"][0] < 0.05 * ZETA


def test_noisy_ci_coverage_over_seeds():
    """The nominal 95 % intervals cover the truth in ≥ 85 % of 50 independent records."""
    hits_period = hits_zeta = 0
    seeds = range(50)
    for seed in seeds:
        s = analyse_decay(*_noisy(seed)).summary()
        hits_period += s["period_ci95"][0] <= PERIOD <= s["period_ci95"][1]
        hits_zeta += s["damping_ratio_ci95"][0] <= ZETA <= s["damping_ratio_ci95"][1]
    # 85 %: with 50 draws at a true 95 % coverage the count falls below 43 with p < 0.5 %.
    assert hits_period >= 0.85 * len(seeds)
    assert hits_zeta >= 0.85 * len(seeds)


def test_drifting_mean_is_fitted():
    t = np.arange(0.0, 4 * PERIOD, 1e-3)
    drift = 0.002  # m/s: the mean moves by 20 % of the offset over the record
    result = analyse_decay(t, free_decay(t, drift=drift), drift=True)
    s = result.summary()
    assert rel(s["period_mean"], PERIOD) < CLEAN_TOL
    assert rel(s["damping_ratio"], ZETA) < CLEAN_TOL
    assert rel(result.fit.param("drift"), drift) < CLEAN_TOL


def test_uneven_time_steps():
    rng = np.random.default_rng(3)
    t = np.cumsum(rng.uniform(0.2e-3, 3e-3, 1600))  # steps vary 15-fold, as with adaptive Δt
    t = t[t < 4 * PERIOD]
    result = analyse_decay(t, free_decay(t))
    s = result.summary()
    assert rel(s["period_mean"], PERIOD) < CLEAN_TOL
    assert rel(s["damping_ratio"], ZETA) < CLEAN_TOL
    # Per cycle, 3 ms steps give (ωΔt)² ~ 1e-3: the same 0.1 % bound, with margin.
    assert np.all(np.abs(result.periods(-1) / PERIOD - 1) < CLEAN_TOL)


def test_record_cut_short_mid_swing():
    t = np.arange(0.0, 1.85 * PERIOD, 1e-3)  # stops while rising towards a maximum
    result = analyse_decay(t, free_decay(t))
    s = result.summary()
    assert rel(s["period_mean"], PERIOD) < CLEAN_TOL
    assert rel(s["damping_ratio"], ZETA) < CLEAN_TOL
    assert 1.5 <= s["n_cycles"] < 2
    # No extremum is invented at the cut: every one is a true turning point.
    sigma = ZETA * 2 * math.pi / PERIOD / math.sqrt(1 - ZETA**2)
    for t_e, a_e, _ in result.extrema:
        assert t_e < t[-1] - 0.05 * PERIOD
        assert rel(abs(a_e), OFFSET * math.exp(-sigma * t_e)) < CLEAN_TOL  # extrema at ω_d t = kπ


def test_given_and_tail_equilibrium():
    t = np.arange(0.0, 6 * PERIOD, 1e-3)
    x = free_decay(t)
    given = analyse_decay(t, x, equilibrium=EQ)
    assert given.equilibrium_source == "given"
    assert rel(given.summary()["damping_ratio"], ZETA) < CLEAN_TOL
    tail = analyse_decay(t, x, equilibrium="tail")
    assert tail.equilibrium_source == "tail"
    # After 6 cycles at ζ = 0.15 the tail still holds ~1e-4 of the offset: 0.5 % is ample.
    assert rel(tail.summary()["damping_ratio"], ZETA) < 5e-3


def test_quadratic_damping_recovered():
    omega, zeta, c_q = 10.0, 0.05, 20.0  # c_q in 1/m: the quadratic part dominates early on

    def rhs(_, s):
        return [s[1], -2 * zeta * omega * s[1] - c_q * abs(s[1]) * s[1] - omega**2 * s[0]]

    t = np.linspace(0.0, 2.5, 600)
    sol = solve_ivp(rhs, (0, 2.5), [0.02, 0.0], t_eval=t, rtol=1e-11, atol=1e-14)
    result = analyse_decay(t, sol.y[0] + EQ, quadratic=True)
    d = decay_dict(result, unit="m")
    # Clean ODE data: the fit is limited by the integrator tolerances only.
    assert rel(d["damping_ratio"], zeta) < 1e-3
    assert rel(d["quadratic_damping"], c_q) < 1e-3
    assert rel(d["natural_period"], 2 * math.pi / omega) < 1e-4
    assert d["damping_ratio_equivalent"] > zeta


def test_too_short_refused():
    t = np.arange(0.0, 1.2 * PERIOD, 1e-3)
    with pytest.raises(InputError, match=r"usable cycles.*need at least 1\.5"):
        analyse_decay(t, free_decay(t))


def test_amplitude_below_noise_refused():
    t = np.arange(0.0, 4 * PERIOD, 1e-3)
    x = free_decay(t, offset=1e-5) + np.random.default_rng(0).normal(0.0, 1e-3, t.size)
    with pytest.raises(InputError, match="below 3× the residual rms"):
        analyse_decay(t, x)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_nan_and_inf_refused_not_dropped(bad):
    t = np.arange(0.0, 4 * PERIOD, 1e-3)
    x = free_decay(t)
    x[100] = bad
    with pytest.raises(InputError, match="non-finite value .* at sample 100"):
        analyse_decay(t, x)
    t[50] = np.nan
    with pytest.raises(InputError, match="time: non-finite"):
        analyse_decay(t, free_decay(np.arange(t.size) * 1e-3))


def test_bad_time_and_too_few_samples_refused():
    t = np.arange(0.0, 4 * PERIOD, 1e-3)
    t_back = t.copy()
    t_back[10] = t_back[9]
    with pytest.raises(InputError, match="not strictly increasing at sample 10"):
        analyse_decay(t_back, free_decay(t))
    with pytest.raises(InputError, match="need at least 20"):
        analyse_decay(t[:5], free_decay(t[:5]))
    with pytest.raises(InputError, match="no oscillation"):
        analyse_decay(t, np.zeros_like(t))


def _cli(argv):
    parser = argparse.ArgumentParser()
    analyse_command.register(parser.add_subparsers())
    args = parser.parse_args(["analyse", *argv])
    return args.func(args)


def test_cli_json_keys_and_angles_in_degrees(tmp_path, capsys):
    t = np.arange(0.0, 4 * PERIOD, 1e-3)
    roll_deg = free_decay(t, offset=10.0, eq=0.0)  # synthetic roll record, degrees in the file
    write_motion(tmp_path / "motion.csv", t, roll=roll_deg)
    png = tmp_path / "decay.png"
    assert _cli([str(tmp_path), "--dof", "roll", "--json", "--plot", str(png)]) == 0
    data = json.loads(capsys.readouterr().out)
    for key in ("periods", "period_mean", "period_ci95", "damping_ratio", "damping_ratio_ci95",
                "n_cycles", "natural_period", "log_decrements", "damping_ratios", "extrema"):
        assert key in data
    assert data["unit"] == "deg"
    assert rel(data["period_mean"], PERIOD) < CLEAN_TOL
    assert len(data["period_ci95"]) == 2
    assert rel(data["amplitude"], 10.0 * math.hypot(1, ZETA / math.sqrt(1 - ZETA**2))) < 1e-6
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_table_and_errors(tmp_path, capsys):
    t = np.arange(0.0, 4 * PERIOD, 1e-3)
    write_motion(tmp_path / "motion.csv", t, z=free_decay(t))
    assert _cli([str(tmp_path / "motion.csv"), "--equilibrium", str(EQ)]) == 0
    out = capsys.readouterr().out
    assert "damped period T_d" in out and "damping ratio" in out
    with pytest.raises(InputError, match="--equilibrium 'x'"):
        _cli([str(tmp_path), "--equilibrium", "x"])
    with pytest.raises(InputError, match="neither a motion CSV, a run folder nor a case"):
        _cli([str(tmp_path / "missing")])
    (tmp_path / "nan").mkdir()
    (tmp_path / "nan" / "motion.csv").write_text(
        (tmp_path / "motion.csv").read_text().replace("\n0.5,", "\nnan,", 1))
    with pytest.raises(InputError, match="non-finite"):
        _cli([str(tmp_path / "nan")])
