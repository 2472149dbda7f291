"""Shared by every test: matplotlib without a display, the project's folders, and a build folder
of the test's own.

The tests mirror the packages of src/floatfoam (tests/bodies/, tests/hydrostatics/, ...); the CFD
regression runs are in tests/cfd/; tests of the whole package stay here. The helper modules here
(cfdcases, fakes, procutil, references) are importable from every folder
(pyproject.toml: pythonpath = ["tests"]).
"""

import os
from pathlib import Path

import pytest

from floatfoam.cores import THREAD_VARIABLES
from floatfoam.foam.ranks import hold_cores

os.environ.setdefault("MPLBACKEND", "Agg")
if "PYTEST_XDIST_WORKER" in os.environ:
    # Two workers share the 2 cores with the solvers' ranks: every computation takes one
    # thread (Capytaine's OpenMP and OpenBLAS spin on a core they wait for; floatfoam.cores.
    # threads_beside_solvers has the measurement), set before numpy is loaded
    for _name in THREAD_VARIABLES:
        os.environ.setdefault(_name, "1")

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


@pytest.hookimpl(trylast=True)  # after `-m` has deselected
def pytest_collection_modifyitems(config, items):
    """Under pytest-xdist (make test: ``-n 2 --dist worksteal``, whose first worker takes the
    first half of the collection and the second the rest, then each takes tests from the tail
    of the other's queue), both workers run the solver's tests beside each other: the first
    worker's half begins with the Slurm tests (each worker that ran one would start a Slurm of
    its own), then every other solver test, then tests without the solver; the second's
    begins with tests without the solver (while the Slurm tests hold the cores) and ends with
    the other solver tests. Alone, pytest keeps the files' order."""
    if not hasattr(config, "workerinput"):  # not an xdist worker; every worker sorts alike
        return
    solver = [item for item in items if item.get_closest_marker("openfoam") is not None]
    slurm = [item for item in solver if item.path.parent.name == "cluster"]
    runs = [item for item in solver if item.path.parent.name != "cluster"]
    rest = [item for item in items if item.get_closest_marker("openfoam") is None]
    items[:] = slurm + runs[0::2] + rest + runs[1::2]  # the halves split within ``rest``


@pytest.fixture(autouse=True)
def solvers_share_the_cores(request, tmp_path_factory, monkeypatch):
    """The session's workers share the cores among their solvers: a test that runs the solver
    names a lock shared by the workers (beside the session's own temporary folder) in
    FLOATFOAM_SOLVER_LOCK, and each of its runs holds as many of the cores as it has ranks
    while its solver runs (foam.ranks.hold_cores: two 1-rank solvers at once, a 2-rank one
    alone; meshing, potential flow and analysis go on beside the other worker's solver); the
    Slurm tests, whose jobs take the submitter's environment, hold every core from start to
    end instead."""
    if request.node.get_closest_marker("openfoam") is None:
        yield
        return
    lock = tmp_path_factory.getbasetemp().parent / "floatfoam-solver.lock"
    if request.node.path.parent.name != "cluster":
        monkeypatch.setenv("FLOATFOAM_SOLVER_LOCK", str(lock))
        yield
        return
    monkeypatch.delenv("FLOATFOAM_SOLVER_LOCK", raising=False)
    with hold_cores(lock, os.cpu_count() or 1):
        yield
