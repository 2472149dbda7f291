"""``floatfoam run CASE``: the CFD free-decay run of a case (OpenFOAM interFoam + six DoF)."""

from __future__ import annotations

import sys
from pathlib import Path

from floatfoam.cli.common import add_case_arguments, add_level_argument, add_np_argument
from floatfoam.errors import InputError
from floatfoam.interrupts import SignalInterruptError

EXIT_LOCKED = 75  # EX_TEMPFAIL (sysexits.h): another run holds the directory, try later


def register(sub) -> None:
    p = sub.add_parser("run", help="run the CFD free decay of a case (OpenFOAM v1912)")
    add_case_arguments(p)
    add_level_argument(p)
    add_np_argument(p)
    p.add_argument("--hostfile", type=Path, default=None, metavar="FILE",
                   help="Open MPI hostfile for the ranks (default: this machine)")
    p.add_argument("--force", action="store_true",
                   help="move an earlier run of this case and level aside and run anew")
    p.add_argument("--dt-divisor", type=int, default=1, metavar="K",
                   help="divide the level's time-step limits (largest step, Courant numbers) "
                        "by K: a time-step study, run in <level>-dt<K> (default 1)")
    p.add_argument("--morphing", type=float, default=1.0, metavar="F",
                   help="spread the mesh motion wider (F > 1) or narrower: the six-DoF "
                        "morphing distances (run.inner_distance and run.outer_distance, or "
                        "their defaults) × F, for the Laplacian (F > 1 only) its "
                        "diffusivity 1/d instead of 1/d², for the layered motion its rows "
                        "that move with the body over F × its height: a study of the mesh "
                        "motion, run in <level>-morph<F> (default 1)")
    p.set_defaults(func=run)


def run(args) -> int:
    """Exit codes: 0 done, 1 the run failed (log and fatal error in the message), 2 bad input,
    75 another run holds the run directory, 128 + signal when interrupted (130 SIGINT,
    143 SIGTERM, 129 SIGHUP)."""
    from floatfoam.case import load_case
    from floatfoam.foam.driver import run_plan
    from floatfoam.foam.runlock import RunLockedError
    from floatfoam.foam.runner import RunError
    from floatfoam.plan.runplan import resolve

    try:
        case = load_case(args.case, args.overrides)
        plan = resolve(case, args.level, args.np, hostfile=args.hostfile,
                       divisor=args.dt_divisor, morphing=args.morphing)
        result = run_plan(plan, args.force)
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
    print_summary(case, result, plan.equilibrium)
    return 0


def _say(line: str) -> None:
    """One line on stderr; a closed terminal (SIGHUP) must not turn it into a traceback."""
    try:
        print(line, file=sys.stderr, flush=True)
    except OSError:
        pass


def print_summary(case, result, eq) -> None:
    """For each DoF the release displaces, its turning points (:func:`turning_rows`), then its
    period and damping ratio beside the theory's period (a DoF the release leaves alone is not
    analysed: its record is noise)."""
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
    for d in released(case.release) or released({"heave": 1.0}):
        # heave's column is G's height in the tank (z = 0 the still water's level), not its
        # distance from equilibrium: named as such
        quantity = f"z of G ({d.unit})" if d.name == "heave" else f"{d.name} ({d.unit})"
        print("\n".join(turning_rows(motion["time"], motion[d.column], quantity)))
        _dof_summary(d, motion, theory)


# A turning point counts once the record has turned back from it by more than 1 % of its range:
# the six-DoF state's jitter from step to step and a record's settled end make none, while a
# lightly damped decay (ζ ≈ 0.03) keeps swings over 1 % for some 50 turning points, more than
# the table shows.
TURN_SWING = 0.01  # of the record's range (max − min)
TABLE_TURNS = 13  # turning points shown: with the first and last sample, 15 rows


def turning_points(t, x, *, swing: float = TURN_SWING) -> list[tuple[float, float]]:
    """The turning points (time, value) of a record: its maxima and minima, in order, each the
    vertex of the parabola through the extreme sample and its two neighbours (as
    :func:`floatfoam.analysis.extrema.crossing_reduction` refines its extrema).

    An extreme sample counts once the record has turned back from it by more than ``swing`` ×
    the record's range; the first sample (the release) is not one.
    """
    import numpy as np

    from floatfoam.analysis.extrema import parabola_peak

    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    least = swing * float(np.ptp(x)) if x.size else 0.0
    turns, k, heading = [], 0, 0.0  # heading +1: rising to a maximum, −1: falling to a minimum
    for i in range(1, x.size):
        if heading == 0.0:
            if abs(x[i] - x[0]) > least:
                heading, k = float(np.sign(x[i] - x[0])), i
        elif heading * (x[i] - x[k]) > 0:
            k = i
        elif heading * (x[k] - x[i]) > least:
            turns.append(k)
            heading, k = -heading, i
    return [parabola_peak(t, x, k) for k in turns]


def turning_rows(t, x, quantity: str) -> list[str]:
    """The run's closing table of one DoF: its first sample, its first :data:`TABLE_TURNS`
    turning points (:func:`turning_points`) and its last sample; ``quantity`` heads the value
    column (e.g. "roll (deg)", in the unit of ``x``)."""
    turns = turning_points(t, x)
    rows = [(t[0], x[0], "  first sample"), *((a, b, "") for a, b in turns[:TABLE_TURNS]),
            (t[-1], x[-1], "  last sample")]
    lines = [f"turning points of {quantity}, each the vertex of the parabola through three "
             "samples:", f"{'time (s)':>9} {quantity:>14}"]
    lines += [f"{a:>9.4f} {b:>14.6g}{note}" for a, b, note in rows]
    if len(turns) > TABLE_TURNS:
        lines.insert(-1, f"{'…':>9} {len(turns) - TABLE_TURNS} more turning points, the last "
                         f"at {turns[-1][0]:.4f} s")
    return lines


def _still_water(case, run_dir: Path) -> None:
    """The currents the scheme drives around a held body (analysis.stillwater): one line, and
    every written time in still_water.json of the run directory."""
    from floatfoam.analysis import stillwater
    from floatfoam.tank import tank

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
