"""``floatfoam run CASE``: the CFD free-decay run of a case (OpenFOAM interFoam + six DoF)."""

from __future__ import annotations

import sys
from pathlib import Path

from floatfoam.cli.common import add_case_arguments
from floatfoam.errors import InputError
from floatfoam.interrupts import SignalInterruptError
from floatfoam.layout import LEVELS

EXIT_LOCKED = 75  # EX_TEMPFAIL (sysexits.h): another run holds the directory, try later


def register(sub) -> None:
    p = sub.add_parser("run", help="run the CFD free decay of a case (OpenFOAM v1912)")
    add_case_arguments(p)
    p.add_argument("--level", default="coarse", help=f"mesh level: {', '.join(LEVELS)}")
    p.add_argument("--np", type=int, default=1, help="MPI ranks (default 1: serial)")
    p.add_argument("--hostfile", type=Path, default=None, metavar="FILE",
                   help="Open MPI hostfile for the ranks (default: this machine)")
    p.add_argument("--force", action="store_true",
                   help="move an earlier run of this case and level aside and run anew")
    p.add_argument("--dt-divisor", type=int, default=1, metavar="K",
                   help="divide the level's time-step limits (largest step, Courant numbers) "
                        "by K: a time-step study, run in <level>-dt<K> (default 1)")
    p.add_argument("--morphing", type=float, default=1.0, metavar="F",
                   help="multiply the six-DoF morphing distances (run.inner_distance and "
                        "run.outer_distance, or their defaults) by F: a morphing study, run in "
                        "<level>-morph<F> (default 1)")
    p.set_defaults(func=run)


def run(args) -> int:
    """Exit codes: 0 done, 1 the run failed (log and fatal error in the message), 2 bad input,
    75 another run holds the run directory, 128 + signal when interrupted (130 SIGINT,
    143 SIGTERM, 129 SIGHUP)."""
    from floatfoam.case import load_case
    from floatfoam.foam.driver import run_case
    from floatfoam.foam.runlock import RunLockedError
    from floatfoam.foam.runner import RunError
    from floatfoam.hydrostatics.theory import equilibrium

    try:
        case = load_case(args.case, args.overrides)
        if args.level not in LEVELS:
            raise InputError(f"--level {args.level!r}: valid levels are {', '.join(LEVELS)}")
        eq = equilibrium(case)  # solved once, handed to the rendering and the summary
        result = run_case(case, args.level, args.np, args.force, equilibrium=eq,
                          hostfile=args.hostfile, time_step_divisor=args.dt_divisor,
                          morphing=args.morphing)
    except RunError as err:
        _say(f"floatfoam run: {err}")
        return 1
    except RunLockedError as err:
        _say(f"floatfoam run: {err}")
        return EXIT_LOCKED
    except SignalInterruptError as err:
        where = f"at t = {err.time:g} s" if err.time is not None else "before the solver ran"
        _say(f"floatfoam run: interrupted ({err}) {where}; run the same command to resume")
        return err.exit_code
    if result.already_finished:
        print(f"{result.run_dir} holds a finished run (use --force to run it again).")
    print_summary(case, result, eq)
    return 0


def _say(line: str) -> None:
    """One line on stderr; a closed terminal (SIGHUP) must not turn it into a traceback."""
    try:
        print(line, file=sys.stderr, flush=True)
    except OSError:
        pass


