"""Benchmark: wall time of `floatfoam theory CASE --json` for every case in cases/.

Each case is run as a fresh process (as a user would, imports included), 5 times after one
warm-up run; the best, the median and the worst are printed. Target: a median ≤ 0.6 s for every
closed-form case on the 2-core reference machine.
"""

import statistics
import subprocess
import sys
import time

from floatfoam.layout import ROOT, list_cases

REPEAT = 5


def main() -> int:
    exe = ROOT / ".venv" / "bin" / "floatfoam"
    cases = [folder.name for folder in list_cases()]
    print(f"{'case':<24} {'best (s)':>9} {'median (s)':>11} {'worst (s)':>10}")
    for name in cases:
        times = []
        for run in range(REPEAT + 1):  # the first run warms the file cache and is not counted
            t0 = time.perf_counter()
            subprocess.run([str(exe), "theory", name, "--json"], check=True,
                           stdout=subprocess.DEVNULL)
            if run:
                times.append(time.perf_counter() - t0)
        print(f"{name:<24} {min(times):>9.3f} {statistics.median(times):>11.3f} "
              f"{max(times):>10.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
