"""Submitted jobs: the submission of an array and the job after it, their records, each task's
state and progress from the queue and from its run's own folder, and the summary of a sweep.

Every submission has a folder of its own, ``<build>/slurm/<name>-<n>/``: its record
(``record.json``: the array's job id, its tasks — case, run folder, command —, the job after
it), its scripts, the tasks' outputs (``<job>_<task>.out``) and the summary. A job id is the
cluster's, and two clusters (or a restarted one) may give the same id: a record is found by
its id and every match is shown. The state of a task is the queue's while Slurm holds it, else
its run's: finished (the driver's marker), stopped at the time it reached, or never started.
Its simulated time and rate come from the solver's log.
"""

from __future__ import annotations

import datetime
import json
import math
import os
import re
import sys
from pathlib import Path

from floatfoam import layout
from floatfoam.cluster import slurm
from floatfoam.cluster.slurm import Task
from floatfoam.errors import ComputationError, InputError
from floatfoam.jsonfile import dump_json
from floatfoam.plan.record import record_or_none

JOBS_DIR = "slurm"
RECORD = "record.json"
TAIL_BYTES = 1 << 20  # the end of the solver's log read for its progress
_TIME = re.compile(r"^Time = ([-+0-9.eE]+)\s*$")
_CLOCK = re.compile(r"ClockTime = ([0-9.eE+-]+) s")


def jobs_dir(build: Path | None = None) -> Path:
    return Path(build or layout.build_dir()) / JOBS_DIR


def _free_folder(stem: str, build: Path | None = None) -> Path:
    """The first ``<build>/slurm/<stem>-<n>`` that does not exist (not made here)."""
    folder, n = jobs_dir(build), 1
    while (folder / f"{stem}-{n}").exists():
        n += 1
    return folder / f"{stem}-{n}"


def write_record(record: dict) -> Path:
    """Write (or update) a submission's record whole: a reader never sees half of it."""
    path = Path(record["folder"]) / RECORD
    fresh = path.with_name(f".{path.name}.new")
    fresh.write_text(dump_json(record) + "\n")
    os.replace(fresh, path)
    return path


def submit(tasks: list[Task], *, kind: str, name: str, label: str, np_: int, time: str,
           end_times: list[float | None], after_argv: tuple[str, ...],
           script: Path | None = None) -> dict:
    """Submit ``tasks`` as one array and ``after_argv`` as a job after it, whatever the
    array's outcome (``{folder}`` in it: the submission's folder); returns the record.
    ``script``: where the array's script goes (a new file; default the submission's folder);
    ``name``: the jobs' name and the folder's stem; ``label``: what the record says was
    submitted. The cluster is asked first (``sbatch --test-only``): what it refuses is an
    InputError before anything is written."""
    stem = slurm.job_name(name)
    folder = _free_folder(stem)
    array = slurm.array_script(tasks, np_=np_, time=time, name=stem, out_dir=folder)
    slurm.test_only(array)
    folder.mkdir(parents=True)  # a new folder: a submission never writes into another's
    script = script or folder / "array.sh"
    with open(script, "x") as fh:
        fh.write(array)
    script.chmod(0o755)
    job = slurm.sbatch(script)
    record = {"job": job, "kind": kind, "label": label, "folder": str(folder),
              "script": str(Path(script).resolve()), "after": None,
              "submitted": datetime.datetime.now().isoformat(timespec="seconds"),
              "tasks": [{"case": t.case, "run": t.run, "argv": list(t.argv), "end_time": e}
                        for t, e in zip(tasks, end_times, strict=True)]}
    write_record(record)
    after = folder / "after.sh"
    after_argv = tuple(a.replace("{folder}", str(folder)) for a in after_argv)
    after.write_text(slurm.single_script(after_argv, time="1:00:00", name=f"{stem}-after",
                                         out_dir=folder))
    after.chmod(0o755)
    try:
        record["after"] = slurm.sbatch(after, after=job)
    except ComputationError as err:
        print(f"floatfoam: the array is submitted as job {job}, but not the job after it "
              f"({err}); submit it with `sbatch --dependency=afterany:{job} {after}`",
              file=sys.stderr)
        raise
    finally:
        write_record(record)
    return record


def read_records(jobs: list[str] | None = None, build: Path | None = None) -> list[dict]:
    """The records of ``jobs`` (each must match one or more), or every record, newest first."""
    folder = jobs_dir(build)
    paths = sorted(folder.glob(f"*/{RECORD}")) if folder.is_dir() else []
    records = sorted((json.loads(p.read_text()) for p in paths),
                     key=lambda r: r.get("submitted", ""), reverse=True)
    if not jobs:
        return records
    chosen = []
    for job in jobs:
        if (Path(job) / RECORD).is_file():  # a submission's folder
            chosen.append(json.loads((Path(job) / RECORD).read_text()))
            continue
        found = [r for r in records if r["job"] == job]
        if not found:
            known = ", ".join(r["job"] for r in records) or "none"
            raise InputError(f"JOB {job}: no job of floatfoam's submitted from build folder "
                             f"{folder.parent}; valid: {known}")
        chosen += found
    return chosen


