"""Scratch folders in the temporary directory that outlive no command.

A command's scratch folder (``floatfoam-<what>-XXXXXXXX`` in ``$TMPDIR``, named by
``mkdtemp``) is removed when the command ends, even by a signal. A SIGKILL leaves it behind: so
each folder holds a lock file, locked (``flock``) while its command lives, and every command
first removes the folders of that exact name whose lock file exists and nobody holds
(:func:`sweep`). The kernel drops a lock when its holder dies, however it dies. A folder
without the lock file is never removed: it is not one of these (a build folder named
``floatfoam-runs``, say), or an empty one left by a kill between its creation and its lock.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import re
import shutil
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

PREFIX = "floatfoam-"
WHATS = ("mesh",)  # the scratch folders' kinds
NAME = re.compile(rf"^{PREFIX}({'|'.join(WHATS)})-[a-z0-9_]{{8}}$")  # mkdtemp's 8 characters
LOCK = ".owner.lock"
LOCKING = 2.0  # s: a lock file this young may be between its creation and its lock


@contextlib.contextmanager
def scratch_dir(what: str) -> Iterator[Path]:
    """A new folder ``$TMPDIR/floatfoam-<what>-XXXXXXXX``, locked while the block runs and
    removed after it."""
    folder = Path(tempfile.mkdtemp(prefix=f"{PREFIX}{what}-"))
    fd = None
    try:
        fd = os.open(folder / LOCK, os.O_CREAT | os.O_WRONLY | os.O_CLOEXEC, 0o600)
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield folder
    finally:
        if fd is not None:
            os.close(fd)
        shutil.rmtree(folder, ignore_errors=True)


def sweep(root: Path | None = None) -> list[Path]:
    """Remove the scratch folders under ``root`` (default ``$TMPDIR``) that no live command
    holds: named as :func:`scratch_dir` names them, with a lock file nobody holds. Returns the
    folders removed; never raises."""
    removed = []
    root = Path(root or tempfile.gettempdir())
    with contextlib.suppress(OSError):
        for folder in root.glob(f"{PREFIX}*"):
            if NAME.match(folder.name) and folder.is_dir() and not folder.is_symlink() \
                    and _orphaned(folder):
                shutil.rmtree(folder, ignore_errors=True)
                removed.append(folder)
    return removed


def _orphaned(folder: Path) -> bool:
    try:
        fd = os.open(folder / LOCK, os.O_RDONLY | os.O_CLOEXEC)
    except OSError:  # no lock file: not a scratch folder of ours, or never locked
        return False
    try:
        if time.time() - os.fstat(fd).st_mtime < LOCKING:
            return False
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return False  # held: its command is alive
    finally:
        os.close(fd)
    return True
