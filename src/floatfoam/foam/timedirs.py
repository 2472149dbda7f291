"""Written time folders of a run: which are complete, and setting aside the ones that are not.

A solver stopped while writing leaves its last time folder half written (files missing or cut
short); OpenFOAM would restart from it and fail, every time. A time folder is complete when

* it holds the initial fields (the files of ``0.orig``), ``uniform/time`` and, for a moving body,
  ``polyMesh/points`` and, when the six-DoF motion solver moves the mesh,
  ``uniform/sixDoFRigidBodyMotionState`` (the Laplacian's body keeps its state in
  ``pointDisplacement``);
* it holds every file the time folder written before it holds, but for the files a restarted
  solver writes only into the time it restarts from (:data:`RESTART_ONLY`);
* every file ends with OpenFOAM's closing divider line (written last, in ASCII and binary).

An incomplete folder is moved into ``<run>/.floatfoam/incomplete/`` (never deleted), in every
``processor*`` folder of a parallel run, so that the run resumes from the time before.
"""

from __future__ import annotations

import time
from pathlib import Path

from floatfoam.layout import MARKERS, time_folders

FOOTER = b"// ************************************************************************* //"
MOTION_FILES = ("polyMesh/points",)
SOLVER_STATE = "uniform/sixDoFRigidBodyMotionState"  # the six-DoF motion solver's
# interFoam's mesh motion writes its scale field at start-up only, into the time it starts from:
# after a restart the folder restarted from holds it and the next one written does not.
RESTART_ONLY = frozenset({"motionScale"})


def _files(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file()}


def _ends_with_footer(path: Path) -> bool:
    with open(path, "rb") as fh:
        fh.seek(0, 2)
        size = fh.tell()
        fh.seek(max(0, size - len(FOOTER) - 8))
        return FOOTER in fh.read()


def is_complete(folder: Path, required: set[str], previous: Path | None) -> bool:
    """Whether ``folder`` is a complete write (see the module docstring)."""
    files = _files(folder)
    earlier = _files(previous) - RESTART_ONLY if previous is not None else set()
    need = set(required) | earlier
    return need <= files and all(_ends_with_footer(folder / f) for f in files)


def required_files(run_dir: Path, moving: bool) -> set[str]:
    """What every written time folder of this run must hold: the fields floatfoam rendered
    (``0.orig``; ``0/`` also gains motionScale, which the solver writes at start-up only)."""
    initial = {p.name for p in (Path(run_dir) / "0.orig").iterdir() if p.is_file()} \
        if (Path(run_dir) / "0.orig").is_dir() else set()
    motion = set(MOTION_FILES) if moving else set()
    mesh_dict = Path(run_dir) / "constant" / "dynamicMeshDict"
    if moving and "sixDoFRigidBodyMotionCoeffs" in (mesh_dict.read_text(errors="replace")
                                                    if mesh_dict.is_file() else ""):
        motion.add(SOLVER_STATE)
    return initial | {"uniform/time"} | motion


def set_aside_incomplete(run_dir: Path, moving: bool) -> list[Path]:
    """Move the incomplete trailing time folders aside (serial and ``processor*``); returns
    where they went. Only trailing folders are checked: OpenFOAM restarts from the latest."""
    run_dir = Path(run_dir)
    roots = sorted(run_dir.glob("processor[0-9]*")) or [run_dir]
    required = required_files(run_dir, moving)
    moved: list[Path] = []
    while True:
        per_root = [time_folders(root) for root in roots]
        latest = {times[-1][0] for times in per_root if times}
        if not latest:
            return moved
        t = max(latest)
        bad = False
        for times in per_root:
            entries = [p for value, p in times if value == t]
            before = [p for value, p in times if value < t]
            previous = before[-1] if before else None
            if not entries or not is_complete(entries[0], required, previous):
                bad = True  # a processor without the time is as incomplete as a cut file
        if not bad:
            return moved
        stamp = time.strftime("%Y%m%d-%H%M%S")
        target = run_dir / MARKERS / "incomplete"
        target.mkdir(parents=True, exist_ok=True)
        for root, times in zip(roots, per_root, strict=True):
            for value, path in times:
                if value == t:
                    prefix = "" if root == run_dir else f"{root.name}-"
                    dest = target / f"{prefix}{path.name}.{stamp}"
                    n = 1
                    while dest.exists():
                        n += 1
                        dest = target / f"{prefix}{path.name}.{stamp}-{n}"
                    path.rename(dest)
                    moved.append(dest)


def latest_time(run_dir: Path) -> float | None:
    """The latest time written in full: the run's, or for a parallel run the latest that every
    ``processor*`` folder holds; None when only the initial time exists. Call it after
    :func:`set_aside_incomplete`."""
    run_dir = Path(run_dir)
    roots = sorted(run_dir.glob("processor[0-9]*")) or [run_dir]
    latest = [times[-1][0] if times else None for times in map(time_folders, roots)]
    return None if None in latest else min(latest)