def progress(run_dir: Path) -> tuple[float | None, float | None]:
    """(simulated time reached, simulated seconds per wall second) of the solver's log in
    ``run_dir``: the time of the last step it finished and the rate over the log's end, since
    the solver's last start (None for what the log does not say: a solver restarted and
    stopped before its first step has neither)."""
    log = Path(run_dir) / "log.interFoam"
    if not log.is_file():
        return None, None
    with open(log, "rb") as fh:
        fh.seek(max(0, log.stat().st_size - TAIL_BYTES))
        text = fh.read().decode("utf-8", "replace")
    from floatfoam.foam.motionlog import RESUMED

    text = text.rsplit(RESUMED, 1)[-1]
    points, current = [], None
    for line in text.splitlines():
        found = _TIME.match(line)
        if found:
            current = float(found.group(1))
            continue
        clock = _CLOCK.search(line)
        if clock and current is not None:
            points.append((current, float(clock.group(1))))
    if not points:
        return current, None
    (t0, c0), (t1, c1) = points[0], points[-1]
    rate = (t1 - t0) / (c1 - c0) if c1 > c0 and t1 > t0 else None
    return t1, rate


def task_rows(record: dict, queued: dict[str, tuple[str, str]] | None,
              build: Path | None = None) -> list[dict]:
    """One row per task of a record: its id, case, run, state, time reached, end time, ETA
    (s)."""
    rows = []
    for i, task in enumerate(record["tasks"]):
        ident = f"{record['job']}_{i}"
        run_dir = layout.case_build_dir(task["case"], build) / task["run"]
        reached, rate = progress(run_dir)
        end = _end_time(run_dir) or task.get("end_time")
        if queued is not None and ident in queued:
            state, reason = queued[ident]
            state = state.lower() + (f" ({reason})" if state == "PENDING" and reason not in
                                     ("None", "") else "")
        elif layout.is_finished(run_dir):
            state = "finished"
        elif reached is not None:
            state = "stopped" if queued is not None else "not running here"
        else:
            state = "no run" if queued is not None else "not started here"
        running = state.startswith("running")
        eta = (end - reached) / rate if running and rate and end and reached is not None \
            else None
        rows.append({"task": ident, "case": task["case"], "run": task["run"], "state": state,
                     "time": reached, "end_time": end, "eta_s": eta,
                     "run_dir": str(run_dir)})
    return rows


def after_state(record: dict, queued: dict[str, tuple[str, str]] | None) -> str | None:
    """The state of the job after the array: the queue's, else "ended"."""
    after = record.get("after")
    if not after:
        return None
    if queued is not None and after in queued:
        state, reason = queued[after]
        return state.lower() + (f" ({reason})" if state == "PENDING" and reason not in
                                ("None", "") else "")
    return "ended" if queued is not None else "unknown here"


def _end_time(run_dir: Path) -> float | None:
    from floatfoam.foam.extension import own_end_time

    return own_end_time(run_dir)


def clock(seconds: float | None) -> str:
    if seconds is None or not math.isfinite(seconds):
        return "—"
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


def table(rows: list[dict]) -> list[str]:
    """The status table of a record's rows (plain text, aligned)."""
    head = ("task", "case", "run", "state", "t / end (s)", "ETA")
    body = [(r["task"], r["case"], r["run"], r["state"],
             f"{_num(r['time'])} / {_num(r['end_time'])}", clock(r["eta_s"])) for r in rows]
    widths = [max(len(str(x)) for x in col) for col in zip(head, *body, strict=True)]
    return ["  ".join(str(x).ljust(w) for x, w in zip(line, widths, strict=True)).rstrip()
            for line in (head, *body)]


def _num(value: float | None) -> str:
    return "—" if value is None else f"{value:.4g}"


def summary(record: dict, build: Path | None = None) -> list[dict]:
    """Each task's finished run analysed: the released DoFs' damped period and damping ratio
    (or why not), and its cells."""
    from floatfoam.analysis.decay import analyse_decay
    from floatfoam.analysis.released import choose
    from floatfoam.motion import dof_series, file_unit, read_motion

    out = []
    for row in task_rows(record, None, build):
        run_dir = Path(row["run_dir"])
        entry = {"task": row["task"], "case": row["case"], "run": row["run"],
                 "finished": row["state"] == "finished", "time": row["time"], "dofs": {}}
        record = record_or_none(run_dir)
        if record is not None:
            entry["cells"] = record.cells
        motion_csv = run_dir / "motion.csv"
        dofs, motion = (), None
        if entry["finished"] and motion_csv.is_file():
            try:
                motion = read_motion(motion_csv)
                dofs = choose(motion_csv, motion).dofs
            except (InputError, OSError, ValueError) as err:
                entry["note"] = str(err)
            for dof in dofs:
                scale, unit = file_unit(dof)
                t, x = dof_series(motion, dof)
                try:
                    fit = analyse_decay(t, x, units=(scale, unit), name=dof).summary()
                    entry["dofs"][dof] = {"period_s": fit["period_mean"],
                                          "damping_ratio": fit["damping_ratio"]}
                except InputError as err:
                    entry["dofs"][dof] = {"error": str(err)}
        out.append(entry)
    return out


def summary_markdown(record: dict, entries: list[dict]) -> str:
    lines = [f"# Job {record['job']}: {record['label']}", "",
             "| task | case | run | finished | cells | DoF | T_d (s) | ζ |",
             "|---|---|---|---|---|---|---|---|"]
    for e in entries:
        first = [e["task"], e["case"], e["run"], "yes" if e["finished"] else
                 f"no ({_num(e['time'])} s)", str(e.get("cells") or "—")]
        if not e["dofs"]:
            note = e.get("note", "—").split(";")[0].replace("|", "/")
            lines.append("| " + " | ".join([*first, "—", "—", note]) + " |")
        for dof, fit in e["dofs"].items():
            values = [f"{fit['period_s']:.4f}", f"{fit['damping_ratio']:.4f}"] \
                if "period_s" in fit else ["—", fit["error"].split(";")[0].replace("|", "/")]
            lines.append("| " + " | ".join([*first, dof, *values]) + " |")
    return "\n".join(lines) + "\n"
