"""Helpers of the tests that run OpenFOAM in processes: who works in a run directory, and
whether a run holds its lock."""

from __future__ import annotations

import fcntl
import os
from pathlib import Path

#: cylinder_heave's O-grid with fewer cells: 2,820, a third of its coarse level's 8,104, for the
#: runs whose checks are of the driver (where it ends, what it writes, a hostfile, a batch
#: script, a study's tasks), not of the motion. Measured here, serial, to t = 0.6 s: 7.3 s
#: against 17.7 s, medians of 3 (`farm-bench -n 3 -- floatfoam run cylinder_heave --np 1
#: --force --set run.end_time=0.6 [SMALL_OGRID]`, `--vs` the same without).
SMALL_OGRID_SETTINGS = ["mesh.cells_side=20", "mesh.cells_radial=8", "mesh.cells_horizontal=20",
                        "mesh.cells_below=15", "mesh.cells_above=8"]
SMALL_OGRID = [word for setting in SMALL_OGRID_SETTINGS for word in ("--set", setting)]


def processes_in(folder: Path) -> list[int]:
    """PIDs of the processes working in ``folder`` (their current directory)."""
    pids = []
    for proc in Path("/proc").glob("[0-9]*"):
        try:
            if Path(os.readlink(proc / "cwd")) == folder:
                pids.append(int(proc.name))
        except OSError:
            continue
    return pids


def locked(path: Path) -> bool:
    """Whether a run holds the lock file ``path`` (its watchdog holds it until the solver is
    gone)."""
    with open(path) as fh:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return True
        fcntl.flock(fh, fcntl.LOCK_UN)
        return False
