"""External computations with a bound: gmsh and Capytaine in a child process.

gmsh can loop for ever on a degenerate surface and can crash the process with a segmentation
fault; a BEM solve can be far longer than its user meant. :func:`run_bounded` runs such work in
a child process (a fresh interpreter: ``func`` and its arguments must pickle) and waits for it
with a time limit: a child that runs past it, crashes or is
interrupted is stopped, and the caller gets one :class:`~floatfoam.errors.ComputationError`
line (or the interrupt) instead of a hang, a core dump or a traceback. The child dies
with its parent (parent-death signal), so it cannot outlive the command either. Started while
other runs' solver ranks run, the child takes the cores they leave free for its OpenMP and BLAS
threads (:func:`floatfoam.cores.threads_beside_solvers`), unless the environment sets them.

Long work says how far it is on stderr: :class:`Progress` (a line per counted step, at most
every few seconds) and :class:`Heartbeat` (a line every 10 s from a thread, also for work that
cannot count: the time-domain models, the GZ curve, a long record's analysis).
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import sys
import threading
import time
import traceback

from floatfoam.cores import threads_beside_solvers
from floatfoam.errors import ComputationError, InputError
from floatfoam.interrupts import die_with_parent


def _child(conn, func, args, kwargs) -> None:
    die_with_parent(signal.SIGKILL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides
    try:
        conn.send(("ok", func(*args, **kwargs)))
    except (InputError, ComputationError) as err:
        conn.send(("error", type(err).__name__, str(err)))
    except BaseException as err:  # noqa: BLE001 - reported to the parent as one line
        last = traceback.extract_tb(err.__traceback__)[-1:]
        where = f" at {last[0].filename}:{last[0].lineno}" if last else ""
        conn.send(("error", "ComputationError", f"{type(err).__name__}: {err}{where}"))
    finally:
        conn.close()


def run_bounded(func, *args, limit: float, label: str, advice: str, **kwargs):
    """``func(*args, **kwargs)`` in a child process, at most ``limit`` seconds; returns its
    result. ``label`` names the work and ``advice`` what to change, in the error line."""
    # spawn, not fork: a process that has used OpenMP threads (Capytaine, BLAS) cannot fork a
    # child that uses them again — measured here, the forked child of such a process hangs
    context = multiprocessing.get_context("spawn")
    parent, child = context.Pipe(duplex=False)
    process = context.Process(target=_child, args=(child, func, args, kwargs), daemon=True)
    with _environment(threads_beside_solvers()):  # the child takes the environment at start
        process.start()
    child.close()
    start = time.monotonic()
    try:
        while not parent.poll(0.2):
            if not process.is_alive():
                break
            if time.monotonic() - start > limit:
                raise ComputationError(f"{label}: not done within {limit:.0f} s; {advice}")
        message = None
        if parent.poll(0):
            with contextlib.suppress(EOFError):  # the child died: its end of the pipe closed
                message = parent.recv()
        if message is None:
            process.join(1.0)
            code = process.exitcode
            cause = (f"crashed ({signal.Signals(-code).name})" if code is not None and code < 0
                     else f"stopped (exit code {code})")
            raise ComputationError(f"{label}: {cause}; {advice}")
    finally:
        if process.is_alive():
            process.kill()
        process.join()
        parent.close()
        _stop_resource_tracker()
    if message[0] == "ok":
        return message[1]
    kind, text = message[1], message[2]
    raise (InputError if kind == "InputError" else ComputationError)(text)


@contextlib.contextmanager
def _environment(values: dict[str, str]):
    """``values`` set in this process's environment for the block's length."""
    before = {name: os.environ.get(name) for name in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for name, value in before.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value


def _stop_resource_tracker() -> None:
    """Stop and reap the resource-tracker process that the spawn start method launches: left
    to itself it outlives the command by a moment (a zombie in the command's process group,
    measured with farm-bench). ``_stop`` is CPython's own (3.11), private; a later bounded call
    starts a new tracker."""
    from multiprocessing import resource_tracker

    with contextlib.suppress(Exception):
        resource_tracker._resource_tracker._stop()


class Progress:
    """A progress line on stderr at most every ``every`` seconds: done / total, elapsed, ETA."""

    def __init__(self, label: str, total: int, every: float = 5.0):
        self.label, self.total, self.every = label, total, every
        self.start = time.monotonic()
        self.last = self.start

    def update(self, done: int) -> None:
        now = time.monotonic()
        if now - self.last < self.every and done < self.total:
            return
        self.last = now
        elapsed = now - self.start
        eta = elapsed / done * (self.total - done) if done else float("nan")
        eta_text = f"{eta:.0f} s" if eta == eta else "--"
        print(f"[{self.label}] {done}/{self.total} frequencies, {elapsed:.0f} s, ETA {eta_text}",
              file=sys.stderr, flush=True)


class Heartbeat:
    """A progress line on stderr every ``every`` seconds while long work runs, from a daemon
    thread: ``[label] stage: done/total unit, elapsed, ETA`` for work that counts
    (:meth:`update`), ``[label] stage, elapsed`` for work that cannot stop to say how far it is
    (a fit over a long record, a CSV being written). A context manager; :meth:`stage` names
    the step under way. Quick work prints nothing, nor does work before the first stage: the
    checks of the input come first, and a bad input stays one line."""

    def __init__(self, label: str, every: float = 10.0):
        self.label, self.every = label, every
        self.start = time.monotonic()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._beat, daemon=True)
        self.what, self.total, self.unit, self.done = None, None, "", 0.0
        self.stage_start = self.start

    def stage(self, what: str, total: float | None = None, unit: str = "") -> None:
        """The step under way from now on, and its size when it counts (``update``)."""
        # the total and start first, the name last: the thread prints once a name is set
        self.done, self.stage_start, self.total, self.unit = 0.0, time.monotonic(), total, unit
        self.what = what

    def update(self, done: float) -> None:
        """How far the counting step is (of ``total``); cheap enough for every step."""
        self.done = done

    def line(self) -> str:
        now = time.monotonic()
        elapsed = f"{now - self.start:.0f} s"
        if not self.total:
            return f"[{self.label}] {self.what}, {elapsed}"
        fraction = min(max(self.done / self.total, 0.0), 1.0)
        spent = now - self.stage_start
        eta = f"{spent / fraction * (1.0 - fraction):.0f} s" if fraction > 0 else "--"
        return (f"[{self.label}] {self.what}: {self.done:.4g}/{self.total:.4g} {self.unit}, "
                f"{elapsed}, ETA {eta}")

    def _beat(self) -> None:
        while not self._stop.wait(self.every):
            if self.what is None:
                continue
            with contextlib.suppress(OSError):  # a closed terminal must not end the work
                print(self.line(), file=sys.stderr, flush=True)

    def __enter__(self) -> Heartbeat:
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join()
