"""Benchmark: the CFD cases, serial and on 2 MPI ranks.

For each case and rank count, a coarse run of ``--end-time`` simulated seconds (default 1 s,
0.5 s for the 3D case: enough for the time step to settle; a case's whole record costs about
its end time × the wall time per simulated second): cells, mesh kind, time steps, wall time
(render, mesh and solver included) and wall time per simulated second. Prints a table and
writes build/bench/cfd.json. Each run goes to build/bench/ and is moved aside when rerun.

Accuracy per second: each run's record is analysed in its released DoF (T_d and ζ of what it
ran, HEAD's analysis for every run), and its T_d set against the case's converged value (the
grid study's Richardson extrapolation, from ``floatfoam validate``'s study of today's settings
when one is in the build) and its measured one (the case's [reference]). With ``--baseline
REV`` each case is also run, just before, by the code and cases of git revision REV (the
previous defaults: ``git archive`` into <build>/bench/baseline/<sha>/, sharing this tree's
solver), and the rows give the two side by side with the ratio of their walls: the machine's
speed varies from one day to the next, the ratio of two runs made back to back much less.

    .venv/bin/python scripts/bench_cfd.py --cases A B [--levels coarse] [--ranks 1 2]
                                          [--end-time 1.0 | --full] [--baseline REV]
"""

import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import time
from pathlib import Path

from floatfoam.analysis.compare import analyse_run, excited_dofs
from floatfoam.analysis.decay import decay_dict
from floatfoam.analysis.uncertainty import current_study
from floatfoam.case import load_case
from floatfoam.errors import InputError
from floatfoam.foam.driver import run_case
from floatfoam.layout import PROJECT_BUILD, ROOT, build_dir, run_dir
from floatfoam.plan.release import end_time_of

