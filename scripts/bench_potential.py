"""Benchmark: wall time of the potential-flow solve (mesh + BEM, no cache) for every case.

Each case runs in a fresh process with the BLAS/OpenMP threads fixed (``--threads``, default
1: on a machine whose cores are busy with CFD, one thread per process is the fastest; at most
2). Printed: the method, the panels, the number of frequencies, the solve time (meshing and
solving, what a user waits for on a cache miss) and the process wall time (with the imports).
A JSON copy stamped with the versions, the date and the git revision goes to
build/bench/potential.json. Target: < 30 s per body on the 2-core reference machine.

    .venv/bin/python scripts/bench_potential.py [--threads 1|2] [CASE ...]
"""

import argparse
import json
import os
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
    parser.add_argument("--threads", type=int, default=1, choices=(1, 2))
    args = parser.parse_args()
    cases = args.cases or [folder.name for folder in list_cases()]
    env = {**os.environ, "OMP_NUM_THREADS": str(args.threads),
           "OPENBLAS_NUM_THREADS": str(args.threads), "MKL_NUM_THREADS": str(args.threads)}
    python = ROOT / ".venv" / "bin" / "python"
    rows = []
    print(f"threads: {args.threads}")
    print(f"{'case':<22} {'method':<40} {'panels':>6} {'freq':>5} {'solve (s)':>10} "
          f"{'process (s)':>12}")
    for name in cases:
        start = time.perf_counter()
        out = subprocess.run([str(python), "-c", CHILD.format(name=name)], env=env, check=True,
                             capture_output=True, text=True, cwd=ROOT)
        wall = time.perf_counter() - start
        row = {"case": name, **json.loads(out.stdout.strip().splitlines()[-1]),
               "process_s": wall}
        rows.append(row)
        print(f"{name:<22} {row['method']:<40} {row['panels']:>6} {row['frequencies']:>5} "
              f"{row['solve_s']:>10.2f} {wall:>12.2f}")
    import capytaine
    import numpy

    stamp = {"date": datetime.now(UTC).isoformat(timespec="seconds"), "git": git_revision(),
             "capytaine": capytaine.__version__, "numpy": numpy.__version__,
             "python": sys.version.split()[0], "threads": args.threads,
             "cpus": os.cpu_count(), "load_average": os.getloadavg(), "results": rows}
    target = build_dir() / "bench" / "potential.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(stamp, indent=2))
    print(f"→ {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
