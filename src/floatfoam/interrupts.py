"""Interrupts, in one place: signals that stop a command with one line, and children that die
with the process that started them.

* :func:`signals_interrupt`: within it, SIGINT, SIGTERM and SIGHUP raise
  :class:`SignalInterruptError`, so that every ``finally`` on the way stops what it started and
  the CLI prints one line and exits with 128 + the signal (130, 143, 129);
* :func:`die_with_parent`: in a child process, the kernel's parent-death signal (Linux), so that
  a SIGKILL of the parent takes the child with it.
"""

from __future__ import annotations

import contextlib
import ctypes
import signal

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


@contextlib.contextmanager
def signals_interrupt():
    """Within the block, SIGINT, SIGTERM and SIGHUP raise :class:`SignalInterruptError`."""
    def handler(signum, frame):
        raise SignalInterruptError(signum)

    previous = {s: signal.signal(s, handler) for s in INTERRUPTS}
    try:
        yield
    finally:
        for s, h in previous.items():
            signal.signal(s, h)


def die_with_parent(sig: int) -> None:
    """In a child process: receive ``sig`` when the parent dies (Linux; elsewhere a no-op)."""
    with contextlib.suppress(OSError):
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, sig, 0, 0, 0)
