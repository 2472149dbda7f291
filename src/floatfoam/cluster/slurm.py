"""Slurm: the array script of a set of runs, its submission with ``sbatch``, and what the queue
says of it (``squeue``).

Each task of an array runs one plain ``floatfoam run`` (a level of a sweep, or a run of a
validation study), which resumes where an earlier attempt stopped and exits at once when its
run is finished; so a task killed by its time limit or requeued (``scontrol requeue``) comes
back and finishes, and a resubmitted script redoes only what is missing. The script asks
Slurm for ``--ntasks`` = the run's ``--np``: ``mpirun`` inside the task takes its ranks from
the allocation (Open MPI's Slurm support), and the case is decomposed into as many parts.
Without Slurm, ``SLURM_ARRAY_TASK_ID=i bash script`` runs task i.
"""

from __future__ import annotations

import datetime
import os
import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from floatfoam import layout
from floatfoam.errors import ComputationError, InputError

SLURM_TIME = re.compile(r"^(\d+-)?\d{1,2}(:\d{2}){0,2}$")
JOB_ID = re.compile(r"^\d+$")


@dataclass(frozen=True)
class Task:
    """One task of an array: a run of a case, and the command that makes it."""

    case: str  # the case's name (its build folder)
    run: str  # the run folder's name: level[-dt<k>][-morph<f>] (layout.run_name)
    argv: tuple[str, ...]  # the command, floatfoam's executable first

    @property
    def level(self) -> str:
        return layout.parse_run_name(self.run)[0]


def executable() -> str:
    """This installation's ``floatfoam`` (beside the running Python), else the name alone."""
    exe = Path(sys.executable).with_name("floatfoam")
    return str(exe) if exe.exists() else "floatfoam"


def run_command(case_path: str | Path, level: str, np_: int, overrides: list[str], *,
                divisor: int = 1, morphing: float = 1.0,
                hostfile: Path | None = None) -> tuple[str, ...]:
    """The ``floatfoam run`` of one task; ``--np`` is the task's ``$SLURM_NTASKS`` under Slurm
    (the allocation it was given, which the script asks to be ``np_``), else ``np_``."""
    argv = [executable(), "run", str(case_path), "--level", level,
            "--np", f"${{SLURM_NTASKS:-{np_}}}"]
    if divisor != 1:
        argv += ["--dt-divisor", str(divisor)]
    if morphing != 1:
        argv += ["--morphing", repr(float(morphing))]
    if hostfile is not None:
        argv += ["--hostfile", str(Path(hostfile).resolve())]
    for item in overrides:
        argv += ["--set", item]
    return tuple(argv)


def check_time(value: str) -> str:
    if not SLURM_TIME.match(value):
        raise InputError(f"--time {value!r}: valid is a Slurm time, e.g. 12:00:00 or "
                         "2-00:00:00")
    return value


def _word(arg: str) -> str:
    """A shell word: quoted, but ``${SLURM_NTASKS:-n}`` left for the shell to expand."""
    if re.fullmatch(r"\$\{SLURM_NTASKS:-\d+\}", arg):
        return f'"{arg}"'
    return shlex.quote(arg)


def job_name(text: str) -> str:
    """A job name of letters, digits and ``._-`` (a case's folder name may hold others)."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text)[:64] or "floatfoam"


def _sbatch_value(text: str) -> str:
    """An ``#SBATCH`` option's value, double-quoted (sbatch reads the quotes)."""
    if re.search(r'["\x00-\x1f\x7f]', text):
        raise InputError(f"{text!r}: a path with a double quote or a control character cannot "
                         "go into a Slurm script; valid is a build folder path without them")
    return f'"{text}"'


def _comment(text: str) -> str:
    return re.sub(r"[\x00-\x1f\x7f]", "?", text)


def _header(name: str, np_: int, time: str, output: str, extra: list[str]) -> list[str]:
    build = os.environ.get(layout.BUILD_ENV)
    return [
        "#!/bin/bash",
        f"#SBATCH --job-name={job_name(name)}",
        *extra,
        f"#SBATCH --ntasks={np_}",
        f"#SBATCH --time={time}",
        f"#SBATCH --output={_sbatch_value(output)}",
        "#SBATCH --open-mode=append",  # a requeued task adds to its output, never replaces it
        f"# Written by floatfoam on {datetime.datetime.now().isoformat(timespec='seconds')}.",
        "set -eu",
        f"cd {shlex.quote(str(layout.ROOT))}",
        *([f"export {layout.BUILD_ENV}={shlex.quote(str(layout.build_dir()))}"]
          if build else []),
    ]


