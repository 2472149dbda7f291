"""Run OpenFOAM applications in a run directory: one log per application, serial or MPI,
a progress line (its ETA from the recent step rate), a motion CSV written as the solver goes,
early divergence detection, resume after an interruption.

Written by hand rather than with foamlib's ``FoamCase.run`` (which the rendering could use):
the solver must run in a watched session that dies with floatfoam
(:mod:`floatfoam.foam.processes`), under the run's lock, with its log read as it grows — none
of which foamlib's runner offers.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import sys
import time
from collections import deque
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from floatfoam.errors import ComputationError, InputError
from floatfoam.foam import processes
from floatfoam.foam.logwatch import LogWatcher, Step, euler_angles, fatal_block
from floatfoam.foam.motionlog import RESUMED, MotionWriter
from floatfoam.interrupts import SignalInterruptError
from floatfoam.layout import mark_done, step_done, time_folders

FOAM_ENV = {
    "WM_PROJECT_DIR": "/usr/share/openfoam",
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_btl_vader_single_copy_mechanism": "none",  # no CMA in containers
    # runs that share the cores advance at their share: a rank waiting on the others gives
    # its core away instead of polling, and no rank is bound to a core (two runs' ranks bound
    # to the same two cores could not move). Two 2-rank runs at once on 2 cores: 6.0 × the
    # time alone each without these, 2.85–3.1 × with the yield alone, 2.1–2.2 × with both;
    # alone unchanged (`make bench-sharing`, docs/guide/benchmarks.md)
    "OMPI_MCA_mpi_yield_when_idle": "1",
    "OMPI_MCA_hwloc_base_binding_policy": "none",
}


class RunError(ComputationError):
    """An OpenFOAM application failed or the solution diverged (message: one line)."""


@dataclass(frozen=True)
class Limits:
    """Divergence thresholds: a step beyond them stops the run."""

    max_courant: float = 20.0  # 7–20× the default maxCo (3, 1 in 3D): only a blow-up gets there
    max_body_speed: float = 10.0  # m/s
    # A morphing mesh that can no longer follow the body squeezes cells until the Courant limit
    # shrinks the time step ~500× (measured: the capsizing ellipse at 80°, 5 ms → 1e-5 s, after
    # which it made no progress). So does a flow blown up where the mesh motion changes fastest
    # (the 3D ellipsoid at 5° heel, inner/outer distances 0.06/0.32 m: air at 10³ m/s, steps of
    # 3e-6 s). 100 steps in a row below this time step stop the run.
    min_delta_t: float | None = None
    stall_steps: int = 100


class Stall:
    """Counts consecutive steps below ``Limits.min_delta_t``; says why when they are too many."""

    def __init__(self, limits: Limits):
        self.limits, self.count = limits, 0

    def check(self, steps: list[Step]) -> str | None:
        floor = self.limits.min_delta_t
        if floor is None:
            return None
        for s in steps:
            self.count = self.count + 1 if s.delta_t is not None and s.delta_t < floor else 0
            if self.count >= self.limits.stall_steps:
                where = ""
                if s.orientation is not None:
                    roll, pitch, _ = (math.degrees(a) for a in euler_angles(s.orientation))
                    where = f" with the body at roll {roll:.1f}°, pitch {pitch:.1f}°"
                return (f"the time step collapsed to {s.delta_t:.2g} s at t = {s.time:g} s"
                        f"{where}: the moving mesh squeezed its cells (a turn too large for "
                        "morphing: a smaller run.remesh_angle) or the flow blew up where the "
                        "mesh motion changes fastest (even at a few degrees); on the six-DoF "
                        "distances' motion, larger run.inner_distance and run.outer_distance "
                        "spread the deformation")
        return None


LOW_DISK = 64 * 2**20  # bytes: less free than a coarse 2D run writes in a few time folders


def free_bytes(folder: Path) -> int:
    """Free bytes on the disk holding ``folder`` (or its nearest existing parent)."""
    folder = Path(folder)
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    return shutil.disk_usage(folder).free


def disk_note(run_dir: Path) -> str:
    """A clause for a failure's message when the run's disk is (nearly) full, else "": an
    OpenFOAM application that cannot write dies with a signal or an I/O error that does not
    say so."""
    free = free_bytes(run_dir)
    if free >= LOW_DISK:
        return ""
    return (f"; the disk holding {run_dir} is full ({free / 2**20:.1f} MiB free): free some "
            "space, then run the same command to resume")


def check_disk(folder: Path) -> None:
    """Refuse to start a run on a (nearly) full disk, before anything is written."""
    free = free_bytes(folder)
    if free < LOW_DISK:
        raise InputError(f"build folder {folder}: its disk has {free / 2**20:.1f} MiB free: "
                         f"valid is at least {LOW_DISK // 2**20} MiB (free some space, or "
                         "FLOATFOAM_BUILD names a folder on another disk)")


def foam_env() -> dict:
    env = dict(os.environ)
    env.update(FOAM_ENV)
    return env


UNSAFE = re.compile(r"[\s'\"]")
# OpenFOAM reads no string over 1024 characters ("is too long (max. 1024 characters)", v1912's
# blockMesh); a run folder's deepest file adds ~60 (processor12/0.123456789/uniform/
# sixDoFRigidBodyMotionState), so the folder itself keeps 100 free.
MAX_RUN_PATH = 1024 - 100
NAME_MAX = 255  # bytes in one file name (Linux)


def check_path(run_dir: Path) -> None:
    """OpenFOAM takes no white space or quote in a case path (its file names drop them) and no
    path over 1024 characters; no file system takes a name over 255 bytes: refuse such a case
    directory before anything is written."""
    bad = UNSAFE.search(str(run_dir))
    if bad:
        raise InputError(f"case directory {str(run_dir)!r} holds {bad.group()!r}, which OpenFOAM "
                         "cannot take in a case path: valid is a case name and build folder "
                         "(FLOATFOAM_BUILD) without spaces or quotes")
    long_part = next((part for part in Path(run_dir).parts
                      if len(part.encode()) > NAME_MAX), None)
    if long_part is not None:
        raise InputError(f"case directory {str(run_dir)[:60]!r}…: its part {long_part[:20]!r}… "
                         f"is {len(long_part.encode())} bytes long: valid is at most {NAME_MAX} "
                         "bytes per folder name (FLOATFOAM_BUILD names another build folder)")
    if len(str(run_dir)) > MAX_RUN_PATH:
        raise InputError(f"case directory {str(run_dir)[:60]!r}… is {len(str(run_dir))} "
                         f"characters long: valid is at most {MAX_RUN_PATH}, for OpenFOAM reads "
                         "no path over 1024 (FLOATFOAM_BUILD names a shorter build folder)")


def run_app(run_dir: Path, name: str, argv: list[str], *, np_: int = 1,
            hostfile: Path | None = None, log_name: str | None = None, quiet: bool = False,
            marker: bool = True, check: bool = True) -> Path:
    """Run one OpenFOAM application to completion in ``run_dir``, logging to ``log.<name>``,
    in a watched process group (:mod:`floatfoam.foam.processes`).

    With ``marker`` (a step of the run driver) it is skipped when its marker says it already
    ran, and marked done after; with ``check`` a non-zero exit raises RunError with the log's
    path and its fatal-error lines (checkMesh, which exits non-zero on a poor mesh, is read from
    its log instead)."""
    log = run_dir / f"log.{log_name or name}"
    if marker and step_done(run_dir, name):
        return log
    cmd = _mpi(argv, np_, hostfile)
    if not quiet:
        label = f"{run_dir.parent.name}/{run_dir.name}"  # <case>/<level>, as the progress lines
        print(f"[{label}] {' '.join(argv)} → {log.name}", file=sys.stderr)
    with open(log, "w") as fh:
        code = processes.run(cmd, cwd=run_dir, stdout=fh, env=foam_env())
    if check and code != 0:
        cause = fatal_block(log.read_text(errors="replace").splitlines())
        raise RunError(f"{argv[0]} failed (exit code {code})"
                       + (f": {cause}" if cause else "") + f"; see {log}" + disk_note(run_dir))
    if marker:
        mark_done(run_dir, name)
    return log


def _mpi(argv: list[str], np_: int, hostfile: Path | None = None) -> list[str]:
    if np_ <= 1:
        return argv
    hosts = ["--hostfile", str(hostfile)] if hostfile else []
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", *hosts, "-np", str(np_), *argv,
            "-parallel"]


def run_solver(run_dir: Path, argv: list[str], *, end_time: float, np_: int = 1,
               hostfile: Path | None = None, motion_csv: Path | None = None,
               limits: Limits = Limits(), label: str = "", progress_every: float = 10.0,
               log_name: str | None = None, keep_fds=(), reference=None,
               stop=None) -> list[Step]:
    """Run the solver, watching its log: progress line, motion CSV, divergence, and the end.

    The log of a resumed run is appended to ``log.<solver>`` after a separator, so earlier
    output is never lost. The solver runs in a watched process group (``keep_fds``: the run's
    lock, held by its watchdog); the motion's angles are from the attitude ``reference``
    (rotation tensor; default upright). A :class:`~floatfoam.interrupts.SignalInterruptError`
    stops it and is re-raised with the last time reached (``time``). A run that ends before
    ``end_time`` is an error, unless ``stop`` (an object whose ``check(steps)`` gives a reason
    to stop, or None) gave one: the solver is then asked to write its current time and stop
    (:func:`stop_at_write_now`), and ``stop.fired`` holds the reason. Returns the parsed steps
    of this invocation.
    """
    name = log_name or Path(argv[0]).name
    label = label or run_dir.name
    log = run_dir / f"log.{name}"
    if log.exists():
        with open(log, "a") as fh:
            fh.write(f"\n{RESUMED} at {time.strftime('%Y-%m-%d %H:%M:%S')}\n")
    offset = log.stat().st_size if log.exists() else 0
    watcher = LogWatcher()
    writer = MotionWriter(motion_csv, reference) if motion_csv else None
    start = time.monotonic()
    with open(log, "a") as fh:
        child = processes.Child(_mpi(argv, np_, hostfile), cwd=run_dir, stdout=fh,
                                env=foam_env(), keep_fds=keep_fds)
    last_report = -math.inf
    rate = StepRate()
    stall = Stall(limits)
    try:
        with open(log) as reader:
            reader.seek(offset)
            try:
                while True:
                    finished = child.poll() is not None
                    if watcher.fatal and not finished:  # let it finish writing its message
                        _wait(child, 10.0)
                        finished = True
                    new_steps = watcher.feed(reader.read())
                    if finished:
                        new_steps += watcher.close()
                    if new_steps:
                        if writer:
                            writer.append(new_steps)
                        problem = diverged(new_steps, limits)
                        if problem:
                            raise RunError(f"{label}: diverged at t = {new_steps[-1].time:g} s "
                                           f"({problem}); see {log}")
                        problem = stall.check(new_steps)
                        if problem:
                            raise RunError(f"{label}: stopped: {problem}; see {log}")
                        if stop is not None and not stop.fired and not finished:
                            stop.fired = stop.check(new_steps)
                            if stop.fired:
                                print(f"[{label}] t = {new_steps[-1].time:g} s: "
                                      f"{stop.fired}", file=sys.stderr, flush=True)
                                stop_at_write_now(run_dir)
                    if watcher.fatal and finished:
                        raise RunError(f"{label}: {name} stopped: {watcher.fatal_message()}; "
                                       f"see {log}{disk_note(run_dir)}")
                    now = time.monotonic()
                    if watcher.steps and (now - last_report >= progress_every or finished):
                        last_report = now
                        step = watcher.steps[-1]
                        rate.add(now, step.time)
                        print(progress_line(label, step, len(watcher.steps), end_time,
                                            now - start, rate.eta(end_time)),
                              file=sys.stderr, flush=True)
                    if finished:
                        break
                    time.sleep(0.5)
            except SignalInterruptError as err:
                # the solver may have written more steps (and a time folder) since the last
                # read: stop it, then record what its log holds, so a resume misses no step
                child.close()
                rest = watcher.feed(reader.read()) + watcher.close_finished(
                    written=lambda t: _time_written(run_dir, t))
                if writer and rest:
                    writer.append(rest)
                err.time = watcher.steps[-1].time if watcher.steps else None
                raise
    finally:
        child.close()
        if stop is not None and stop.fired:
            stop_at_write_now(run_dir, False)
    if child.proc.returncode != 0:
        raise RunError(f"{label}: {name} failed (exit code {child.proc.returncode}); "
                       f"see {log}{disk_note(run_dir)}")
    reached = watcher.steps[-1].time if watcher.steps else None
    if stop is not None and stop.fired:
        if reached is not None and reached >= end_time * (1 - 1e-9) - 1e-12:
            stop.fired = None  # it fired at the last step: the run is done all the same
        else:
            return watcher.steps
    if reached is None or reached < end_time * (1 - 1e-9) - 1e-12:
        raise RunError(f"{label}: {name} ended at t = {reached} s, short of end_time = "
                       f"{end_time:g} s; see {log}")
    return watcher.steps


_STOP_AT = re.compile(r"^stopAt\s+\w+;", re.MULTILINE)


def stop_at_write_now(run_dir: Path, now: bool = True) -> None:
    """Ask the running solver to write its current time and stop (``stopAt writeNow`` in its
    controlDict, which it reads again at its next step: ``runTimeModifiable yes``), or put
    ``stopAt endTime`` back (``now`` False). The file is replaced whole, so the solver never
    reads it half written."""
    path = run_dir / "system" / "controlDict"
    text = _STOP_AT.sub(f"stopAt {'writeNow' if now else 'endTime'};", path.read_text(),
                        count=1)
    fresh = path.with_name(path.name + ".new")
    fresh.write_text(text)
    os.replace(fresh, path)


def _time_written(run_dir: Path, t: float) -> bool:
    """Whether the solver began to write the time folder of ``t`` (in the run or its first
    processor folder; the log and the folder's name round the time to 8 digits): it writes a
    step's fields after the step's last coupling iteration, so the state it printed is the
    step's own."""
    roots = (run_dir / "processor0", run_dir)
    return any(abs(value - t) <= 1e-7 * abs(t) for root in roots
               for value, _ in time_folders(root))


def _wait(child: processes.Child, seconds: float) -> None:
    end = time.monotonic() + seconds
    while child.poll() is None and time.monotonic() < end:
        time.sleep(0.1)


def diverged(steps: list[Step], limits: Limits) -> str | None:
    """A reason if any step shows a blow-up: NaN, Courant or body speed beyond the limits."""
    for s in steps:
        co = s.courant_max
        if co is not None and not math.isfinite(co):
            return f"Courant number is {co}"
        if co is not None and co > limits.max_courant:
            return f"Courant number {co:.3g} > {limits.max_courant:g}"
        for name in ("centre_of_mass", "velocity", "angular_velocity"):
            value = getattr(s, name)
            if value is not None and not np.all(np.isfinite(value)):
                return f"body {name.replace('_', ' ')} is not finite"
        speed = float(np.linalg.norm(s.velocity)) if s.velocity is not None else 0.0
        if speed > limits.max_body_speed:
            return f"body speed {speed:.3g} m/s > {limits.max_body_speed:g} m/s"
    return None


# The ETA's step rate is measured over the last minute of wall time: the start-up's steps (a
# first Δt far below the Courant limit's, grown step by step) leave it after a minute instead of
# weighing on it to the end, while a minute's steps still average out the swing of Δt with the
# body's speed (twice a period).
RATE_WINDOW = 60.0  # s of wall time


class StepRate:
    """Simulated seconds per wall second over the last ``window`` seconds of wall time.

    Fed one (wall, simulated time) sample per progress line; the rate is the slope between the
    newest sample and the oldest one still needed to span the window (before the run has
    lasted a window: the first sample).
    """

    def __init__(self, window: float = RATE_WINDOW):
        self.window = window
        self.samples: deque[tuple[float, float]] = deque()

    def add(self, wall: float, sim_time: float) -> None:
        self.samples.append((wall, sim_time))
        while len(self.samples) > 2 and self.samples[1][0] <= wall - self.window:
            self.samples.popleft()

    def rate(self) -> float:
        """Simulated s per wall s; NaN before two samples or while the time stands still."""
        if len(self.samples) < 2:
            return math.nan
        (w0, t0), (w1, t1) = self.samples[0], self.samples[-1]
        return (t1 - t0) / (w1 - w0) if w1 > w0 and t1 > t0 else math.nan

    def eta(self, end_time: float) -> float:
        """Wall seconds to ``end_time`` at the recent rate (NaN when there is none yet)."""
        rate = self.rate()
        if not math.isfinite(rate):
            return math.nan
        return max(end_time - self.samples[-1][1], 0.0) / rate


def progress_line(label: str, step: Step, count: int, end_time: float, wall: float,
                  eta: float) -> str:
    """``[label] t = 1.234/3.2 s (38.6 %)  step 412  Δt 2.5 ms  Co 0.41  wall 2:31  ETA 4:02``.

    ``count`` is the steps this invocation ran (a resumed run counts from its restart),
    ``wall`` the wall seconds since it started, ``eta`` the wall seconds left
    (:meth:`StepRate.eta`; NaN prints ``--:--``). Δt and Co are left out when the log has none.
    """
    fraction = min(max(step.time / end_time, 0.0), 1.0) if end_time > 0 else 1.0
    return (f"[{label}] t = {step.time:.4g}/{end_time:g} s ({100 * fraction:.1f} %)  "
            f"step {count}"
            + (f"  Δt {1e3 * step.delta_t:.3g} ms" if step.delta_t is not None else "")
            + (f"  Co {step.courant_max:.3g}" if step.courant_max is not None else "")
            + f"  wall {_clock(wall)}  ETA {_clock(eta)}")


def _clock(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "--:--"
    seconds = int(round(seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


def move_aside(run_dir: Path) -> Path:
    """Rename a run directory to ``<name>.old-<timestamp>`` (nothing is deleted)."""
    stem = f"{run_dir.name}.old-{time.strftime('%Y%m%d-%H%M%S')}"
    target, n = run_dir.with_name(stem), 1
    while target.exists():
        n += 1
        target = run_dir.with_name(f"{stem}-{n}")
    run_dir.rename(target)
    return target
