"""motion.csv from the solver's log: written as the solver goes, rebuilt from the whole log.

The six-DoF state the solver prints each step (:mod:`floatfoam.foam.logwatch`) becomes a row of
the motion CSV (columns in :data:`floatfoam.motion.MOTION_COLUMNS`). A resumed run restarts
from its last written time: its rows replace those of the interrupted run after that time
(OpenFOAM restarts with other time steps, so the interrupted run's later rows fall between
the new ones and must go).
The file is never rewritten in place: a new version is written beside it and renamed over it,
so an interrupt cannot leave it empty or cut.

The log is the motion's one source. v1912's ``sixDoFRigidBodyState`` function object is not
written: it reads the six-DoF motion *solver*, which the Laplacian route does not have (the
body's six-DoF equations live in its point displacement condition there), so it would serve
one route of two; the log carries the state on both, step by step, as the progress line reads
it.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from floatfoam.foam.logwatch import LogWatcher, Step
from floatfoam.motion import MOTION_COLUMNS

RESUMED = "// floatfoam: resumed"  # the separator the runner writes into a resumed log


ANGLES = [MOTION_COLUMNS.index(name) for name in ("roll", "pitch", "yaw")]


class MotionWriter:
    """Append motion rows to a CSV as the solver goes (header written once). On resume,
    rows at or after the restart time replace the ones of the interrupted run. The angles run
    on through ±180° (a body that turns over reaches 215°, not −145°): each is taken within
    180° of the row before."""

    def __init__(self, path: Path, reference=None):
        self.path = Path(path)
        self.reference = reference  # the equilibrium attitude: angles are measured from it
        self.last_time = -math.inf
        self.last_angles: list[float] | None = None

    def append(self, steps: list[Step]) -> None:
        rows = [r for r in (s.motion_row(self.reference) for s in steps) if r is not None]
        if not rows:
            return
        if self.last_time == -math.inf:  # the first rows of this solver run
            # rows up to the restart time, less half the first step for the log's rounding
            self._keep_before(restart_time(steps) + 0.5 * _first_step(steps))
        with open(self.path, "a") as fh:
            for row in rows:
                self._continue(row)
                fh.write(",".join(f"{v:.10g}" for v in row) + "\n")
        self.last_time = rows[-1][0]

    def _continue(self, row: list[float]) -> None:
        """The row's angles within 180° of the last row's (whole turns added)."""
        if self.last_angles is not None:
            for k, last in zip(ANGLES, self.last_angles, strict=True):
                row[k] += 360.0 * round((last - row[k]) / 360.0)
        self.last_angles = [row[k] for k in ANGLES]

    def _keep_before(self, t: float) -> None:
        """Rewrite the file with the header and the complete rows before ``t`` (just after the
        time the solver restarted from: the interrupted run's later rows, which a restart
        computes again with other steps, and a row cut by an interrupt are dropped),
        atomically."""
        kept = [",".join(MOTION_COLUMNS)]
        if self.path.exists():
            for line in self.path.read_text().splitlines()[1:]:
                cells = line.split(",")
                try:
                    values = [float(c) for c in cells]
                except ValueError:
                    continue
                if len(values) == len(MOTION_COLUMNS) and values[0] < t:
                    kept.append(line)
                    self.last_angles = [values[k] for k in ANGLES]
        fresh = self.path.with_name(self.path.name + ".new")
        fresh.write_text("\n".join(kept) + "\n")
        os.replace(fresh, self.path)


def restart_time(steps: list[Step]) -> float:
    """The time a solver run started from: its first step's time less that step's Δt (the
    log rounds the time to 8 digits and Δt to 10), or its first step's time when no Δt is
    printed."""
    first = steps[0]
    return first.time - _first_step(steps)


def _first_step(steps: list[Step]) -> float:
    dt = steps[0].delta_t
    return dt if dt is not None and dt > 0.0 else 0.0


def rebuild_motion(log: Path, csv: Path, reference=None) -> None:
    """Write ``csv`` anew from the whole solver log, resumed parts included (for a run whose
    driver stopped after the solver's last step but before recording it); angles from the
    attitude ``reference``."""
    fresh = csv.with_name(csv.name + ".rebuilt")
    fresh.unlink(missing_ok=True)
    for part in Path(log).read_text(errors="replace").split(RESUMED):
        watcher = LogWatcher()
        steps = watcher.feed(part) + watcher.close()
        MotionWriter(fresh, reference).append(steps)
    if fresh.exists():
        os.replace(fresh, csv)
