"""Child processes that never outlive the command that started them.

Every OpenFOAM application (and ``mpirun`` with its ranks) runs in a session of its own: Open
MPI puts each rank in a process group of its own but keeps them in mpirun's session, so the
session is what holds "the solver". Three guards keep it from running on without floatfoam:

* SIGINT, SIGTERM and SIGHUP of the driver raise
  :class:`~floatfoam.interrupts.SignalInterruptError`, and the ``finally`` of the caller stops
  the session;
* the direct child gets SIGTERM from the kernel if the driver dies (``PR_SET_PDEATHSIG``), so
  that mpirun can take its ranks down;
* a watchdog process (:data:`WATCHDOG`) holds a pipe from the driver: when the pipe closes
  without the word ``done`` — the driver was killed, even with SIGKILL — it stops every process
  of the session (ranks orphaned by a dead mpirun included), then exits. It also holds the
  run's lock (:mod:`floatfoam.foam.runlock`) until the session is empty, so that no new run
  starts beside a dying one.

Stopping is SIGTERM to every live process of the session, then SIGKILL after
:data:`STOP_GRACE` seconds. Signals are blocked while a child and its watchdog are started,
so that an interrupt cannot fall between the two.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from floatfoam.interrupts import INTERRUPTS, die_with_parent

STOP_GRACE = 5.0  # s between SIGTERM and SIGKILL of a session

WATCHDOG = r"""
import sys
from floatfoam.foam.processes import stop_session
word = sys.stdin.buffer.read()  # returns when the driver closes the pipe or dies
if word.strip() != b"done":
    stop_session(int(sys.argv[1]))
"""


def session_members(sid: int) -> list[int]:
    """Live (not zombie) processes of session ``sid``, read from /proc."""
    members = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        # after the command: state, ppid, pgrp, session, ...
        if len(fields) > 3 and fields[3] == str(sid) and fields[0] not in ("Z", "X"):
            members.append(int(stat.parent.name))
    return members


def stop_session(sid: int, grace: float = STOP_GRACE) -> None:
    """SIGTERM every live process of session ``sid``, SIGKILL what is left after ``grace``
    seconds; returns when the session is empty (or after a last grace period)."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        for pid in session_members(sid):
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(pid, sig)
        end = time.monotonic() + grace
        while session_members(sid) and time.monotonic() < end:
            time.sleep(0.1)
        if not session_members(sid):
            return


def _child_setup(parent: int) -> None:
    """In the child, before exec: unblock the interrupts (blocked in the parent around the
    spawn), SIGTERM when the parent dies, and stop at once if it is already gone."""
    signal.pthread_sigmask(signal.SIG_UNBLOCK, INTERRUPTS)
    die_with_parent(signal.SIGTERM)  # not Linux: the watchdog still guards
    if os.getppid() != parent:
        os._exit(1)


class Child:
    """A command in a session of its own, watched (see the module docstring)."""

    def __init__(self, cmd: list[str], *, cwd, stdout, env: dict, keep_fds=()):
        parent = os.getpid()
        # the mask to put back, read without changing it: a pending interrupt's handler may
        # raise from the call that blocks them, and the mask must not stay blocked then
        mask = signal.pthread_sigmask(signal.SIG_BLOCK, ())
        try:
            signal.pthread_sigmask(signal.SIG_BLOCK, INTERRUPTS)
            self.proc = subprocess.Popen(cmd, cwd=cwd, stdout=stdout, stderr=subprocess.STDOUT,
                                         env=env, start_new_session=True,
                                         preexec_fn=lambda: _child_setup(parent))
            self.sid = self.proc.pid
            try:
                self.watchdog = subprocess.Popen(
                    [sys.executable, "-c", WATCHDOG, str(self.sid)], stdin=subprocess.PIPE,
                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                    start_new_session=True, pass_fds=tuple(keep_fds),
                    preexec_fn=lambda: signal.pthread_sigmask(signal.SIG_UNBLOCK, INTERRUPTS))
            except BaseException:
                stop_session(self.sid)
                raise
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)

    def poll(self) -> int | None:
        return self.proc.poll()

    def wait(self) -> int:
        return self.proc.wait()

    def close(self) -> None:
        """The command ended, or the caller gives up on it: stop whatever of the session is
        left, then release the watchdog."""
        if self.proc.poll() is None or session_members(self.sid):
            stop_session(self.sid)
        self.proc.poll()
        with contextlib.suppress(BrokenPipeError, ValueError):
            self.watchdog.stdin.write(b"done")
            self.watchdog.stdin.close()
        self.watchdog.wait()


def run(cmd: list[str], *, cwd, stdout, env: dict) -> int:
    """Run ``cmd`` to its end as a watched :class:`Child`; the session is stopped if this is
    interrupted. Returns the exit code."""
    child = Child(cmd, cwd=cwd, stdout=stdout, env=env)
    try:
        return child.wait()
    finally:
        child.close()