def array_script(tasks: list[Task], *, np_: int, time: str, name: str, out_dir: Path) -> str:
    """The array script: task i runs ``tasks[i].argv``; ``--requeue``, so that a requeued or
    preempted task runs again (and resumes)."""
    lines = _header(name, np_, time, str(out_dir / "%A_%a.out"),
                    [f"#SBATCH --array=0-{len(tasks) - 1}", "#SBATCH --requeue"])
    lines += [
        "# One task per run, each a plain `floatfoam run`: it resumes where an earlier attempt",
        "# stopped, and a finished run exits at once.",
        'case "${SLURM_ARRAY_TASK_ID:?set by Slurm, or by hand to run one task}" in',
    ]
    for i, task in enumerate(tasks):
        lines.append(f"  {i})  # {_comment(task.case)} {task.run}")
        lines.append("    exec " + " ".join(_word(a) for a in task.argv) + " ;;")
    lines += [f'  *) echo "no task $SLURM_ARRAY_TASK_ID: valid 0-{len(tasks) - 1}" >&2; '
              "exit 2 ;;", "esac"]
    return "\n".join(lines) + "\n"


def single_script(argv: tuple[str, ...], *, time: str, name: str, out_dir: Path) -> str:
    """The script of a one-task job (the gather after an array)."""
    lines = _header(name, 1, time, str(out_dir / "%j.out"), [])
    lines.append("exec " + " ".join(_word(a) for a in argv))
    return "\n".join(lines) + "\n"


def require_sbatch() -> None:
    """Slurm's ``sbatch`` must be on PATH for a submission (checked before anything is
    written)."""
    if shutil.which("sbatch") is None:
        raise InputError("--submit/--slurm: no `sbatch` on PATH; valid on a machine with "
                         "Slurm's client (write the script without --submit and copy it)")


SBATCH_TIMEOUT = 120.0  # s: sbatch waits on the controller; more than this, it is not answering


def test_only(text: str) -> None:
    """``sbatch --test-only`` of a script's text: what the cluster refuses (a time over the
    partition's limit, more tasks than a node has, no default partition) is an InputError
    before anything is written."""
    try:
        proc = subprocess.run(["sbatch", "--test-only"], input=text, capture_output=True,
                              text=True, timeout=SBATCH_TIMEOUT)
    except subprocess.TimeoutExpired:
        raise InputError(f"sbatch --test-only did not answer in {SBATCH_TIMEOUT:g} s: is "
                         "Slurm's controller up (`sinfo`)?") from None
    if proc.returncode != 0:
        message = " ".join(proc.stderr.split()) or f"exit code {proc.returncode}"
        raise InputError(f"sbatch refuses the job: {message}; valid: what the cluster allows "
                         "(--time, --np; `sinfo`)")


def sbatch(script: Path, *, after: str | None = None) -> str:
    """Submit ``script`` (after the job ``after`` has ended, whatever its outcome); returns the
    job id."""
    argv = ["sbatch", "--parsable", *([f"--dependency=afterany:{after}"] if after else []),
            str(script)]
    try:
        proc = subprocess.run(argv, capture_output=True, text=True, timeout=SBATCH_TIMEOUT)
    except subprocess.TimeoutExpired:
        raise ComputationError(f"sbatch {script} did not answer in {SBATCH_TIMEOUT:g} s: the "
                               "job may or may not be submitted (`squeue --me`)") from None
    if proc.returncode != 0:
        message = " ".join(proc.stderr.split()) or f"exit code {proc.returncode}"
        raise ComputationError(f"sbatch {script} failed: {message}")
    job = proc.stdout.strip().split(";")[0]
    if not JOB_ID.match(job):
        raise ComputationError(f"sbatch {script}: no job id in its answer {proc.stdout!r}")
    return job


def queue(jobs: list[str]) -> dict[str, tuple[str, str]] | None:
    """Slurm's state and reason of each task (``<job>_<i>``) and job still in the queue, by
    id; None when the queue cannot be asked (no Slurm here, or its controller is down)."""
    if not jobs or shutil.which("squeue") is None:
        return None
    proc = subprocess.run(["squeue", "--noheader", "--array", "--jobs", ",".join(jobs),
                           "--format=%i|%T|%r"], capture_output=True, text=True, timeout=60)
    if proc.returncode != 0:  # a job Slurm has forgotten is an error when asked alone
        if "Invalid job id" in proc.stderr:
            return {}
        return None
    states = {}
    for line in proc.stdout.splitlines():
        parts = line.strip().split("|")
        if len(parts) == 3:
            states[parts[0]] = (parts[1], parts[2])
    return states
