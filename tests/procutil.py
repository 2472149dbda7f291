"""Helpers of the tests that run OpenFOAM in processes: who works in a run directory, and
whether a run holds its lock."""

from __future__ import annotations

import fcntl
import os
from pathlib import Path


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
