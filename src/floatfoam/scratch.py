"""Scratch folders in the temporary directory that outlive no command.

A command's scratch folder (``floatfoam-<what>-*`` in ``$TMPDIR``) is removed when the command
ends, even by a signal. A SIGKILL leaves it behind: so each folder holds a lock file, locked
(``flock``) while its command lives, and every command first removes the folders whose lock
nobody holds (:func:`sweep`). The kernel drops a lock when its holder dies, however it dies.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

PREFIX = "floatfoam-"
LOCK = ".owner.lock"
YOUNG = 60.0  # s: a folder without its lock file yet may be one being made right now
LOCKING = 2.0  # s: a lock file this young may be between its creation and its lock


@contextlib.contextmanager
def scratch_dir(what: str) -> Iterator[Path]:
    """A new folder ``$TMPDIR/floatfoam-<what>-XXXXXXXX``, locked while the block runs and
    removed after it."""
    folder = Path(tempfile.mkdtemp(prefix=f"{PREFIX}{what}-"))
    fd = os.open(folder / LOCK, os.O_CREAT | os.O_WRONLY | os.O_CLOEXEC, 0o600)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield folder
    finally:
        os.close(fd)
        shutil.rmtree(folder, ignore_errors=True)


def sweep(root: Path | None = None) -> list[Path]:
    """Remove the scratch folders under ``root`` (default ``$TMPDIR``) that no live command
    holds: their lock is free, or they have no lock file and are over a minute old. Returns
    the folders removed; never raises."""
    removed = []
    root = Path(root or tempfile.gettempdir())
    with contextlib.suppress(OSError):
        for folder in root.glob(f"{PREFIX}*"):
            if folder.is_dir() and not folder.is_symlink() and _orphaned(folder):
                shutil.rmtree(folder, ignore_errors=True)
                removed.append(folder)
    return removed


def _orphaned(folder: Path) -> bool:
    try:
        fd = os.open(folder / LOCK, os.O_RDONLY | os.O_CLOEXEC)
    except FileNotFoundError:
        with contextlib.suppress(OSError):
            return time.time() - folder.stat().st_mtime > YOUNG
        return False
    except OSError:
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
