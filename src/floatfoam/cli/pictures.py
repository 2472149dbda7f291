"""``floatfoam pictures RUN``: pictures of the flow of a finished CFD run (pyvista, off-screen).

RUN is a run folder or a CASE with ``--level`` (:func:`floatfoam.cli.common.resolve_run`); the
pictures go to ``<build>/<case>/pictures/<run>/`` (floatfoam.analysis.pictures.run_pictures).
"""

from __future__ import annotations

from floatfoam.cli.common import add_run_argument, resolve_run
from floatfoam.errors import InputError

COLOURS = ("velocity", "vorticity")


def register(sub) -> None:
    p = sub.add_parser("pictures", help="pictures of the flow of a finished CFD run (PNG, GIF)")
    add_run_argument(p)
    p.add_argument("--colour", default="velocity",
                   help=f"colour of the water: {' or '.join(COLOURS)} (default velocity)")
    p.add_argument("--times", type=float, nargs="+", default=None, metavar="T",
                   help="times in s within the written record (default: the first written "
                        "time after the release, the first trough and the last written time)")
    p.set_defaults(func=run)


def run(args) -> int:
    """Exit codes: 0 done, 2 bad input (nothing written), 1 a failure."""
    if args.colour not in COLOURS:
        raise InputError(f"--colour {args.colour!r}: valid are {', '.join(COLOURS)}")
    from floatfoam.analysis.pictures import run_pictures

    pairs = run_pictures(resolve_run(args.run, args.level), colour=args.colour,
                         times=args.times)
    for path, alt in pairs:
        print(f"{path}  ({alt})")
    return 0
