"""Capsizing bodies in the decay models (issue 13, item 5): the linear models refuse with the
verdict; the nonlinear model turns the body over towards the stable attitude of its GZ curve.

ellipsoid_printed_verdict (KG = 0.18 m, GM = −0.033 m) has GZ < 0 from 0° to 180°: it is stable
upside down. parabolic_cylinder (GM = −0.0096 m) is stable near 105° of heel.
"""

from __future__ import annotations

import json
import warnings

import pytest

from floatfoam.cli import main


@pytest.mark.parametrize("model", ["linear", "cummins"])
def test_linear_models_refuse_a_capsizing_body(model, capsys):
    assert main(["decay-model", "ellipsoid_printed_verdict", "--model", model]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "roll capsizes (GM = -0.03312 m)" in err
    assert "--model nonlinear" in err


@pytest.mark.parametrize("case, stable, extra", [
    ("ellipsoid_printed_verdict", 180.0, []),
    ("parabolic_cylinder", 105.0, ["--set", "release.heel=5"]),  # its case: heave alone
])
def test_nonlinear_model_turns_the_body_over(case, stable, extra, capsys, tmp_path):
    """No damping in the model: once over, the body swings about its stable attitude, so the
    swing brackets the GZ curve's stable angle (found to the curve's 1° step)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow or fit warning may reach the user
        assert main(["decay-model", case, "--model", "nonlinear", "--json", "--out",
                     str(tmp_path / "decay.csv"), *extra]) == 0
    roll = json.loads(capsys.readouterr().out)["dofs"]["roll"]
    assert roll["GM"] < 0 and roll["stable_attitude"] == pytest.approx(stable, abs=1.0)
    low, high = roll["swing"]
    assert low < roll["stable_attitude"] < high and high - low > 90.0
