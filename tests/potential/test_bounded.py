"""Bounded external computations (gmsh, Capytaine): a time limit, crashes and interrupts become
one line, and no child outlives the command (issue 13, item 2)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from floatfoam.cli import main
from floatfoam.errors import ComputationError, InputError
from floatfoam.potential import radiation
from floatfoam.potential.bounded import run_bounded

FLOATFOAM = str(Path(sys.executable).with_name("floatfoam"))
ADVICE = {"label": "test work", "advice": "valid: less work"}


def _square(x):
    return x * x


def _bad_input():
    raise InputError("body.radius = -1: valid is a number > 0")


def _bug():
    return {}["missing"]


def _sleep():
    time.sleep(60)


def _segfault():
    os.kill(os.getpid(), signal.SIGSEGV)


def test_result_and_errors_come_back_as_one_line():
    assert run_bounded(_square, 7, limit=30, **ADVICE) == 49
    with pytest.raises(InputError, match="body.radius = -1"):
        run_bounded(_bad_input, limit=30, **ADVICE)
    with pytest.raises(ComputationError, match=r"KeyError: 'missing' at .*test_bounded.py"):
        run_bounded(_bug, limit=30, **ADVICE)


def test_time_limit_and_crash_stop_the_child():
    start = time.monotonic()
    with pytest.raises(ComputationError, match=r"test work: not done within 1 s; valid: less"):
        run_bounded(_sleep, limit=1.0, **ADVICE)
    assert time.monotonic() - start < 10  # stopped, not waited for (the child sleeps 60 s)
    with pytest.raises(ComputationError, match=r"test work: crashed \(SIGSEGV\)"):
        run_bounded(_segfault, limit=30, **ADVICE)


def test_potential_past_its_limit_is_one_line_exit_1(monkeypatch, capsys):
    monkeypatch.setattr(radiation, "time_limit", lambda *args: 0.01)
    assert main(["potential", "sphere", "--no-cache"]) == 1
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith("floatfoam potential: potential flow of sphere (z_c = ")
    assert "800 panels" in err and "--panels" in err and "not done within" in err


def test_sigterm_stops_potential_and_its_child(tmp_path):
    """SIGTERM while gmsh/Capytaine work in the child: one line, exit 143, child gone."""
    marker = tmp_path / "cache"  # a unique argument to find the processes by
    proc = subprocess.Popen([FLOATFOAM, "potential", "sphere", "--no-cache", "--set",
                             "potential.frequencies=200"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "FLOATFOAM_BUILD": str(marker)})
    time.sleep(3.0)  # meshing and solving by now
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 143 and err.strip().splitlines()[-1].endswith("(SIGTERM)")
    time.sleep(0.5)
    leftovers = [p for p in Path("/proc").glob("[0-9]*")
                 if _environ_has(p, f"FLOATFOAM_BUILD={marker}")]
    assert not leftovers


def _environ_has(proc: Path, entry: str) -> bool:
    try:
        return entry.encode() in (proc / "environ").read_bytes().split(b"\0")
    except OSError:
        return False
