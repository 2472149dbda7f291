"""Benchmark: runs that share the cores. One case's coarse run of ``--end-time`` s, alone and
then two of it at once (each in a build folder of its own), for each rank count: the solver's
clock time (log.interFoam's last ClockTime) alone and at once, and their ratio (a fair share
of 2 cores: 2 × for two 2-rank runs, 1 × for two 1-rank runs). Prints a table and writes
build/bench/sharing.json.

    .venv/bin/python scripts/bench_sharing.py [--case cylinder_heave] [--ranks 1 2]
                                               [--end-time 1.0]
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

from floatfoam.layout import ROOT, build_dir

CLOCK = re.compile(r"ClockTime = ([0-9.eE+-]+) s")


def solver_clock(run_dir) -> float:
    """The solver's clock time: the last ClockTime of its log."""
    return float(CLOCK.findall((run_dir / "log.interFoam").read_text())[-1])


def start(case: str, ranks: int, end: float, folder):
    """`floatfoam run` of the case in a build folder of its own (started, not waited for)."""
    shutil.rmtree(folder, ignore_errors=True)
    env = {**os.environ, "FLOATFOAM_BUILD": str(folder)}
    return subprocess.Popen([str(ROOT / ".venv" / "bin" / "floatfoam"), "run", case, "--np",
                             str(ranks), "--set", f"run.end_time={end}"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


def finish(process, case: str, folder) -> float:
    _, err = process.communicate()
    if process.returncode:
        sys.exit(f"bench_sharing: the run in {folder} failed: {err.strip().splitlines()[-1:]}")
    return solver_clock(folder / case / "coarse")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="cylinder_heave")
    parser.add_argument("--ranks", nargs="+", type=int, default=[1, 2])
    parser.add_argument("--end-time", type=float, default=1.0)
    args = parser.parse_args()
    root = build_dir() / "bench" / "sharing"
    rows = []
    for ranks in args.ranks:
        alone = finish(start(args.case, ranks, args.end_time, root / "alone"), args.case,
                       root / "alone")
        pair = [start(args.case, ranks, args.end_time, root / f"pair{k}") for k in (0, 1)]
        together = [finish(p, args.case, root / f"pair{k}") for k, p in enumerate(pair)]
        rows.append({"case": args.case, "ranks": ranks, "alone_s": alone,
                     "together_s": together,
                     "ratio": [round(t / alone, 2) for t in together]})
        print(f"{args.case} {ranks} rank(s): alone {alone:.0f} s; two at once "
              f"{together[0]:.0f} s and {together[1]:.0f} s ({rows[-1]['ratio'][0]} ×, "
              f"{rows[-1]['ratio'][1]} ×)", flush=True)
    sha = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                         text=True).stdout.strip()
    out = build_dir() / "bench" / "sharing.json"
    out.write_text(json.dumps({"git": sha, "date": time.strftime("%Y-%m-%d %H:%M UTC",
                                                                   time.gmtime()),
                               "cores": os.cpu_count(), "rows": rows}, indent=2))
    print(f"written: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
