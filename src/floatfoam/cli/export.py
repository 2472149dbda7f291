"""``floatfoam export RUN --vtk``: a finished run's fields as VTK files, for a viewer without
OpenFOAM's reader (:func:`floatfoam.foam.paraview.export_vtk`). RUN is a run folder or a CASE
with ``--level`` (:func:`floatfoam.cli.common.resolve_run`)."""

from __future__ import annotations

import sys


def register(sub) -> None:
    from floatfoam.cli.common import add_run_argument

    p = sub.add_parser("export", help="a finished run's fields as VTK files (foamToVTK), in "
                       "RUN/VTK")
    add_run_argument(p)
    p.add_argument("--vtk", action="store_true",
                   help="VTK files of every written time, the mesh moved as the body moved "
                        "(foamToVTK; the one format offered)")
    p.add_argument("--force", action="store_true",
                   help="delete an existing RUN/VTK first (without it, it is refused)")
    p.set_defaults(func=run)


def run(args) -> int:
    """Exit codes: 0 done, 1 foamToVTK (or reconstructPar) failed, 2 bad input (nothing
    written), 75 a run holds the run folder."""
    from floatfoam.cli.common import resolve_run
    from floatfoam.cli.run import EXIT_LOCKED
    from floatfoam.errors import InputError
    from floatfoam.foam.paraview import export_vtk
    from floatfoam.foam.runlock import RunLockedError

    if not args.vtk:
        raise InputError("no format given; valid is --vtk (foamToVTK into RUN/VTK)")
    run_dir = resolve_run(args.run, args.level)
    try:
        out = export_vtk(run_dir, force=args.force)
    except RunLockedError as err:
        print(f"floatfoam export: {err}", file=sys.stderr)
        return EXIT_LOCKED
    print(out)
    return 0
