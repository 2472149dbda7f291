"""The decay analysis on a committed real OpenFOAM motion series (tests/data/README.md)."""

import conftest
import pytest

from floatfoam.analysis.decay import analyse_decay
from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.motion import dof_series, read_motion
from floatfoam.potential.radiation import potential_summary

DATA = conftest.DATA / "cylinder_heave_coarse_motion.csv"


def test_real_heave_record():
    t, z = dof_series(read_motion(DATA), "heave")
    result = analyse_decay(t, z)
    s = result.summary()
    # Against 2D potential flow (an independent method): the period with added mass at
    # resonance is 0.620 s; within 5 %, since the potential period is undamped and linear
    # while the record is damped (T_d = T_n/√(1 − ζ²)) and released at a third of the radius.
    potential = potential_summary(load_case("cylinder_heave")).to_dict()
    assert s["period_mean"] == pytest.approx(potential["heave_period"], rel=0.05)
    # radiation damping is most of the damping of a half-immersed cylinder: same order
    assert 0.5 < s["damping_ratio"] / potential["heave_damping_ratio"] < 1.5
    lo, hi = s["period_ci95"]
    assert hi - lo < 0.02  # 3 cycles of a clean record pin the period to a few ms
    assert s["n_cycles"] >= 2.5
    # per-cycle zero-up-crossing periods agree with the fit within a few per cent
    for period in result.periods("up"):
        assert period == pytest.approx(s["period_mean"], rel=0.05)


def test_analyse_cli_on_real_record(capsys):
    import json

    assert main(["analyse", str(DATA), "--dof", "heave", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {"periods", "period_mean", "period_ci95", "damping_ratio", "damping_ratio_ci95",
            "n_cycles"} <= data.keys()
