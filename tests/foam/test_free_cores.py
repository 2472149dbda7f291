"""Runs that share the cores (floatfoam.foam.ranks): one line before the solver starts when its
ranks and the solver ranks already running exceed the cores (check_free_cores), and the cores
that runs naming one FLOATFOAM_SOLVER_LOCK share out among their solvers (hold_cores)."""

import os
import subprocess
import threading
import time

import pytest

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


class Holder:
    """hold_cores in a thread of its own: ``taken`` is set once it holds its cores, and it
    lets them go when ``release`` is set (flock's locks belong to each open file, so threads
    of one process contend for them as processes do)."""

    def __init__(self, lock, ranks_):
        self.taken, self.release = threading.Event(), threading.Event()
        self.thread = threading.Thread(target=self._hold, args=(lock, ranks_), daemon=True)
        self.thread.start()

    def _hold(self, lock, ranks_):
        with ranks.hold_cores(lock, ranks_):
            self.taken.set()
            self.release.wait(30)

    def done(self):
        self.release.set()
        self.thread.join(10)


@pytest.fixture
def two_cores(monkeypatch):
    monkeypatch.setattr(os, "cpu_count", lambda: 2)


def test_runs_of_one_rank_share_two_cores_and_a_third_waits(tmp_path, two_cores, capsys):
    lock = tmp_path / "cores.lock"
    first, second = Holder(lock, 1), Holder(lock, 1)
    assert first.taken.wait(5) and second.taken.wait(5)  # one core each, at once
    third = Holder(lock, 1)
    assert not third.taken.wait(1.0)
    first.done()
    assert third.taken.wait(5)
    second.done(), third.done()
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "cores.lock", "cores.lock.2", "cores.lock.queue"]
    err = capsys.readouterr().err.splitlines()
    assert err == [f"waiting for the cores: another run's solver holds {lock} "
                   "(FLOATFOAM_SOLVER_LOCK)"]  # said once, by the one that waited


def test_a_run_of_two_ranks_is_served_before_later_runs_of_one(tmp_path, two_cores):
    """A 2-rank run waiting for both cores is not kept waiting by 1-rank runs that start
    after it and could each take the core that comes free first."""
    lock = tmp_path / "cores.lock"
    first, second = Holder(lock, 1), Holder(lock, 1)
    assert first.taken.wait(5) and second.taken.wait(5)
    wide = Holder(lock, 2)
    time.sleep(0.5)  # the 2-rank run waits at the queue's head
    later = Holder(lock, 1)
    first.done()
    assert not wide.taken.wait(1.0) and not later.taken.wait(0.1)
    second.done()
    assert wide.taken.wait(5) and not later.taken.wait(1.0)
    wide.done()
    assert later.taken.wait(5)
    later.done()


def test_more_ranks_than_cores_hold_every_core(tmp_path, two_cores):
    lock = tmp_path / "cores.lock"
    wide = Holder(lock, 3)
    assert wide.taken.wait(5)
    one = Holder(lock, 1)
    assert not one.taken.wait(1.0)
    wide.done()
    assert one.taken.wait(5)
    one.done()


def test_computations_beside_running_solvers_take_the_free_cores(monkeypatch):
    """A child computation (potential.bounded.run_bounded: Capytaine, BLAS) started while solver
    ranks run takes the cores they leave free, at least one; alone, or with the threads set
    by the user, the environment is left as it is."""
    from floatfoam import cores
    from floatfoam.potential.bounded import run_bounded

    for name in cores.THREAD_VARIABLES:
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    assert cores.threads_beside_solvers(busy=0) == {}
    assert cores.threads_beside_solvers(busy=1) == dict.fromkeys(cores.THREAD_VARIABLES, "1")
    assert cores.threads_beside_solvers(busy=4)["OMP_NUM_THREADS"] == "1"
    monkeypatch.setattr(cores, "running_solver_ranks", lambda name=cores.SOLVER_NAME: 1)
    seen = run_bounded(os.getenv, "OMP_NUM_THREADS", limit=60, label="t", advice="-")
    assert seen == "1" and "OMP_NUM_THREADS" not in os.environ  # the child's alone
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "2")  # the user's choice
    assert cores.threads_beside_solvers(busy=1) == {}
    assert run_bounded(os.getenv, "OMP_NUM_THREADS", limit=60, label="t", advice="-") is None


def test_a_run_holds_its_ranks_cores_and_with_a_hostfile_every_one(tmp_path, two_cores,
                                                                   monkeypatch):
    """solver_turn: as many cores as the run's ranks; a run with a hostfile, whose ranks may
    run here too, all of them; none without FLOATFOAM_SOLVER_LOCK."""
    monkeypatch.delenv("FLOATFOAM_SOLVER_LOCK", raising=False)
    with ranks.solver_turn("a", 1) as fds:
        assert fds == ()
    monkeypatch.setenv("FLOATFOAM_SOLVER_LOCK", str(tmp_path / "cores.lock"))
    with ranks.solver_turn("a", 1) as fds:
        assert len(fds) == 1
    with ranks.solver_turn("a", 1, tmp_path / "hosts") as fds:
        assert len(fds) == 2
