"""How many MPI ranks a run takes: the default when --np is not given, the check of a given
--np and --hostfile, the cores other runs already use, and the cores runs share out among
their solvers (:envvar:`FLOATFOAM_SOLVER_LOCK`). Light on purpose: every command's parser asks
for the default."""

from __future__ import annotations

import contextlib
import fcntl
import os
import sys
import time
from pathlib import Path

from floatfoam.cores import running_solver_ranks
from floatfoam.errors import InputError

#: the most ranks a run takes by default: every measurement in this project (the README's and
#: docs/' tables) was made on 2 ranks, where the coarse 2D meshes of 4–13 k cells run 1.1–1.7 ×
#: faster than on one and the 3D ones 1.2–3.8 ×; more is a choice to make with --np, measured
#: first (`make bench-cfd`). One default on every machine of 2 cores or more also keeps a run
#: resumable there: its stamp holds its --np.
DEFAULT_RANKS_CAP = 2


def default_ranks() -> int:
    """The ranks of a run when --np is not given (``run``, ``validate``, ``batch`` and make):
    the cores this process may use (a taskset or a container's CPU set counts), at most
    :data:`DEFAULT_RANKS_CAP`."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # no sched_getaffinity (not Linux)
        cores = os.cpu_count() or 1
    return max(1, min(cores, DEFAULT_RANKS_CAP))


def check_ranks(np_: int, hostfile: Path | None) -> None:
    """--np and --hostfile: a whole number ≥ 1, an existing file; more ranks than this
    machine's cores (without a hostfile) is allowed but said."""
    if isinstance(np_, bool) or not isinstance(np_, int) or np_ < 1:
        raise InputError(f"--np {np_}: valid is a whole number ≥ 1")
    if hostfile is not None:
        if not Path(hostfile).is_file():
            raise InputError(f"--hostfile {hostfile}: no such file; valid is an Open MPI "
                             "hostfile (one host per line, e.g. 'node1 slots=16')")
        return
    cores = os.cpu_count() or 1
    if np_ > cores:
        # measured here: 3 ranks on 2 cores took 458 s for what 2 ranks ran in 4 s (Open
        # MPI's ranks busy-wait for each other when they share a core)
        print(f"warning: --np {np_} is more than the {cores} cores of this machine: the ranks "
              f"will share them and run far slower than --np {cores}; give --hostfile to use "
              "other machines", file=sys.stderr)


def check_free_cores(np_: int, hostfile: Path | None, *, label: str = "",
                     busy: int | None = None) -> bool:
    """Before the solver starts: say in one line when its ``np_`` ranks and the solver ranks
    already running (``busy``, default :func:`running_solver_ranks`) are more than this
    machine's cores. Returns whether they are (a run on other machines, with a hostfile, is
    not counted here)."""
    if hostfile is not None:
        return False
    busy = running_solver_ranks() if busy is None else busy
    cores = os.cpu_count() or 1
    if busy == 0 or busy + np_ <= cores:
        return False
    share = (busy + np_) / cores
    where = f"[{label}] " if label else ""
    print(f"{where}warning: {busy} solver rank(s) of other runs already use this machine's "
          f"{cores} cores: this run's {np_} rank(s) will share them, each about {share:.2g} × "
          "slower than alone (the ranks yield a core they wait on: Open MPI's "
          "mpi_yield_when_idle)", file=sys.stderr)
    return True


#: the environment variable naming a lock file: runs that name the same one share this machine's
#: cores among their solvers (each takes as many as it has ranks, and waits while too few are
#: free), instead of oversubscribing them
SOLVER_LOCK = "FLOATFOAM_SOLVER_LOCK"

#: how often a run waiting for cores looks again, seconds
_POLL = 0.2


def solver_lock() -> Path | None:
    """The lock file :data:`SOLVER_LOCK` names, checked (InputError: a file that can be made
    in an existing folder); None when it is unset or empty."""
    value = os.environ.get(SOLVER_LOCK, "")
    if not value:
        return None
    path = Path(value)
    if path.is_dir() or not path.parent.is_dir():
        raise InputError(f"{SOLVER_LOCK}={value}: valid is a file in an existing folder (the "
                         "lock by which runs naming it share the cores)")
    return path


def core_files(path: Path) -> list[Path]:
    """The lock files of a :data:`SOLVER_LOCK` ``path``, one per core of this machine: the
    file itself for the first, ``FILE.2`` … ``FILE.<cores>`` beside it for the others."""
    cores = os.cpu_count() or 1
    return [path] + [path.with_name(f"{path.name}.{k}") for k in range(2, cores + 1)]


@contextlib.contextmanager
def hold_cores(path: Path, ranks: int, label: str = ""):
    """Hold ``ranks`` of the core files of ``path`` (all of them for as many ranks as cores or
    more): a run that finds too few free says so in one line and waits (an interrupt stops
    the wait). One run at a time gathers its cores, holding ``FILE.queue`` until it has them
    all, so a run of two ranks is not kept waiting by runs of one that follow each other.
    Yields the held files' descriptors."""
    slots = core_files(path)
    need = min(max(1, ranks), len(slots))
    where = f"[{label}] " if label else ""
    said = False

    def wait_message():
        nonlocal said
        if not said:
            print(f"{where}waiting for the cores: another run's solver holds {path} "
                  f"({SOLVER_LOCK})", file=sys.stderr, flush=True)
            said = True

    held = {}  # core index: its open, locked file
    try:
        with open(path.with_name(f"{path.name}.queue"), "a") as queue:
            start = time.monotonic()
            while True:
                try:
                    fcntl.flock(queue, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except BlockingIOError:
                    if time.monotonic() - start > 1.0:  # not another run taking its cores
                        wait_message()
                    time.sleep(_POLL)
            while True:
                for k, slot in enumerate(slots):
                    if len(held) == need or k in held:
                        continue
                    handle = open(slot, "a")
                    try:
                        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    except BlockingIOError:  # another run's core
                        handle.close()
                        continue
                    except BaseException:  # an interrupt: the file is not left open
                        handle.close()
                        raise
                    held[k] = handle
                if len(held) == need:
                    break
                wait_message()
                time.sleep(_POLL)
        yield tuple(handle.fileno() for handle in held.values())
    finally:
        for handle in held.values():  # each lock goes with its file's closing
            handle.close()


@contextlib.contextmanager
def solver_turn(label: str = "", ranks: int = 1, hostfile: Path | None = None):
    """Hold ``ranks`` cores of the :data:`SOLVER_LOCK` file's while the solver runs
    (:func:`hold_cores`; all of them for a run with a ``hostfile``, whose ranks may run here
    too). Yields the held files' descriptors (for the solver's watchdog, which
    holds the cores until a killed driver's solver is gone: :mod:`floatfoam.foam.processes`);
    none without the variable, when runs do not wait for each other."""
    path = solver_lock()
    if path is None:
        yield ()
        return
    with hold_cores(path, ranks if hostfile is None else os.cpu_count() or 1, label) as fds:
        yield fds
