"""The CLI: JSON keys, tables, and one-line errors with exit code 2 for bad input."""

import json
import signal
import subprocess
import sys

import pytest
from conftest import ROOT

from floatfoam.cli import main

JSON_KEYS = {"draft", "displaced_volume", "waterplane_area", "KB", "BM_roll", "BM_pitch",
             "GM_roll", "GM_pitch", "heave_period", "roll_period", "pitch_period",
             "verdict_roll", "verdict_pitch", "memoir", "memoir_printed"}
VERDICTS = {"oscillates", "neutral", "capsizes"}


def run_json(capsys, *argv):
    assert main(list(argv)) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("case", ["cylinder_heave", "sphere", "ellipsoid", "elliptic_cylinder",
                                  "parabolic_cylinder", "box_bilge", "superellipsoid_buoy",
                                  "stl_pontoon"])
def test_theory_json_keys(capsys, case):
    data = run_json(capsys, "theory", case, "--json")
    assert JSON_KEYS <= data.keys()
    assert data["verdict_roll"] in VERDICTS and data["verdict_pitch"] in VERDICTS
    for dof in ("roll", "pitch"):
        oscillates = data[f"verdict_{dof}"] == "oscillates"
        assert (data[f"{dof}_period"] is not None) == oscillates
    assert data["heave_period"] > 0 and isinstance(data["memoir"], dict)


def test_set_override_changes_result(capsys):
    light = run_json(capsys, "theory", "cylinder_heave", "--json", "--set", "mass.density=250")
    half = run_json(capsys, "theory", "cylinder_heave", "--json")
    assert light["draft"] < half["draft"]


def test_theory_table(capsys):
    assert main(["theory", "sphere"]) == 0
    out = capsys.readouterr().out
    assert "heave period" in out and "GM roll" in out


def test_gz_json_and_plot(capsys, tmp_path):
    png = tmp_path / "gz.png"
    data = run_json(capsys, "gz", "box_bilge", "--max-angle", "60", "--json", "--plot", str(png))
    assert len(data["angles"]) == len(data["GZ"]) == 61
    assert png.stat().st_size > 5000


BAD_INPUT = [
    (["--set", "mass.density=1200"], "mass.density"),
    (["--set", "body.radius=-0.1"], "body.radius"),
    (["--set", "body.radius=0"], "body.radius"),
    (["--set", "mass.gyradius=[0.05, 0.0, 0.2]"], "mass.gyradius"),
    (["--set", "mass.cog=[0.0, 0.0, 0.5]"], "mass.cog"),
    (["--set", "body.colour=3"], "body.colour"),
    (["--set", "nonsense"], "nonsense"),
]


@pytest.mark.parametrize("extra, name", BAD_INPUT)
def test_bad_input_one_line_exit_2(capsys, extra, name):
    assert main(["theory", "cylinder_heave", *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and name in err and "valid" in err


def test_implicit_not_closed(capsys):
    # the surface z = 0.05 - x² … is open: F < 0 on the boundary of the bounds
    args = ["theory", "superellipsoid_buoy", "--set", 'body.expression="z - 0.05"']
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "not a closed surface" in err and "body.expression" in err


def test_unknown_case(capsys):
    assert main(["theory", "no_such_case"]) == 2
    assert "cylinder_heave" in capsys.readouterr().err


def test_exit_code_and_no_traceback_from_the_console_script():
    proc = subprocess.run([sys.executable, "-m", "floatfoam.cli", "theory", "sphere", "--set",
                           "mass.density=2000"], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1


def test_version(capsys):
    """`floatfoam --version`: the installed package's version, pyproject.toml's."""
    import tomllib
    from importlib.metadata import version

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert capsys.readouterr().out == f"floatfoam {pyproject['project']['version']}\n"
    assert version("floatfoam") == pyproject["project"]["version"]


def test_decay_model_with_set_never_replaces_the_case_own_series(tmp_path, monkeypatch):
    """decay-model's default CSV: the case's own, and with --set one of its own per override
    (a series of another body never replaces the case's)."""
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path))
    assert main(["decay-model", "sphere", "--model", "linear", "--duration", "1"]) == 0
    assert main(["decay-model", "sphere", "--model", "linear", "--duration", "1", "--set",
                 "mass.density=600"]) == 0
    own = tmp_path / "sphere" / "decay_linear.csv"
    (other,) = (tmp_path / "sphere").glob("decay_linear_set-????????.csv")
    assert own.read_text() != other.read_text()


INTERRUPTED_WHILE_BLOCKED = """
import os, signal, sys, time
from floatfoam.interrupts import SignalInterruptError, signals_interrupt
if sys.argv[1] == "before":  # pending when the block starts
    os.kill(os.getpid(), signal.SIGTERM)
try:
    with signals_interrupt():
        if sys.argv[1] == "within":
            os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5)
    print("not interrupted")
except SignalInterruptError as err:
    print("raised", err)
print("blocked after:", signal.SIGTERM in signal.pthread_sigmask(signal.SIG_BLOCK, ()))
print("handler after:", signal.getsignal(signal.SIGTERM) == signal.SIG_DFL)
"""


@pytest.mark.parametrize("when", ["within", "before"])
def test_a_command_started_with_the_interrupts_blocked_still_stops_on_them(when):
    """A process inherits its parent's signal mask: started with SIGTERM blocked (a launcher
    that blocks it), a command's SIGTERM, sent within ``signals_interrupt`` or pending when it
    starts, still raises there (else it would stay pending to the command's end, which would
    then exit 0 as if never stopped), and the caller's mask and handler are back after it."""
    done = subprocess.run([sys.executable, "-c", INTERRUPTED_WHILE_BLOCKED, when],
                          capture_output=True, text=True, timeout=60,
                          preexec_fn=lambda: signal.pthread_sigmask(signal.SIG_BLOCK,
                                                                    [signal.SIGTERM]))
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[:3] == ["raised SIGTERM", "blocked after: True",
                                           "handler after: True"]
