"""Benchmark: the CFD cases, serial and on 2 MPI ranks.

For each case and rank count, a coarse run of ``--end-time`` simulated seconds (default 1 s,
0.5 s for the 3D case: enough for the time step to settle; a case's whole record costs about
its end time × the wall time per simulated second): cells, mesh kind, time steps, wall time
(render, mesh and solver included) and wall time per simulated second. Prints a table and
writes build/bench/cfd.json. Each run goes to build/bench/ and is moved aside when rerun.

    .venv/bin/python scripts/bench_cfd.py --cases A B [--levels coarse] [--ranks 1 2]
                                          [--end-time 1.0 | --full]
"""

import argparse
import json
import platform
import subprocess
import sys
import time

from floatfoam.case import load_case
from floatfoam.foam.driver import run_case
from floatfoam.layout import ROOT, build_dir
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
    args = parser.parse_args()
    rows = []
    for name in args.cases:
        for level in args.levels:
            for ranks in args.ranks:
                base = load_case(name)
                record = SHORTER.get(name, 1.0) * args.end_time
                end = end_time_of(base) if args.full else min(record, end_time_of(base))
                case = load_case(name, [f"run.end_time={end}"])
                build = build_dir() / "bench" / f"np{ranks}"
                t0 = time.perf_counter()
                result = run_case(case, level, ranks, force=True, build_dir=build)
                wall = time.perf_counter() - t0
                log = (result.run_dir / "log.interFoam").read_text()
                steps = sum(1 for line in log.splitlines() if line.startswith("Time = "))
                rows.append({"case": name, "level": level, "ranks": ranks,
                             "mesh": result.info.mesh, "cells": result.info.cells,
                             "steps": steps, "simulated_s": end, "wall_s": round(wall, 1),
                             "wall_per_simulated_s": round(wall / end, 1),
                             "record_s": end_time_of(base)})
                print(_line(rows[-1]), flush=True)
    sha = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                         text=True).stdout.strip()
    out = build_dir() / "bench" / "cfd.json"
    out.write_text(json.dumps({"git": sha, "date": time.strftime("%Y-%m-%d %H:%M UTC",
                                                                   time.gmtime()),
                               "machine": platform.machine(), "rows": rows}, indent=2))
    print(f"{'case':<26} {'level':<7} {'ranks':>5} {'mesh':<8} {'cells':>7} {'steps':>6} "
          f"{'wall (s)':>9} {'wall/sim s':>10} {'record (s)':>10}")
    for r in rows:
        print(_line(r))
    print(f"written: {out}")
    return 0


def _line(r: dict) -> str:
    return (f"{r['case']:<26} {r['level']:<7} {r['ranks']:>5} {r['mesh'] or '':<8} "
            f"{r['cells']:>7} {r['steps']:>6} {r['wall_s']:>9.1f} "
            f"{r['wall_per_simulated_s']:>10.1f} {r['record_s']:>10.3g}")


if __name__ == "__main__":
    sys.exit(main())
