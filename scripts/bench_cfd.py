"""Benchmark: the cylinder_heave CFD run, serial and on 2 MPI ranks.

Prints and writes build/bench/cfd.json: cells, time steps, wall time, wall time per simulated
second, for each (level, ranks). Each run goes to build/bench/ and is moved aside when rerun.

    .venv/bin/python scripts/bench_cfd.py [--levels coarse] [--ranks 1 2] [--end-time 3.2]
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


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", nargs="+", default=["coarse"])
    parser.add_argument("--ranks", nargs="+", type=int, default=[1, 2])
    parser.add_argument("--end-time", type=float, default=3.2)
    args = parser.parse_args()
    rows = []
    for level in args.levels:
        for ranks in args.ranks:
            case = load_case("cylinder_heave", [f"run.end_time={args.end_time}"])
            build = build_dir() / "bench" / f"np{ranks}"
            t0 = time.perf_counter()
            result = run_case(case, level, ranks, force=True, build_dir=build)
            wall = time.perf_counter() - t0
            log = (result.run_dir / "log.interFoam").read_text()
            steps = sum(1 for line in log.splitlines() if line.startswith("Time = "))
            rows.append({"level": level, "ranks": ranks, "cells": result.info["cells"],
                         "steps": steps, "simulated_s": args.end_time, "wall_s": round(wall, 1),
                         "wall_per_simulated_s": round(wall / args.end_time, 1)})
    sha = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                         text=True).stdout.strip()
    out = build_dir() / "bench" / "cfd.json"
    out.write_text(json.dumps({"git": sha, "date": time.strftime("%Y-%m-%d %H:%M UTC",
                                                                   time.gmtime()),
                               "machine": platform.machine(), "rows": rows}, indent=2))
    print(f"{'level':<8} {'ranks':>5} {'cells':>7} {'steps':>6} {'wall (s)':>9} "
          f"{'wall/sim s':>10}")
    for r in rows:
        print(f"{r['level']:<8} {r['ranks']:>5} {r['cells']:>7} {r['steps']:>6} "
              f"{r['wall_s']:>9.1f} {r['wall_per_simulated_s']:>10.1f}")
    print(f"written: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
