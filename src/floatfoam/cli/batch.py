"""``floatfoam batch CASE ... --levels L ...``: one Slurm array script for a sweep.

The script runs one task per (case, level), each a plain ``floatfoam run`` with the same
options, so a cluster user submits it as is (``sbatch sweep.sh``) and resubmits it to resume
whatever did not finish. Without Slurm, ``SLURM_ARRAY_TASK_ID=i bash sweep.sh`` runs task i.
"""

from __future__ import annotations

import datetime
import os
import re
import shlex
import sys
from pathlib import Path

from floatfoam import layout
from floatfoam.cli.common import add_np_argument
from floatfoam.errors import InputError
from floatfoam.layout import LEVELS

SLURM_TIME = re.compile(r"^(\d+-)?\d{1,2}(:\d{2}){0,2}$")


def register(sub) -> None:
    p = sub.add_parser("batch", help="write a Slurm array script running CASES × LEVELS")
    p.add_argument("cases", nargs="+", metavar="CASE", help="folder names under cases/ or paths")
    p.add_argument("--levels", nargs="+", default=["coarse"], metavar="LEVEL",
                   help=f"mesh levels ({', '.join(LEVELS)}; default coarse)")
    add_np_argument(p, "MPI ranks per task")
    p.add_argument("--hostfile", default=None, metavar="FILE",
                   help="Open MPI hostfile for every task (default: Slurm's allocation)")
    p.add_argument("--time", default="24:00:00", metavar="D-HH:MM:SS",
                   help="Slurm time limit per task (default 24:00:00)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a case value in every task, e.g. run.end_time=1.6")
    p.add_argument("--out", default="floatfoam-batch.sh", metavar="FILE",
                   help="script to write (default floatfoam-batch.sh; never overwritten)")
    p.set_defaults(func=run)


def run(args) -> int:
    from floatfoam.case import load_case

    for level in args.levels:
        if level not in LEVELS:
            raise InputError(f"--levels {level!r}: valid levels are {', '.join(LEVELS)}")
    if args.np < 1:
        raise InputError(f"--np {args.np}: valid is a whole number ≥ 1")
    if not SLURM_TIME.match(args.time):
        raise InputError(f"--time {args.time!r}: valid is a Slurm time, e.g. 12:00:00 or "
                         "2-00:00:00")
    if args.hostfile is not None and not Path(args.hostfile).is_file():
        raise InputError(f"--hostfile {args.hostfile}: no such file")
    out = Path(args.out)
    if not out.parent.is_dir():
        raise InputError(f"--out {out}: no folder {out.parent}; valid is a new file in an "
                         "existing folder")
    if out.exists():
        raise InputError(f"--out {out}: the file exists; valid is a new file (nothing is "
                         "overwritten)")
    from floatfoam.foam.render import end_time_of
    from floatfoam.hydrostatics.theory import equilibrium

    cases = [load_case(name, args.overrides) for name in args.cases]  # each checked now
    from floatfoam.foam.domain import plan
    from floatfoam.foam.render import release_state

    for case in cases:
        state = release_state(case, equilibrium(case))  # the release in the tank
        for level in args.levels:  # the mesh each task makes: its domain, [motion] free …
            plan(case, level, state["pose"], local=args.hostfile is None)
        end_time_of(case)  # run.end_time, or the theory's periods to set it from
    check_run_folders(cases, args.levels, args.np)
    tasks = [(str(case.path), level) for case in cases for level in args.levels]
    out.write_text(script(tasks, args))
    out.chmod(0o755)
    print(f"{out}: {len(tasks)} tasks ({len(cases)} cases × {len(args.levels)} levels, "
          f"{args.np} rank(s) each); submit with `sbatch {out}`")
    return 0


def check_run_folders(cases, levels: list[str], np_: int) -> None:
    """Refuse tasks that would share a run folder (a case or level given twice) and run
    folders that already hold a run of other settings (or --np), which a task would refuse
    after the job started: one line each, before the script is written."""
    from floatfoam.foam.driver import existing_run

    seen: dict[Path, str] = {}
    for case in cases:
        for level in levels:
            run_dir = layout.run_dir(case.name, level)
            task = f"{case.path} at {level}"
            if run_dir in seen:
                raise InputError(f"{task}: the same run folder as {seen[run_dir]} ({run_dir}); "
                                 "valid is each case and level once")
            seen[run_dir] = task
            existing_run(case, level, np_)  # InputError when it holds other settings


def script(tasks: list[tuple[str, str]], args) -> str:
    """The Slurm array script of ``tasks`` ((case path, level) pairs)."""
    exe = Path(sys.executable).with_name("floatfoam")
    command = [str(exe) if exe.exists() else "floatfoam", "run", '"$CASE"', "--level",
               '"$LEVEL"', "--np", str(args.np)]
    if args.hostfile:
        command += ["--hostfile", shlex.quote(str(Path(args.hostfile).resolve()))]
    for item in args.overrides:
        command += ["--set", shlex.quote(item)]
    build = str(layout.build_dir()) if os.environ.get(layout.BUILD_ENV) else None
    lines = [
        "#!/bin/bash",
        "#SBATCH --job-name=floatfoam",
        f"#SBATCH --array=0-{len(tasks) - 1}",
        f"#SBATCH --ntasks={args.np}",
        f"#SBATCH --time={args.time}",
        "#SBATCH --output=floatfoam-%A_%a.out",
        f"# Written by floatfoam batch on {datetime.datetime.now().isoformat(timespec='seconds')}"
        ": one task per (case, level),",
        "# each a plain `floatfoam run` (it resumes where an earlier submission stopped).",
        "set -eu",
        f"cd {shlex.quote(str(layout.ROOT))}",
        *([f"export {layout.BUILD_ENV}={shlex.quote(build)}"] if build else []),
        "TASKS=(",
        *[f"  {shlex.quote(case)}$'\\t'{level}" for case, level in tasks],
        ")",
        "IFS=$'\\t' read -r CASE LEVEL <<< \"${TASKS[${SLURM_ARRAY_TASK_ID:?set by Slurm}]}\"",
        "exec " + " ".join(command),
    ]
    return "\n".join(lines) + "\n"
