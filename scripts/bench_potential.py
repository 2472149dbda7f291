"""Benchmark: wall time of the potential-flow solve (mesh + BEM, no cache) for every case.

Each case runs ``--repeat`` times (default 3), each in a fresh process with the BLAS/OpenMP
threads fixed (``--threads``, default 2: the reference machine's cores; 1 when they are busy
with CFD). Printed per case: the method, the panels, the number of frequencies, the median
(min–max) solve time (meshing and solving, what a user waits for on a cache miss), the median
process wall time (with the imports) and the target it is held to (3D ≤ 30 s, a section
≤ 2 s, issue 13). A JSON copy stamped with the versions, the date and the git revision goes to
build/bench/potential.json.

    .venv/bin/python scripts/bench_potential.py [--threads 1|2] [--repeat N] [CASE ...]
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from datetime import UTC, datetime

from floatfoam.layout import ROOT, build_dir, list_cases

CHILD = """
import json, time
from floatfoam.case import load_case
from floatfoam.potential.radiation import radiation_coefficients
from floatfoam.hydrostatics.theory import equilibrium
case = load_case({name!r})
eq = equilibrium(case)
start = time.perf_counter()
coef = radiation_coefficients(case, eq, cache=False)
print(json.dumps({{"method": coef.method, "panels": coef.panels,
                   "frequencies": len(coef.omega) + 1,
                   "solve_s": time.perf_counter() - start}}))
"""


def git_revision() -> str:
    try:
        return subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", help="case names (default: all in cases/)")
    parser.add_argument("--threads", type=int, default=2, choices=(1, 2))
    parser.add_argument("--repeat", type=int, default=3, choices=range(1, 11), metavar="N")
    args = parser.parse_args()
    cases = args.cases or [folder.name for folder in list_cases()]
    env = {**os.environ, "OMP_NUM_THREADS": str(args.threads),
           "OPENBLAS_NUM_THREADS": str(args.threads), "MKL_NUM_THREADS": str(args.threads)}
    python = ROOT / ".venv" / "bin" / "python"
    rows = []
    print(f"threads: {args.threads}")
    print(f"{'case':<26} {'method':<40} {'panels':>6} {'freq':>5} "
          f"{'solve median (min–max) s':>25} {'process s':>10}  target")
    for name in cases:
        runs = []
        for _ in range(args.repeat):
            start = time.perf_counter()
            out = subprocess.run([str(python), "-c", CHILD.format(name=name)], env=env,
                                 check=True, capture_output=True, text=True, cwd=ROOT)
            runs.append({**json.loads(out.stdout.strip().splitlines()[-1]),
                         "process_s": time.perf_counter() - start})
        solve = [r["solve_s"] for r in runs]
        row = {"case": name, **{k: runs[0][k] for k in ("method", "panels", "frequencies")},
               "solve_s": solve, "solve_median_s": statistics.median(solve),
               "process_median_s": statistics.median(r["process_s"] for r in runs)}
        target = 2.0 if row["method"] == "panel-2d" else 30.0
        row["target_s"] = target
        rows.append(row)
        verdict = "ok" if row["solve_median_s"] <= target else "OVER"
        print(f"{name:<26} {row['method'][:40]:<40} {row['panels']:>6} {row['frequencies']:>5} "
              f"{row['solve_median_s']:>9.2f} ({min(solve):.2f}–{max(solve):.2f}){'':>4} "
              f"{row['process_median_s']:>10.2f}  ≤ {target:g} s {verdict}")
    import capytaine
    import numpy

    stamp = {"date": datetime.now(UTC).isoformat(timespec="seconds"), "git": git_revision(),
             "capytaine": capytaine.__version__, "numpy": numpy.__version__,
             "python": sys.version.split()[0], "threads": args.threads, "repeat": args.repeat,
             "cpus": os.cpu_count(), "load_average": os.getloadavg(), "results": rows}
    target = build_dir() / "bench" / "potential.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(stamp, indent=2))
    print(f"→ {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
