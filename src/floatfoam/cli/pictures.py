"""``floatfoam pictures CASE``: pictures of the flow of a finished CFD run (pyvista, off-screen).

They go to ``<build>/<case>/pictures/<level>/`` (floatfoam.analysis.pictures.case_pictures).
"""

from __future__ import annotations

from floatfoam.cli.common import add_case_arguments, add_level_argument
from floatfoam.errors import InputError
from floatfoam.layout import LEVELS

COLOURS = ("velocity", "vorticity")


def register(sub) -> None:
    p = sub.add_parser("pictures", help="pictures of the flow of a finished CFD run (PNG, GIF)")
    add_case_arguments(p)
    add_level_argument(p)
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
    if args.level not in LEVELS:
        raise InputError(f"--level {args.level!r}: valid levels are {', '.join(LEVELS)}")
    if args.overrides:  # the pictures show the run on disk, made with the case it was run with
        raise InputError(f"--set {args.overrides[0]}: valid is no --set (the pictures show the "
                         "run on disk; rerun floatfoam run to change the case)")
    from floatfoam.analysis.pictures import case_pictures
    from floatfoam.case import load_case

    case = load_case(args.case)
    pairs = case_pictures(case.name, args.level, colour=args.colour, times=args.times)
    for path, alt in pairs:
        print(f"{path}  ({alt})")
    return 0
