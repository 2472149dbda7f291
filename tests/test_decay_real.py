"""The decay analysis on a committed real OpenFOAM motion series (tests/data/README.md)."""

from pathlib import Path

import pytest

from floatfoam.cli import main
from floatfoam.decay import analyse_decay
from floatfoam.motioncsv import dof_series, read_motion

DATA = Path(__file__).parent / "data" / "cylinder_heave_coarse_motion.csv"


def test_real_heave_record():
    t, z = dof_series(read_motion(DATA), "heave")
    result = analyse_decay(t, z)
    s = result.summary()
    # Ito cylinder: damped period 0.6-0.65 s (published range quoted in
    # docs/openfoam-v1912.md), well above the no-added-mass 0.491 s; ζ of order 0.1.
    assert 0.58 < s["period_mean"] < 0.66
    assert 0.08 < s["damping_ratio"] < 0.2
    lo, hi = s["period_ci95"]
    assert lo < s["period_mean"] < hi and hi - lo < 0.02
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