# the 3D cases: ~0.3 s of wall per 1.1 ms step on 2 ranks (ellipsoid_roll, half domain), ~0.6 s
# per step (stl_pontoon, 155,916 tetrahedra in the whole tank); superellipsoid_buoy as the pontoon
SHORTER = {"ellipsoid_roll": 0.5, "ellipsoid_pitch": 0.5, "ellipsoid": 0.5,
           "ellipsoid_printed_verdict": 0.45, "stl_pontoon": 0.2, "superellipsoid_buoy": 0.2}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", required=True,
                        help="the cases (make bench-cfd: the Makefile's CFD_CASES)")
    parser.add_argument("--levels", nargs="+", default=["coarse"])
    parser.add_argument("--ranks", nargs="+", type=int, default=[1, 2])
    parser.add_argument("--end-time", type=float, default=1.0)
    parser.add_argument("--full", action="store_true", help="each case's whole record")
    parser.add_argument("--baseline", metavar="REV",
                        help="also run each case as git revision REV did, just before")
    args = parser.parse_args()
    try:
        baseline = baseline_tree(args.baseline) if args.baseline else None
    except InputError as error:
        print(f"bench_cfd: error: {error}", file=sys.stderr)
        return 2
    rows = []
    for name in args.cases:
        for level in args.levels:
            for ranks in args.ranks:
                base = load_case(name)
                record = SHORTER.get(name, 1.0) * args.end_time
                end = end_time_of(base) if args.full else min(record, end_time_of(base))
                case = load_case(name, [f"run.end_time={end}"])
                row = {"case": name, "level": level, "ranks": ranks, "simulated_s": end,
                       "record_s": end_time_of(base)}
                if baseline is not None:
                    row["baseline"] = run_baseline(baseline, case, level, ranks, end)
                build = build_dir() / "bench" / f"np{ranks}"
                t0 = time.perf_counter()
                result = run_case(case, level, ranks, force=True, build_dir=build)
                wall = time.perf_counter() - t0
                row.update({"mesh": result.info.mesh, "cells": result.info.cells,
                            "steps": steps_of(result.run_dir), "wall_s": round(wall, 1),
                            "wall_per_simulated_s": round(wall / end, 1),
                            **accuracy(case, result.run_dir)})
                rows.append(row)
                print(_line(row), flush=True)
    sha = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                         text=True).stdout.strip()
    out = build_dir() / "bench" / "cfd.json"
    out.write_text(json.dumps({"git": sha, "baseline": baseline.name if baseline else None,
                               "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                               "machine": platform.machine(), "rows": rows}, indent=2))
    print(HEADER)
    for r in rows:
        print(_line(r))
    if baseline is not None:
        print(f"\nagainst {baseline.name} ({args.baseline}), run just before each row's:")
        print(BASELINE_HEADER)
        for r in rows:
            print(_baseline_line(r))
    print(f"written: {out}")
    return 0


def steps_of(run: Path) -> int:
    """The solver's time steps in a run folder's log."""
    log = (run / "log.interFoam").read_text()
    return sum(1 for line in log.splitlines() if line.startswith("Time = "))


def accuracy(case, run: Path) -> dict:
    """T_d and ζ of a run's record in the case's released DoF, and T_d's relative error
    against the case's converged value (``converged_period``: the grid study's extrapolation, or
    None without a study of today's settings) and its measured one (``reference_period``)."""
    dof = excited_dofs(case)[0]
    try:
        _, _, result = analyse_run(run / "motion.csv", dof)
    except (InputError, ValueError) as error:  # a record too short for a decay fit
        return {"dof": dof, "period": None, "damping_ratio": None, "converged_period": None,
                "reference_period": None, "note": str(error)}
    fitted = decay_dict(result)
    out = {"dof": dof, "period": fitted["period_mean"], "damping_ratio": fitted["damping_ratio"]}
    study, _ = current_study(case)
    grid = (study or {}).get("dofs", {}).get(dof, {}).get("quantities", {}).get("period", {})
    converged = grid.get("grid", {}).get("extrapolated")
    measured = (case.reference or {}).get(f"{dof}_period", {})
    out["converged_period"] = converged
    out["reference_period"] = measured.get("value") if isinstance(measured, dict) else None
    return out


def baseline_tree(rev: str) -> Path:
    """The files of git revision ``rev`` in <build>/bench/baseline/<sha>/ (``git archive``,
    made once), with this tree's solver: its floatfoam runs the cases as that revision did. An
    unknown revision is an InputError."""
    found = subprocess.run(["git", "rev-parse", "--short", "--verify", "--quiet",
                            f"{rev}^{{commit}}"], cwd=ROOT, capture_output=True, text=True)
    if found.returncode != 0:
        raise InputError(f"--baseline {rev!r}: valid is a git revision of this repository "
                         "(a commit, tag or branch; `git log --oneline` lists them)")
    tree = build_dir() / "bench" / "baseline" / found.stdout.strip()
    if not (tree / ".complete").is_file():  # marked when whole: a copy cut short starts again
        part = tree.with_name(tree.name + ".part")
        shutil.rmtree(part, ignore_errors=True)
        part.mkdir(parents=True)
        archive = subprocess.Popen(["git", "archive", "--format=tar", found.stdout.strip()],
                                   cwd=ROOT, stdout=subprocess.PIPE)
        subprocess.run(["tar", "-x", "-C", str(part)], stdin=archive.stdout, check=True)
        if archive.wait() != 0:
            raise RuntimeError(f"git archive {rev} failed")
        (part / "build").mkdir(exist_ok=True)
        (part / "build" / "solver").symlink_to(PROJECT_BUILD / "solver")
        (part / ".complete").touch()
        shutil.rmtree(tree, ignore_errors=True)
        part.rename(tree)
    return tree


def run_baseline(tree: Path, case, level: str, ranks: int, end: float) -> dict:
    """One run of ``case`` by the floatfoam of ``tree`` (its own cases and shared files) in
    build/bench/baseline-np<ranks>/: wall, steps and :func:`accuracy` (HEAD's analysis)."""
    build = build_dir() / "bench" / f"baseline-np{ranks}"
    env = {**os.environ, "PYTHONPATH": str(tree / "src"), "FLOATFOAM_BUILD": str(build)}
    command = [sys.executable, "-c", "import sys; from floatfoam.cli import main; "
               "sys.exit(main())", "run", case.name, "--level", level, "--np", str(ranks),
               "--force", "--set", f"run.end_time={end}"]
    t0 = time.perf_counter()
    subprocess.run(command, cwd=tree, env=env, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    run = run_dir(case.name, level, build)
    return {"wall_s": round(wall, 1), "steps": steps_of(run), **accuracy(case, run)}


HEADER = (f"{'case':<26} {'level':<7} {'ranks':>5} {'mesh':<8} {'cells':>7} {'steps':>6} "
          f"{'wall (s)':>9} {'wall/sim s':>10} {'record (s)':>10} {'T_d (s)':>8} {'ζ':>7} "
          f"{'vs conv.':>8} {'vs meas.':>8}")
BASELINE_HEADER = (f"{'case':<26} {'ranks':>5} {'wall base':>9} {'wall now':>9} {'ratio':>6} "
                   f"{'T_d base':>9} {'T_d now':>9} {'ζ base':>8} {'ζ now':>8} "
                   f"{'steps base':>10} {'now':>6}")


def _pct(value, against) -> str:
    return f"{100 * (value - against) / against:+.2f}%" if value and against else "—"


def _num(value, digits: int) -> str:
    return f"{value:.{digits}f}" if value is not None else "—"


def _line(r: dict) -> str:
    return (f"{r['case']:<26} {r['level']:<7} {r['ranks']:>5} {r['mesh'] or '':<8} "
            f"{r['cells']:>7} {r['steps']:>6} {r['wall_s']:>9.1f} "
            f"{r['wall_per_simulated_s']:>10.1f} {r['record_s']:>10.3g} "
            f"{_num(r['period'], 4):>8} {_num(r['damping_ratio'], 4):>7} "
            f"{_pct(r['period'], r['converged_period']):>8} "
            f"{_pct(r['period'], r['reference_period']):>8}")


def _baseline_line(r: dict) -> str:
    b = r["baseline"]
    return (f"{r['case']:<26} {r['ranks']:>5} {b['wall_s']:>9.1f} {r['wall_s']:>9.1f} "
            f"{r['wall_s'] / b['wall_s']:>6.2f} {_num(b['period'], 4):>9} "
            f"{_num(r['period'], 4):>9} {_num(b['damping_ratio'], 5):>8} "
            f"{_num(r['damping_ratio'], 5):>8} {b['steps']:>10} {r['steps']:>6}")


if __name__ == "__main__":
    sys.exit(main())
