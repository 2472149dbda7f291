"""This machine's cores and the solver ranks running on them, for every layer: the run's
warning when its ranks would share the cores (:mod:`floatfoam.foam.ranks`), and the threads a
computation in a child process takes beside running solvers
(:mod:`floatfoam.potential.bounded`). Standard library only."""

from __future__ import annotations

import os
from pathlib import Path

SOLVER_NAME = "interFoam"  # the process name of every rank of a run (floatfoam's build's too)

#: the environment variables that set a process's compute threads: OpenMP's (Capytaine's
#: Fortran core) and the BLAS libraries' (numpy's OpenBLAS, or MKL)
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def running_solver_ranks(name: str = SOLVER_NAME) -> int:
    """The solver processes running on this machine now (other runs' ranks), from /proc."""
    count = 0
    for comm in Path("/proc").glob("[0-9]*/comm"):
        try:
            count += comm.read_text().strip() == name
        except OSError:  # the process ended meanwhile
            continue
    return count


def threads_beside_solvers(busy: int | None = None) -> dict[str, str]:
    """The thread counts for a computation started now (:data:`THREAD_VARIABLES`): none to
    set when any of them is set already or no solver runs (``busy``, default
    :func:`running_solver_ranks`); else the cores the solver ranks leave free, at least one.
    OpenMP's and OpenBLAS's threads spin on a core they wait for: measured on this 2-core
    machine beside a 2-rank run of `cylinder_heave`, the BEM of test_potential.py's
    `test_many_panels_and_short_waves_stay_finite` took 68 s on the default threads and 4.6 s
    on one."""
    if any(os.environ.get(name) for name in THREAD_VARIABLES):
        return {}
    busy = running_solver_ranks() if busy is None else busy
    if busy == 0:
        return {}
    threads = str(max(1, (os.cpu_count() or 1) - busy))
    return dict.fromkeys(THREAD_VARIABLES, threads)
