"""Child processes that never outlive the command that started them.

Every OpenFOAM application (and ``mpirun`` with its ranks) runs in a process group of its own,
so that it can be stopped as a whole. Three guards keep it from running on without floatfoam:

* SIGINT, SIGTERM and SIGHUP of the driver raise :class:`SignalInterruptError` (inside
  :func:`signals_interrupt`), and the ``finally`` of the caller stops the group;
* the direct child gets SIGKILL from the kernel if the driver dies (``PR_SET_PDEATHSIG``);
* a watchdog process (:data:`WATCHDOG`) holds a pipe from the driver: when the pipe closes
  without the word ``done`` — the driver was killed, even with SIGKILL — it stops the whole
  group (mpirun's ranks included, which the death signal does not reach), then exits. It also
  holds the run's lock (:mod:`floatfoam.foam.runlock`) until the group is gone, so that no new
  run starts beside a dying one.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

PR_SET_PDEATHSIG = 1
STOP_GRACE = 5.0  # s between SIGTERM and SIGKILL of a process group

WATCHDOG = r"""
import os, signal, sys, time
from floatfoam.foam.processes import group_alive
pgid = int(sys.argv[1])
word = sys.stdin.buffer.read()  # returns when the driver closes the pipe or dies
if word.strip() != b"done":
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(pgid, sig)
        except ProcessLookupError:
            break
        end = time.monotonic() + 5.0
        while group_alive(pgid) and time.monotonic() < end:
            time.sleep(0.1)
        if not group_alive(pgid):
            break
"""


class SignalInterruptError(Exception):
    """The driver received SIGINT, SIGTERM or SIGHUP (``signum``)."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum
        self.time: float | None = None  # the simulated time reached, when a solver ran

    @property
    def exit_code(self) -> int:
        """128 + the signal number: 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP."""
        return 128 + self.signum


@contextlib.contextmanager
def signals_interrupt():
    """Within the block, SIGINT, SIGTERM and SIGHUP raise :class:`SignalInterruptError`."""
    def handler(signum, frame):
        raise SignalInterruptError(signum)

    names = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
    previous = {s: signal.signal(s, handler) for s in names}
    try:
        yield
    finally:
        for s, h in previous.items():
            signal.signal(s, h)


def _die_with_parent() -> None:
    """In the child, before exec: SIGKILL when the parent dies (Linux)."""
    try:
        libc = ctypes.CDLL("libc.so.6", use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except OSError:  # not Linux: the watchdog still guards
        pass


class Child:
    """A command in its own process group, watched (see the module docstring)."""

    def __init__(self, cmd: list[str], *, cwd, stdout, env: dict, keep_fds=()):
        self.proc = subprocess.Popen(cmd, cwd=cwd, stdout=stdout, stderr=subprocess.STDOUT,
                                     env=env, start_new_session=True,
                                     preexec_fn=_die_with_parent)
        self.pgid = self.proc.pid
        self.watchdog = subprocess.Popen(
            [sys.executable, "-c", WATCHDOG, str(self.pgid)], stdin=subprocess.PIPE,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
            pass_fds=tuple(keep_fds))

    def poll(self) -> int | None:
        return self.proc.poll()

    def wait(self) -> int:
        return self.proc.wait()

    def stop(self) -> None:
        """Stop the whole group: SIGTERM, then SIGKILL after :data:`STOP_GRACE` seconds."""
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(self.pgid, sig)
            except ProcessLookupError:
                break
            end = time.monotonic() + STOP_GRACE
            while time.monotonic() < end and group_alive(self.pgid):
                self.proc.poll()
                time.sleep(0.1)
            if not group_alive(self.pgid):
                break
        self.proc.poll()

    def close(self) -> None:
        """The group is finished (or stopped): release the watchdog."""
        if self.proc.poll() is None or group_alive(self.pgid):
            self.stop()
        try:
            self.watchdog.stdin.write(b"done")
            self.watchdog.stdin.close()
        except (BrokenPipeError, ValueError):
            pass
        self.watchdog.wait()


def group_alive(pgid: int) -> bool:
    """Whether a process of group ``pgid`` still runs (zombies, which hold nothing and only
    wait to be reaped, do not count)."""
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    proc = Path("/proc")
    if not proc.is_dir():
        return True
    for stat in proc.glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if len(fields) > 2 and fields[2] == str(pgid) and fields[0] != "Z":
            return True
    return False


def run(cmd: list[str], *, cwd, stdout, env: dict) -> int:
    """Run ``cmd`` to its end as a watched :class:`Child`; the group is stopped if this is
    interrupted. Returns the exit code."""
    child = Child(cmd, cwd=cwd, stdout=stdout, env=env)
    try:
        return child.wait()
    finally:
        child.close()
