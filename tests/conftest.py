"""Shared by every test: matplotlib without a display, the project's folders, and a build folder
of the test's own.

The tests mirror the packages of src/floatfoam (tests/bodies/, tests/hydrostatics/, ...); the CFD
regression runs are in tests/cfd/; tests of the whole package stay here. The helper modules here
(cfdcases, fakes, procutil, references, steps) are importable from every folder
(pyproject.toml: pythonpath = ["tests"]).
"""

import fcntl
import os
from pathlib import Path

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")

ROOT = Path(__file__).resolve().parents[1]  # the project
DATA = ROOT / "tests" / "data"  # committed real outputs (tests/data/README.md)


@pytest.fixture
def build(tmp_path, monkeypatch):
    """A build folder of the test's own (FLOATFOAM_BUILD), which a refused command must not
    create."""
    folder = tmp_path / "build"
    monkeypatch.setenv("FLOATFOAM_BUILD", str(folder))
    return folder


@pytest.fixture(scope="session")
def shared_runs(request, tmp_path_factory):
    """A folder the session's workers share, for the runs that several tests make alike
    (tests/cfdcases.shared_run): beside the workers' own folders under pytest-xdist, in the
    session's own folder without it."""
    base = tmp_path_factory.getbasetemp()
    return (base.parent if hasattr(request.config, "workerinput") else base) / "shared-runs"


def pytest_collection_modifyitems(config, items):
    """Under pytest-xdist (make test: ``-n 2 --dist worksteal``), the tests that run the solver
    come first, the Slurm ones at their head: the first worker's half of the collection holds
    them all, one after another, and the other worker runs the rest beside them, then takes
    tests from the tail of the first one's queue (so never a Slurm test: each worker that ran
    one would start a Slurm of its own). Alone, pytest keeps the files' order."""
    if hasattr(config, "workerinput"):  # an xdist worker; every worker sorts alike
        items.sort(key=lambda item: (item.get_closest_marker("openfoam") is None,
                                     item.path.parent.name != "cluster"))


@pytest.fixture(autouse=True)
def one_solver_at_a_time(request, tmp_path_factory, monkeypatch):
    """The session's workers run one solver at a time: its ranks take the cores, and two runs
    at once would share them (and warn that they do, foam.ranks.check_free_cores). A test that
    runs the solver names a lock shared by the workers (beside the session's own temporary
    folder) in FLOATFOAM_SOLVER_LOCK, which its runs hold while their solver runs (meshing,
    potential flow and analysis go on beside the other worker's solver); the Slurm tests, whose
    jobs take the submitter's environment, hold it from start to end instead."""
    if request.node.get_closest_marker("openfoam") is None:
        yield
        return
    lock = tmp_path_factory.getbasetemp().parent / "floatfoam-solver.lock"
    if request.node.path.parent.name != "cluster":
        monkeypatch.setenv("FLOATFOAM_SOLVER_LOCK", str(lock))
        yield
        return
    monkeypatch.delenv("FLOATFOAM_SOLVER_LOCK", raising=False)
    with open(lock, "a") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)  # released when the file closes
        yield
