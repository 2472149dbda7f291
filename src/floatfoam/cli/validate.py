"""``floatfoam validate CASE``: the grid and time-step convergence study of a case's CFD.

Runs (or resumes, or reuses when finished) the coarse, medium and fine levels, the medium
level (``--time-level fine``: the fine one) with its time steps halved and the coarse level
with its mesh motion spread wider (``--morphing F``: the six-DoF distances × F, or the
Laplacian's diffusivity 1/d; ``--no-morphing``: not run), then writes
``<build>/<case>/validation/`` (validation.json, validation.md, convergence.png:
:mod:`floatfoam.analysis.validation`).
"""

from __future__ import annotations

import sys
from pathlib import Path

from floatfoam.cli.common import add_case_arguments, add_np_argument
from floatfoam.errors import InputError


def register(sub) -> None:
    p = sub.add_parser("validate", help="grid and time-step convergence (GCI, Celik et al. "
                       "2008) of a case's period and damping")
    add_case_arguments(p)
    add_np_argument(p, "MPI ranks of every run")
    p.add_argument("--time-level", default="medium", metavar="LEVEL",
                   help="the level run once more with its time steps halved: medium "
                   "(default: taken for the fine level's time error) or fine (its own, for "
                   "about four times that run's cost)")
    motion = p.add_mutually_exclusive_group()
    motion.add_argument("--morphing", type=float, default=None, metavar="F",
                        help="the coarse level's mesh-motion run, which no level changes: its "
                        "six-DoF distances × F (÷ F at their defaults, which reach as far as "
                        "the tank allows), for the Laplacian (F > 1) its diffusivity "
                        "1/d instead of 1/d², for the layered motion its rows that move "
                        "with the body over F × the body's height; each quantity's change "
                        "is U_motion, in U_num (default: the study's own factor when its run "
                        "is finished, else "
                        "1.5)")
    motion.add_argument("--no-morphing", action="store_true",
                        help="no mesh-motion run: U_num from the levels and the time step "
                        "alone")
    p.add_argument("--slurm", action="store_true",
                   help="submit the study to Slurm instead: its runs as one array (a task "
                   "each, --np ranks) and the study (GCI, validation.json) as a job after it; "
                   "prints the job id for `floatfoam status`")
    p.add_argument("--time", default=None, metavar="D-HH:MM:SS",
                   help="with --slurm: the time limit of each run's task (default 24:00:00)")
    p.add_argument("--no-run", action="store_true",
                   help="analyse the finished runs only (made with this command's case file "
                   "and --set: others are refused); run nothing")
    p.set_defaults(func=run)


def run(args) -> int:
    """Exit codes as ``floatfoam run``'s: 0 done, 1 a run failed (the others still run and the
    study of what finished is written), 2 bad input, 75 another run holds a run directory,
    128 + signal when interrupted (the same command resumes)."""
    from floatfoam import layout
    from floatfoam.analysis.study_tables import study_markdown, write_study
    from floatfoam.analysis.validation import plan, study_morphing
    from floatfoam.case import load_case
    from floatfoam.cli.run import EXIT_LOCKED
    from floatfoam.foam.driver import check_ranks
    from floatfoam.foam.runlock import RunLockedError
    from floatfoam.workflow import check_study, run_study

    case = load_case(args.case, args.overrides)
    check_ranks(args.np, None)
    build = layout.build_dir()
    morphing = study_morphing(case.name, build, args.morphing, skip=args.no_morphing)
    if args.time is not None and not args.slurm:
        raise InputError(f"--time {args.time}: a Slurm time limit, valid only with --slurm")
    if args.slurm and args.no_run:
        raise InputError("--slurm with --no-run: valid is one of them (--slurm submits the "
                         "runs; --no-run analyses finished ones)")
    if args.slurm:
        runs = plan(args.time_level, morphing)
        check_study(case, args.np, runs, build)  # before the first is submitted
        return _submit(case, args, runs, morphing)
    try:
        outcome = run_study(case, args.np, time_level=args.time_level, morphing=morphing,
                            build=build, run=not args.no_run)
    except RunLockedError as err:
        print(f"floatfoam validate: {err}", file=sys.stderr)
        return EXIT_LOCKED
    result, failed = outcome.study, outcome.failed
    if not result["runs"]:
        return 1
    out = layout.case_build_dir(case.name, build) / "validation"
    paths = write_study(result, Path(out))
    print(study_markdown(result))
    print("written: " + ", ".join(str(p) for p in paths))
    if failed:
        print(f"floatfoam validate: failed: {', '.join(failed)} (the study holds the others)",
              file=sys.stderr)
    return 1 if failed else 0


def _submit(case, args, runs, morphing: float | None) -> int:
    """The study on Slurm: every run a task of one array, then ``validate --no-run`` (the
    study of what finished, as the local command writes it) as a job after the array."""
    from floatfoam import layout
    from floatfoam.cluster import jobs, slurm
    from floatfoam.plan.release import end_time_of

    args.time = slurm.check_time(args.time or "24:00:00")
    slurm.require_sbatch()
    end = end_time_of(case)
    tasks = [slurm.Task(case.name, layout.run_name(level, divisor, factor),
                        slurm.run_command(case.path, level, args.np, args.overrides,
                                          divisor=divisor, morphing=factor))
             for level, divisor, factor in runs]
    study = [slurm.executable(), "validate", str(case.path), "--np", str(args.np), "--no-run",
             "--time-level", args.time_level,
             *(["--no-morphing"] if morphing is None else ["--morphing", repr(morphing)])]
    for item in args.overrides:
        study += ["--set", item]
    record = jobs.submit(tasks, kind="validate", name=f"validate-{case.name}", label=case.name,
                         np_=args.np, time=args.time, end_times=[end] * len(tasks),
                         after_argv=tuple(study))
    print(f"[validate {case.name}] {len(tasks)} runs submitted as job {record['job']}, the "
          f"study as job {record['after']} after it: "
          f"{layout.case_build_dir(case.name) / 'validation'}; follow with "
          f"`floatfoam status {record['job']}` (outputs: {record['folder']}/)")
    return 0