def print_summary(case, result, eq) -> None:
    """The motion series of each DoF the release displaces, its period and damping ratio
    beside the theory's period (a DoF the release leaves alone is not analysed: its record is
    noise)."""
    from floatfoam.dofs import released
    from floatfoam.hydrostatics.theory import theory_summary
    from floatfoam.motion import read_motion

    theory = theory_summary(case, eq)
    if not result.motion_csv.exists():  # a body held still (run.static_body) has no motion
        print(f"no motion series (the body is held still); run: {result.run_dir}")
        _still_water(case, result.run_dir)
        return
    print(f"motion series: {result.motion_csv}")
    motion = read_motion(result.motion_csv)
    dofs = released(case.release) or released({"heave": 1.0})
    columns = [(d, d.column) for d in dofs]
    t = motion["time"]
    header = f"{'time (s)':>9}" + "".join(f" {f'{d.name} ({d.unit})':>14}" for d, _ in columns)
    print(header)
    for i in range(0, len(t), max(1, len(t) // 12)):
        print(f"{t[i]:>9.3f}" + "".join(f" {motion[c][i]:>14.6g}" for _, c in columns))
    for d, _ in columns:
        _dof_summary(d, motion, theory)


def _still_water(case, run_dir: Path) -> None:
    """The currents the scheme drives around a held body (analysis.stillwater): one line, and
    every written time in still_water.json of the run directory."""
    from floatfoam.analysis import stillwater
    from floatfoam.meshing.levels import tank

    band = tank(case).band
    try:
        rows = stillwater.currents(run_dir, band)
    except Exception as err:  # noqa: BLE001 — the run is done; its summary must not lose it
        print(f"still-water currents not read ({type(err).__name__}: {err})")
        return
    stillwater.write(rows, band, run_dir / stillwater.FILE)
    print(stillwater.summary(rows, band))
    print(f"every written time: {run_dir / stillwater.FILE}")


def _dof_summary(d, motion, theory) -> None:
    """Theory period and the CFD's damped period and damping ratio of one DoF."""
    from floatfoam.analysis.decay import analyse_decay
    from floatfoam.motion import dof_series

    period = theory.period(d.name)
    memoir = theory.memoir.get(f"{d.name}_period")
    what = "no added mass" if d.name == "heave" else "no added inertia"
    entry = theory.dofs.get(d.name)
    if entry is not None and entry.verdict not in (None, "oscillates"):
        print(f"theory {d.name}: {entry.verdict} (GM {entry.metacentric_height:.4g} m)")
    elif period:
        print(f"theory {d.name} period ({what}): {period:.4f} s"
              + (f"; memoir: {memoir:.4f} s" if memoir else ""))
    t, x = dof_series(motion, d.name)
    if entry is not None and entry.verdict == "capsizes":
        _capsize_path(d, t, x)
        return
    try:
        decay = analyse_decay(t, x, units=(d.file_scale, d.unit), name=d.column).summary()
        print(f"CFD damped {d.name} period: {decay['period_mean']:.4f} s, damping ratio "
              f"{decay['damping_ratio']:.3f} over {decay['n_cycles']:.1f} cycles")
    except InputError as err:
        print(f"CFD {d.name} decay analysis: {err}")
        _early_period(d, t, x)


def _capsize_path(d, t, x) -> None:
    """A release the theory says capsizes has no period: how far, and how fast, it turned."""
    import numpy as np

    angle = np.abs(np.asarray(x, dtype=float) * d.file_scale)
    k = int(np.argmax(angle))
    marks = [(a, float(np.interp(a, np.maximum.accumulate(angle), t)))
             for a in range(10, int(angle[k]) + 1, 10) if a > angle[0]]
    print(f"CFD {d.name}: from {angle[0]:.3g} {d.unit} to {angle[k]:.4g} {d.unit} at "
          f"{t[k]:.3f} s (the record ends at {angle[-1]:.4g} {d.unit}, {t[-1]:.3f} s)"
          + ("; " + ", ".join(f"{a} {d.unit} at {s:.3f} s" for a, s in marks) if marks else ""))


def _early_period(d, t, x) -> None:
    """A record too damped (or too short) for the decay fit: its first extrema, and the period
    they give (twice their mean spacing), which is what a strongly radiating section offers."""
    from floatfoam.analysis.extrema import first_extrema, period_from_extrema

    turns = first_extrema(x, 4)
    if len(turns) < 2:
        return
    period = period_from_extrema(t, turns)
    marks = ", ".join(f"{t[k]:.3f} s ({x[k] * d.file_scale:+.4g} {d.unit})" for k in turns)
    print(f"  its first extrema: {marks}; period from them {period:.4f} s")
