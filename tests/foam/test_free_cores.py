"""Runs that share the cores (floatfoam.foam.ranks.check_free_cores): one line before the
solver starts when its ranks and the solver ranks already running exceed the cores."""

import os
import subprocess
import time

from floatfoam.foam import ranks


def test_a_run_alone_is_not_warned(capsys):
    cores = os.cpu_count() or 1
    assert not ranks.check_free_cores(cores, None, busy=0)
    assert not ranks.check_free_cores(1, None, busy=cores - 1)
    assert capsys.readouterr().err == ""


def test_ranks_beyond_the_free_cores_are_one_line(capsys):
    cores = os.cpu_count() or 1
    assert ranks.check_free_cores(2, None, label="box/coarse", busy=cores)
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("[box/coarse] warning: ")
    assert f"{cores} solver rank(s) of other runs" in err[0] and "2 rank(s)" in err[0]
    assert not ranks.check_free_cores(2, "hosts", busy=cores)  # other machines: not counted


def test_running_solver_ranks_are_counted_from_proc(tmp_path):
    """A process of the solver's name is counted while it runs (`sleep` under another name:
    the solver's own would count the runs of another command on this machine too)."""
    name = "ffTestSolver"
    fake = tmp_path / name
    fake.symlink_to("/bin/sleep")
    assert ranks.running_solver_ranks(name) == 0
    process = subprocess.Popen([str(fake), "30"])
    try:
        deadline = time.monotonic() + 10.0  # until the child has exec'd under its name
        while ranks.running_solver_ranks(name) == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert ranks.running_solver_ranks(name) == 1
    finally:
        process.kill()
        process.wait()
