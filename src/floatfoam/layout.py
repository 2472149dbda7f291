"""The layout on disk, in one place: where cases live, where their runs and products go.

::

    cases/<case>/case.toml            a case (folders starting with ``_`` are shared material)
    cases/_common/                    OpenFOAM dictionaries every run starts from
    <build>/<case>/<level>/           the run directory of a case at a mesh level
    <build>/<case>/<level>-dt<k>/     the same with its time steps divided by k (a time-step
                                      study: ``floatfoam validate``)
    <build>/<case>/validation/        the grid and time-step convergence study of the case
    <build>/<case>/<level>/.floatfoam/<step>.done
                                      the driver's step markers; ``finished.done`` marks a
                                      finished run (only those reach the comparison and report)
    <build>/<case>/                   a case's other products (gz.png, potential.png, decay_*.csv,
                                      mesh/<level>/)
    <build>/potential/                the potential-flow cache
    <build>/report/                   the project report
    build/solver/bin/interFoam        floatfoam's interFoam (``make setup``)

``<build>`` is the project's ``build/`` unless the environment variable ``FLOATFOAM_BUILD``
names another folder. The solver always lives in the project's ``build/solver`` (it is built
by ``make setup``, not by a run).
"""

from __future__ import annotations

import os
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CASES_DIR = ROOT / "cases"
COMMON_DIR = CASES_DIR / "_common"
PROJECT_BUILD = ROOT / "build"
SOLVER = PROJECT_BUILD / "solver" / "bin" / "interFoam"
BUILD_ENV = "FLOATFOAM_BUILD"

#: Mesh levels, coarse to fine: one refinement ratio between neighbours (meshing.levels).
LEVELS = ("coarse", "medium", "fine")

MARKERS = ".floatfoam"  # folder of the driver's step markers in a run directory
FINISHED = "finished"  # the step that marks a run finished
REMESHED = "remeshed"  # remeshed/<k>/ in a run directory: the run on its k-th mesh, up to its
                       # remeshing (floatfoam.foam.remesh)


def build_dir() -> Path:
    """The build folder: ``$FLOATFOAM_BUILD`` if set, else the project's ``build/``."""
    override = os.environ.get(BUILD_ENV)
    return Path(override).resolve() if override else PROJECT_BUILD


def case_build_dir(case_name: str, build: Path | None = None) -> Path:
    """Where a case's products go: ``<build>/<case>``."""
    return Path(build or build_dir()) / case_name


def run_name(level: str, time_step_divisor: int = 1, morphing: float = 1.0) -> str:
    """A run's folder name: its mesh level, followed by ``-dt<k>`` when its time steps are
    those of the level divided by k (the time-step study of ``floatfoam validate``) and by
    ``-morph<f>`` when its mesh motion is the case's spread by f (its study of the mesh
    motion: :func:`floatfoam.plan.morphing.scaled_morphing`)."""
    name = level if time_step_divisor == 1 else f"{level}-dt{time_step_divisor}"
    return name if morphing == 1 else f"{name}-morph{morphing:g}"


def parse_run_name(name: str) -> tuple[str, int, float]:
    """(level, time-step divisor, morphing factor) of a run's folder name (:func:`run_name`)."""
    level, divisor, morphing = name, 1, 1.0
    if "-morph" in level:
        level, factor = level.split("-morph", 1)
        morphing = float(factor)
    if "-dt" in level:
        level, k = level.split("-dt", 1)
        divisor = int(k)
    return level, divisor, morphing


def run_dir(case_name: str, level: str, build: Path | None = None, *,
            time_step_divisor: int = 1, morphing: float = 1.0) -> Path:
    """The run directory of a case at a mesh level: ``<build>/<case>/<level>`` (and
    ``<level>-dt<k>`` with its time steps divided by k, ``<level>-morph<f>`` with its
    mesh motion spread by f)."""
    return case_build_dir(case_name, build) / run_name(level, time_step_divisor, morphing)


def list_cases(cases_dir: Path | None = None) -> list[Path]:
    """Case folders (holding a case.toml) under ``cases_dir``, skipping names starting with _."""
    return sorted(p.parent for p in Path(cases_dir or CASES_DIR).glob("*/case.toml")
                  if not p.parent.name.startswith("_"))


def marker(run: Path, step: str) -> Path:
    """The marker file of a driver step in a run directory."""
    return Path(run) / MARKERS / f"{step}.done"


def step_done(run: Path, step: str) -> bool:
    return marker(run, step).exists()


def mark_done(run: Path, step: str) -> None:
    path = marker(run, step)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(time.strftime("%Y-%m-%d %H:%M:%S\n"))


def is_finished(run: Path) -> bool:
    """Whether the driver marked this run directory finished."""
    return step_done(run, FINISHED)


def mesh_parts(run: Path) -> list[Path]:
    """The cases a run's record lies in, in time order: each mesh's that a remeshing kept
    (``remeshed/1``, ``remeshed/2``, …), then the run directory (its last mesh)."""
    kept = [p for p in (Path(run) / REMESHED).glob("*") if p.is_dir() and p.name.isdigit()]
    return sorted(kept, key=lambda p: int(p.name)) + [Path(run)]


def time_folders(root: Path) -> list[tuple[float, Path]]:
    """The numeric time folders under ``root`` other than 0, in time order."""
    found = []
    for path in Path(root).iterdir() if Path(root).is_dir() else ():
        try:
            value = float(path.name)
        except ValueError:
            continue
        if path.is_dir() and value > 0.0:
            found.append((value, path))
    return sorted(found)
