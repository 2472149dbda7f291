"""Read an OpenFOAM solver log as it grows: time steps, Courant numbers and the six-DoF state.

interFoam-family solvers print, per time step, ``Courant Number mean: … max: …``,
``deltaT = …`` and ``Time = …``; the six-DoF motion solver (``report on``) then prints its
status block (centre of rotation, centre of mass, orientation tensor, linear and angular
velocity). Each step's values are collected into a :class:`Step` when the next ``Time =``
line (or the end of the log) closes it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

_NUM = r"[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|nan|inf|-nan)"
_VEC = re.compile(r"\(\s*(" + _NUM + r"(?:\s+" + _NUM + r")*)\s*\)")
_TIME = re.compile(r"^Time = (" + _NUM + r")\s*$")
_COURANT = re.compile(r"^Courant Number mean: (" + _NUM + r") max: (" + _NUM + ")")
_DELTA_T = re.compile(r"^deltaT = (" + _NUM + ")")
# Lines that mean the solver died (a stack trace from the FPE/segfault handlers, or a fatal
# error); the start-up line "trapFpe: Floating point exception trapping enabled" is not one.
_FATAL = ("FOAM FATAL ERROR", "FOAM FATAL IO ERROR", "Foam::sigFpe::sigHandler",
          "Foam::sigSegv::sigHandler", "Floating point exception (core dumped)")
FATAL_CONTEXT = 8  # lines kept from the fatal error on
_STATE_KEYS = {
    "Centre of mass:": "centre_of_mass",
    "Orientation:": "orientation",
    "Linear velocity:": "velocity",
    "Angular velocity:": "angular_velocity",
}


@dataclass
class Step:
    """One solver time step: simulated time, Courant max, Δt and the body state (or None)."""

    time: float
    courant_max: float | None = None  # None: the solver printed none
    delta_t: float | None = None
    centre_of_mass: np.ndarray | None = None
    orientation: np.ndarray | None = None  # 3×3 rotation tensor, row-major as printed
    velocity: np.ndarray | None = None
    angular_velocity: np.ndarray | None = None  # rad/s

    def motion_row(self, reference: np.ndarray | None = None) -> list[float] | None:
        """time, x, y, z, roll, pitch, yaw (deg), u, v, w (m/s), p, q, r (deg/s); the angles
        are those of the attitude from ``reference`` (the equilibrium attitude's rotation
        tensor; default upright), Q·referenceᵀ."""
        if self.centre_of_mass is None or self.orientation is None:
            return None
        q = self.orientation if reference is None else self.orientation @ np.asarray(
            reference, dtype=float).T
        roll, pitch, yaw = euler_angles(q)
        vel = self.velocity if self.velocity is not None else np.zeros(3)
        omega = self.angular_velocity if self.angular_velocity is not None else np.zeros(3)
        return [self.time, *self.centre_of_mass, *np.degrees([roll, pitch, yaw]), *vel,
                *np.degrees(omega)]


def euler_angles(q: np.ndarray) -> tuple[float, float, float]:
    """Roll, pitch, yaw (radians) of R = R_z(yaw) R_y(pitch) R_x(roll); with zero yaw this is
    the convention of docs/conventions.md (heel first, then trim)."""
    pitch = -math.asin(max(-1.0, min(1.0, q[2, 0])))
    roll = math.atan2(q[2, 1], q[2, 2])
    yaw = math.atan2(q[1, 0], q[0, 0])
    return roll, pitch, yaw


@dataclass
class LogWatcher:
    """Incremental reader: feed it the log text as it grows, collect finished steps."""

    steps: list[Step] = field(default_factory=list)
    current: Step | None = None
    fatal: str | None = None
    fatal_lines: list[str] = field(default_factory=list)  # the fatal line and what follows
    ended: bool = False
    _pending: str = ""
    _courant: float | None = None
    _delta_t: float | None = None
    _current_done: bool = False  # the current step printed its ExecutionTime: it is whole

    def feed(self, text: str) -> list[Step]:
        """Parse new log text; return the steps completed by it."""
        lines = (self._pending + text).split("\n")
        self._pending = lines.pop()  # an unfinished last line waits for more text
        done: list[Step] = []
        for line in lines:
            self._line(line.strip(), done)
        self.steps.extend(done)
        return done

    def close(self) -> list[Step]:
        """Flush the last step (at the end of the log)."""
        done: list[Step] = []
        if self._pending:
            self._line(self._pending.strip(), done)
            self._pending = ""
        if self.current is not None:
            done.append(self.current)
            self.current = None
        self.steps.extend(done)
        return done

    def close_finished(self, written=None) -> list[Step]:
        """Flush the last step if the solver finished it: its ``ExecutionTime`` line is in, or
        ``written(time)`` says its time folder was written (the solver writes a step's fields
        before it prints that line). For a log whose solver was stopped mid-step, where
        :meth:`close` would take the state of an unfinished PIMPLE iteration."""
        done: list[Step] = []
        if self._pending:
            self._line(self._pending.strip(), done)
            self._pending = ""
        finished = self.current is not None and (
            self._current_done or (written is not None and written(self.current.time)))
        if finished:
            done.append(self.current)
        self.current = None
        self.steps.extend(done)
        return done

    def fatal_message(self) -> str:
        """The fatal error in one line: its first line and the cause printed after it."""
        return fatal_block(self.fatal_lines) or (self.fatal or "").strip()

    def _line(self, line: str, done: list[Step]) -> None:
        if self.fatal is not None and len(self.fatal_lines) < FATAL_CONTEXT:
            self.fatal_lines.append(line)
        if m := _TIME.match(line):
            if self.current is not None:
                done.append(self.current)
            self.current = Step(float(m.group(1)), self._courant, self._delta_t)
            self._current_done = False
        elif line.startswith("ExecutionTime"):
            self._current_done = self.current is not None
        elif m := _COURANT.match(line):
            self._courant = float(m.group(2))
        elif m := _DELTA_T.match(line):
            self._delta_t = float(m.group(1))
        elif line == "End":
            self.ended = True
        elif any(marker in line for marker in _FATAL):
            if self.fatal is None:
                self.fatal = line
                self.fatal_lines.append(line)
        elif self.current is not None:
            for key, attr in _STATE_KEYS.items():
                if line.startswith(key):
                    values = _vector(line[len(key):])
                    if values is not None:
                        if attr == "orientation" and values.size == 9:
                            values = values.reshape(3, 3)
                        setattr(self.current, attr, values)


def fatal_block(lines: list[str]) -> str:
    """The first fatal error in ``lines`` as one line: the error line and the cause after it,
    up to the first blank line that follows the cause (OpenFOAM then prints where it was
    raised), joined with " | "."""
    start = next((i for i, line in enumerate(lines)
                  if any(marker in line for marker in _FATAL)), None)
    if start is None:
        return ""
    block: list[str] = []
    for line in lines[start:start + FATAL_CONTEXT]:
        text = line.strip()
        if not text:
            if len(block) > 1:
                break
            continue
        if text.startswith(("FOAM exiting", "FOAM aborting", "From function", "in file")):
            break
        block.append(text)
    return " | ".join(block)


def _vector(text: str) -> np.ndarray | None:
    m = _VEC.search(text)
    if not m:
        return None
    return np.array([float(v) for v in m.group(1).split()])
