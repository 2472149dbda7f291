"""Shared by every test: matplotlib without a display, the project's folders, and a build folder
of the test's own.

The tests mirror the packages of src/floatfoam (tests/bodies/, tests/hydrostatics/, ...); the CFD
regression runs are in tests/cfd/; tests of the whole package stay here. The helper modules here
(cfdcases, fakes, procutil, references, steps) are importable from every folder
(pyproject.toml: pythonpath = ["tests"]).
"""

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
