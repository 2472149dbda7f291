"""Benchmark: wall time of `floatfoam theory CASE --json` for every case in cases/.

Each case is run as a fresh process (as a user would), 3 times; the best and the median are
printed. Target: < 1 s per case on the 2-core reference machine.
"""

import statistics
import subprocess
import sys
import time

from floatfoam.layout import ROOT, list_cases

REPEAT = 3


def main() -> int:
    exe = ROOT / ".venv" / "bin" / "floatfoam"
    cases = [folder.name for folder in list_cases()]
    print(f"{'case':<24} {'best (s)':>9} {'median (s)':>11}")
    for name in cases:
        times = []
        for _ in range(REPEAT):
            t0 = time.perf_counter()
            subprocess.run([str(exe), "theory", name, "--json"], check=True,
                           stdout=subprocess.DEVNULL)
            times.append(time.perf_counter() - t0)
        print(f"{name:<24} {min(times):>9.3f} {statistics.median(times):>11.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
