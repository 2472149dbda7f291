"""One run at a time per run directory: an exclusive lock held for the life of the run.

The lock is ``<build>/<case>/.<level>.lock`` — beside the run directory rather than in it, so
that ``--force`` (which moves the directory aside) is refused too while a run holds it. It is a
kernel ``flock``: the kernel releases it when its last holder dies, however it dies, so a lock
is never stale; the file keeps the holder's PID and start time for the message, and a file
whose PID is gone is simply taken over. The watchdog of the solver
(:mod:`floatfoam.foam.processes`) shares the lock until the solver is gone.
"""

from __future__ import annotations

import fcntl
import os
import time
from pathlib import Path

from floatfoam.layout import case_build_dir


class RunLockedError(RuntimeError):
    """Another live run holds this run directory (message: one line with its PID)."""


def lock_path(case_name: str, level: str, build: Path | None = None) -> Path:
    return case_build_dir(case_name, build) / f".{level}.lock"


class RunLock:
    """The exclusive lock of a run directory (a context manager); ``fd`` is handed to the
    solver's watchdog."""

    def __init__(self, path: Path, label: str):
        self.path, self.label = Path(path), label
        self.fd: int | None = None
        self.previous: str = ""

    def __enter__(self) -> RunLock:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(fd, 200, 0).decode(errors="replace").split()
            os.close(fd)
            pid = holder[0] if holder else "?"
            since = " ".join(holder[1:3]) if len(holder) >= 3 else "an unknown time"
            raise RunLockedError(f"{self.label}: another run (PID {pid}, started {since}) is "
                            f"running in this directory; wait for it to end, or stop it "
                            f"(kill {pid}) and run the same command to resume") from None
        self.previous = os.pread(fd, 200, 0).decode(errors="replace").strip()
        stamp = f"{os.getpid()} {time.strftime('%Y-%m-%d %H:%M:%S')}\n".encode()
        os.ftruncate(fd, 0)
        os.pwrite(fd, stamp, 0)
        self.fd = fd
        return self

    def stale_holder(self) -> str | None:
        """The PID of an earlier holder that died without ending its run, if any."""
        pid = self.previous.split()[0] if self.previous else ""
        return pid or None

    def __exit__(self, *exc) -> None:
        if self.fd is not None:
            os.ftruncate(self.fd, 0)
            os.close(self.fd)  # releases the flock (the watchdogs have let go by now)
            self.fd = None
