"""``floatfoam batch CASE ... --levels L ...``: one Slurm array script for a sweep, and with
``--submit`` its submission and a summary job after it.

The script runs one task per (case, level), each a plain ``floatfoam run`` with the same
options (:mod:`floatfoam.cluster.slurm`), so a cluster user submits it as is (``sbatch
sweep.sh``) and resubmits it to resume whatever did not finish. Without Slurm,
``SLURM_ARRAY_TASK_ID=i bash sweep.sh`` runs task i. ``floatfoam status`` follows a submitted
job.
"""

from __future__ import annotations

from pathlib import Path

from floatfoam import layout
from floatfoam.cli.common import add_np_argument
from floatfoam.errors import InputError
from floatfoam.layout import LEVELS


def register(sub) -> None:
    p = sub.add_parser("batch", help="write (and --submit) a Slurm array script running "
                       "CASES × LEVELS")
    p.add_argument("cases", nargs="+", metavar="CASE", help="folder names under cases/ or paths")
    p.add_argument("--levels", nargs="+", default=["coarse"], metavar="LEVEL",
                   help=f"mesh levels ({', '.join(LEVELS)}; default coarse)")
    add_np_argument(p, "MPI ranks per task (the task's Slurm --ntasks)")
    p.add_argument("--hostfile", default=None, metavar="FILE",
                   help="Open MPI hostfile for every task (default: Slurm's allocation)")
    p.add_argument("--time", default="24:00:00", metavar="D-HH:MM:SS",
                   help="Slurm time limit per task (default 24:00:00); a task stopped by it "
                   "resumes when the script is submitted again")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a case value in every task, e.g. run.end_time=1.6")
    p.add_argument("--out", default="floatfoam-batch.sh", metavar="FILE",
                   help="script to write (default floatfoam-batch.sh; never overwritten)")
    p.add_argument("--submit", action="store_true",
                   help="submit the script with sbatch, and after it a job writing the sweep's "
                   "summary (summary.md in the submission's folder <build>/slurm/batch-<n>/, "
                   "with the tasks' outputs); prints the job id for `floatfoam status`")
    p.set_defaults(func=run)


def run(args) -> int:
    from floatfoam.case import load_case
    from floatfoam.cluster import jobs, slurm

    for level in args.levels:
        if level not in LEVELS:
            raise InputError(f"--levels {level!r}: valid levels are {', '.join(LEVELS)}")
    if args.np < 1:
        raise InputError(f"--np {args.np}: valid is a whole number ≥ 1")
    slurm.check_time(args.time)
    if args.hostfile is not None and not Path(args.hostfile).is_file():
        raise InputError(f"--hostfile {args.hostfile}: no such file")
    out = Path(args.out)
    if not out.parent.is_dir():
        raise InputError(f"--out {out}: no folder {out.parent}; valid is a new file in an "
                         "existing folder")
    if out.exists():
        raise InputError(f"--out {out}: the file exists; valid is a new file (nothing is "
                         "overwritten)")
    if args.submit:
        slurm.require_sbatch()
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.plan.release import end_time_of

    cases = [load_case(name, args.overrides) for name in args.cases]  # each checked now
    from floatfoam.foam.domain import plan
    from floatfoam.plan.release import release_state

    end_times = {}
    for case in cases:
        state = release_state(case, equilibrium(case))  # the release in the tank
        for level in args.levels:  # the mesh each task makes: its domain, [motion] free …
            plan(case, level, state["pose"], local=args.hostfile is None)
        end_times[case.name] = end_time_of(case)  # run.end_time, or the theory's periods
    check_run_folders(cases, args.levels, args.np)
    tasks = [slurm.Task(case.name, level, slurm.run_command(
                 case.path, level, args.np, args.overrides,
                 hostfile=Path(args.hostfile) if args.hostfile else None))
             for case in cases for level in args.levels]
    what = (f"{len(tasks)} tasks ({len(cases)} cases × {len(args.levels)} levels, "
            f"{args.np} rank(s) each)")
    if not args.submit:
        outputs = jobs.jobs_dir()
        text = slurm.array_script(tasks, np_=args.np, time=args.time, name="floatfoam",
                                  out_dir=outputs)  # checked whole before anything is written
        outputs.mkdir(parents=True, exist_ok=True)
        out.write_text(text)
        out.chmod(0o755)
        print(f"{out}: {what}; submit with `sbatch {out}` (its output: {outputs}/)")
        return 0
    record = jobs.submit(tasks, kind="batch", name="batch",
                         label=f"{' '.join(args.cases)} at {' '.join(args.levels)}",
                         np_=args.np, time=args.time, script=out,
                         end_times=[end_times[t.case] for t in tasks],
                         after_argv=(slurm.executable(), "status", "--summary", "{folder}"))
    print(f"{out}: {what}; submitted as job {record['job']}, its summary as job "
          f"{record['after']} after it; follow with `floatfoam status {record['job']}` "
          f"(outputs: {record['folder']}/)")
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
