"""The public Python API (``floatfoam.__all__``): every name resolves to the library function
the command line uses, and a case goes through theory, a decay model and the decay analysis
without the command line."""

import json
import math
import subprocess
import sys

import pytest

import floatfoam
from floatfoam.errors import InputError

FLOATFOAM = [sys.executable, "-m", "floatfoam.cli"]


def test_every_public_name_resolves():
    assert {"load_case", "theory_summary", "radiation_coefficients", "decay_series",
            "run_case", "analyse_decay", "run_study", "validate_case",
            "build_report"} <= set(floatfoam.__all__)
    from importlib import import_module

    for name, module in floatfoam.API.items():  # each the defining module's own object
        assert getattr(floatfoam, name) is getattr(import_module(module), name), name
    assert set(floatfoam.API) <= set(floatfoam.__all__)
    from floatfoam.foam.driver import run_case

    assert floatfoam.run_case is run_case  # the library's own function, not a copy
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        floatfoam.nothing  # noqa: B018


def test_a_case_through_the_api_as_the_command_line_gives_it():
    """The half-immersed sphere: the theory's heave period is the command line's (`floatfoam
    theory --json`, to the last digit), and the memoir's linear model analysed by the decay
    fit oscillates at that period undamped (the model is ω² = ρgA/M exactly: 1e-6 is the fit's
    sampling error, measured 0 to 1e-15)."""
    case = floatfoam.load_case("sphere")
    theory = floatfoam.theory_summary(case)
    heave = theory.dofs["heave"].period
    # ω² = ρ g A_wp / M, A_wp = π a², M = ρ_b (4/3) π a³ with a = 0.1 m, ρ_b = 500 kg/m³
    assert heave == pytest.approx(2 * math.pi / math.sqrt(1000 * 9.81 * math.pi * 0.01
                                                          / (500 * 4 / 3 * math.pi * 1e-3)),
                                  rel=1e-12)
    shown = json.loads(subprocess.run([*FLOATFOAM, "theory", "sphere", "--json"],
                                      capture_output=True, text=True, check=True).stdout)
    assert shown["heave_period"] == heave
    series = floatfoam.decay_series(case, "linear")
    fit = floatfoam.analyse_decay(series["time"], series["z"]).summary()
    assert fit["period_mean"] == pytest.approx(heave, rel=1e-6)
    assert abs(fit["damping_ratio"]) < 1e-6


def test_a_study_without_finished_runs_is_refused(tmp_path):
    """run_study analysing finished runs only (run=False) where none is: InputError naming the
    case and what to do, nothing written."""
    case = floatfoam.load_case("cylinder_heave")
    with pytest.raises(InputError, match=r"^case 'cylinder_heave' has no finished run under "):
        floatfoam.run_study(case, 1, build=tmp_path, run=False)
    assert list(tmp_path.iterdir()) == []
