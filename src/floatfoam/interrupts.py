"""Interrupts, in one place: signals that stop a command with one line, and children that die
with the process that started them.

* :func:`signals_interrupt`: within it, SIGINT, SIGTERM and SIGHUP raise
  :class:`SignalInterruptError`, so that every ``finally`` on the way stops what it started and
  the CLI prints one line and exits with 128 + the signal (130, 143, 129);
* :func:`die_with_parent`: in a child process, the kernel's parent-death signal (Linux), so that
  a SIGKILL of the parent takes the child with it;
* :func:`handlers_kept`: around a library call that resets the process's signal handlers
  behind Python's back (gmsh), Python's are put back.
"""

from __future__ import annotations

import contextlib
import ctypes
import signal
import threading

PR_SET_PDEATHSIG = 1
INTERRUPTS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


class SignalInterruptError(BaseException):
    """The process received SIGINT, SIGTERM or SIGHUP (``signum``). A BaseException, as
    KeyboardInterrupt is, so that no ``except Exception`` on the way swallows it."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum
        self.time: float | None = None  # the simulated time reached, when a solver ran

    @property
    def exit_code(self) -> int:
        """128 + the signal number: 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP."""
        return 128 + self.signum


#: the interrupting signal received within :func:`signals_interrupt`, if any: a signal that
#: lands inside a call into a C library (gmsh's ctypes) reaches the caller wrapped in that
#: library's own exception (ctypes.ArgumentError), no longer a SignalInterruptError
RECEIVED: list[int] = []


@contextlib.contextmanager
def signals_interrupt():
    """Within the block, SIGINT, SIGTERM and SIGHUP raise :class:`SignalInterruptError` (and
    are kept in :data:`RECEIVED`)."""
    def handler(signum, frame):
        RECEIVED.append(signum)
        raise SignalInterruptError(signum)

    RECEIVED.clear()
    # a process started with them blocked (a parent's mask is inherited) would keep them
    # pending to its end: they are unblocked within the block, the caller's mask put back
    # after (read first without a change: one pending raises from the unblocking call)
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, ())
    previous = {s: signal.signal(s, handler) for s in INTERRUPTS}
    try:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, INTERRUPTS)
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        for s, h in previous.items():
            signal.signal(s, h)


@contextlib.contextmanager
def handlers_kept():
    """On leaving the block, the handlers Python holds for SIGINT, SIGTERM, SIGHUP and SIGPIPE
    are installed again in the process.

    A C library may set a signal's action behind Python's back, and Python's own view
    (``signal.getsignal``) does not change. gmsh 4.15.2's first ``gmsh.initialize`` in a process
    sets SIGHUP, SIGTERM and SIGPIPE to their default actions (measured with ``sigaction``):
    afterwards a SIGTERM ended a run at once, without its ``finally`` blocks — no one-line
    message, its meshing folder left in /tmp — and a closed pipe killed the process. Outside
    the main thread, where Python cannot set handlers, this does nothing."""
    signals = (*INTERRUPTS, signal.SIGPIPE)
    held = {s: signal.getsignal(s) for s in signals}
    try:
        yield
    finally:
        if threading.current_thread() is threading.main_thread():
            for s, handler in held.items():
                if handler is not None:  # None: not set from Python, nothing to put back
                    signal.signal(s, handler)


def die_with_parent(sig: int) -> None:
    """In a child process: receive ``sig`` when the parent dies (Linux; elsewhere a no-op)."""
    with contextlib.suppress(OSError):
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, sig, 0, 0, 0)
