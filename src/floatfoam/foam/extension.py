"""A run asked for another end time than the one it was made to (``--set run.end_time``).

run.end_time says only how far a run goes: a run's stamp
(:func:`floatfoam.plan.stamps.settings_digest`) leaves it out, and the run's own end time is
in its ``.floatfoam/info.json``. A run folder of the command's settings asked for another end
time

* **continues** when that time lies past its written times: a finished run from its last time
  (its finished and reconstructPar markers are cleared, so the run is gathered for ParaView
  again at its new end), an unfinished one from its latest complete time, as an interrupted run
  resumes. controlDict's ``endTime`` and info.json's ``end_time`` become the time asked, and
  ``writeInterval`` the largest interval ≤ run.write_interval that divides the time left
  (:func:`floatfoam.foam.render.write_interval`; OpenFOAM counts write times from the time it
  restarts from), so the last write falls on the new end. The motion record goes on from the
  restart (:class:`floatfoam.foam.motionlog.MotionWriter`): no row lost or doubled. The steps
  land on the continued run's own write times, so it matches a run made to the later end time
  from the start within the time step's error, not to the bit.
* is **kept as it is** when it is finished past that time: written times are never cut. Its
  record (motion.csv, which every analysis of the run reads) is longer than asked; ``--force``
  runs it anew to the time asked.
* is **refused** (InputError) when it is unfinished and already written as far as that time:
  valid is an end time past its written times, or ``--force``.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

from floatfoam import layout
from floatfoam.errors import InputError
from floatfoam.foam.paraview import RECONSTRUCT
from floatfoam.foam.render import write_interval
from floatfoam.foam.timedirs import latest_time
from floatfoam.plan.record import read_record, record_or_none, write_record

CONTINUE = "continue"  # the run goes on to the end time asked
KEEP = "keep"  # a finished run past the end time asked: kept as it is

# end times this close (relative) are one: info.json holds the float run.end_time gave
SAME_TIME = 1e-9


def own_end_time(run_dir: Path) -> float | None:
    """The end time the run in ``run_dir`` goes to (its info.json); None before it was
    rendered."""
    record = record_or_none(run_dir)
    return record.end_time if record is not None else None


def end_change(asked: float, run_dir: Path, finished: bool) -> str | None:
    """What the end time ``asked`` (s) makes of the run in ``run_dir``, stamped with the
    command's settings and ``finished`` or not: None (its own end time, or none rendered yet:
    the run as it is), :data:`CONTINUE` or :data:`KEEP` (the module docstring). Raises
    InputError for an unfinished run written as far as ``asked``. Writes nothing."""
    own = own_end_time(run_dir)
    if own is None or math.isclose(asked, own, rel_tol=SAME_TIME):
        return None
    if finished:
        return CONTINUE if asked > own else KEEP
    written = latest_time(run_dir) or 0.0
    if asked > written and not math.isclose(asked, written, rel_tol=SAME_TIME):
        return CONTINUE
    raise InputError(f"run.end_time = {asked:g} s: the unfinished run in {run_dir} is already "
                     f"written to {written:g} s (it goes to {own:g} s); valid: run.end_time > "
                     f"{written:g} s to continue it, or --force to run it anew")


def continue_to(run_dir: Path, end_time: float, interval: float) -> float:
    """Set the run in ``run_dir`` to go on to ``end_time`` (s) from its latest complete time,
    writing every ``interval`` (run.write_interval, shrunk to divide the time left): its
    finished and reconstructPar markers cleared first (a driver stopped part way leaves a run
    to resume, never one marked finished short of its end time), then controlDict's endTime
    and writeInterval and info.json's end_time. Returns the time it restarts from. Call it
    after :func:`floatfoam.foam.timedirs.set_aside_incomplete`."""
    from foamlib import FoamFile

    run_dir = Path(run_dir)
    for step in (layout.FINISHED, RECONSTRUCT):
        layout.marker(run_dir, step).unlink(missing_ok=True)
    restart = latest_time(run_dir) or 0.0
    control = FoamFile(run_dir / "system" / "controlDict")
    control["endTime"] = end_time
    writes_from(control, restart, interval)
    write_record(run_dir, replace(read_record(run_dir), end_time=end_time))
    return restart


def writes_from(control, restart: float, interval: float) -> None:
    """controlDict's (``control``, a FoamFile) writeInterval: the largest ≤ ``interval``
    (run.write_interval) that divides the time from ``restart`` to its endTime. OpenFOAM counts
    write times from the time it restarts from, and its adjustable step lands on write times
    only: the run's last write and step fall on its end time (a continued run's, a remeshed
    run's)."""
    left = float(control["endTime"]) - restart
    if left > 0.0:
        control["writeInterval"] = write_interval(left, min(interval, left))
