"""``floatfoam mesh body|domain|table``: body surfaces, fluid domains and the levels table.

* ``mesh body CASE``: the body's STL (and a 2D section's polygon) at a level and pose, with the
  immersed volume of the discrete body against the exact one;
* ``mesh domain CASE``: the fluid domain (2D, wedge or 3D) as MSH 2.2 for gmshToFoam, and with
  ``--check`` gmshToFoam + checkMesh on it;
* ``mesh table [CASE ...]``: per case and level, the discrete volume errors and (``--domains``)
  the cells, as a Markdown table.

The same arguments serve the thin scripts of meshes/.
"""

from __future__ import annotations

from pathlib import Path

from floatfoam import layout
from floatfoam.case import load_case
from floatfoam.cli.common import add_case_arguments, dump_json
from floatfoam.errors import InputError
from floatfoam.hydrostatics.fluid_domain import check_release
from floatfoam.layout import LEVELS
from floatfoam.meshing.levels import mesh_spec
from floatfoam.tank import POSES, pose


def add_level_argument(parser) -> None:
    parser.add_argument("--level", default="coarse", choices=[*LEVELS, "all"],
                        help="mesh level (default: coarse; all: the three)")


def add_body_arguments(parser) -> None:
    """Arguments of ``mesh body`` (and meshes/body_surface.py)."""
    add_case_arguments(parser)
    add_level_argument(parser)
    parser.add_argument("--pose", default="body", choices=POSES,
                        help="body: its own frame (default; an STL's moved to its "
                             "centroid: docs/conventions.md); equilibrium: the theory's "
                             "floating position; release: equilibrium + the [release] offsets")
    parser.add_argument("--out", metavar="DIR", type=Path,
                        help="output folder (default: build/CASE/mesh/LEVEL)")
    parser.add_argument("--json", action="store_true", help="print the reports as JSON")


def add_domain_arguments(parser) -> None:
    """Arguments of ``mesh domain`` (and meshes/fluid_domain.py)."""
    add_case_arguments(parser)
    add_level_argument(parser)
    parser.add_argument("--kind", default="auto",
                        choices=["auto", "2d", "wedge", "3d", "3d-half"],  # meshing.domains
                        help="auto: 2d for a section, wedge for an upright body of "
                             "revolution, else 3d; 3d-half: x ≥ 0 with a symmetry plane")
    parser.add_argument("--pose", default="release", choices=POSES[1:],
                        help="release (default: the decay test's start) or equilibrium")
    parser.add_argument("--out", metavar="FILE", type=Path,
                        help="output .msh (default: build/CASE/mesh/LEVEL/domain_KIND.msh)")
    parser.add_argument("--check", action="store_true",
                        help="convert with gmshToFoam and run checkMesh (next to the .msh)")
    parser.add_argument("--json", action="store_true", help="print the results as JSON")


def add_table_arguments(parser) -> None:
    """Arguments of ``mesh table`` (and meshes/mesh_table.py)."""
    parser.add_argument("cases", nargs="*", metavar="CASE",
                        help="cases (default: every case under cases/)")
    parser.add_argument("--domains", action="store_true",
                        help="also mesh each level's fluid domain and count its cells")
    parser.add_argument("--check", action="store_true",
                        help="with --domains: gmshToFoam + checkMesh each domain")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON")


def register(sub) -> None:
    p = sub.add_parser("mesh", help="body surfaces, fluid domains and mesh levels (gmsh)")
    actions = p.add_subparsers(dest="mesh_action", required=True, metavar="ACTION")
    add_body_arguments(actions.add_parser("body", help="body STL + discrete volume report"))
    actions.choices["body"].set_defaults(func=run_body)
    add_domain_arguments(actions.add_parser("domain", help="fluid domain for gmshToFoam"))
    actions.choices["domain"].set_defaults(func=run_domain)
    add_table_arguments(actions.add_parser("table", help="mesh levels table (Markdown)"))
    actions.choices["table"].set_defaults(func=run_table)


def _levels(level: str) -> tuple[str, ...]:
    return LEVELS if level == "all" else (level,)


def run_body(args) -> int:
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.meshing.body_surface import write_body
    from floatfoam.meshing.volume_report import discrete_volume_report, format_report

    case = load_case(args.case, args.overrides)
    eq = equilibrium(case)
    where = check_release(case, eq) if args.pose == "release" else pose(case, args.pose, eq)
    reports = []
    stem = "body" if args.pose == "body" else f"body_{args.pose}"
    folders = {level: _body_folder(args, case, level, stem) for level in _levels(args.level)}
    for level, folder in folders.items():
        written = write_body(case, mesh_spec(case, level), where, folder, stem)
        report = discrete_volume_report(case, level, equilibrium=eq)
        report["written"] = {k: str(v) for k, v in written.items()}
        reports.append(report)
        if not args.json:
            print(format_report(report))
            print("  written " + ", ".join(report["written"].values()))
    if args.json:
        print(dump_json(reports))
    return 0


def _body_folder(args, case, level: str, stem: str) -> Path:
    """Where the body of ``level`` goes: --out (a folder per level under it with --level all),
    else the build folder. A file that --out would overwrite is refused."""
    if args.out is None:
        return layout.case_build_dir(case.name) / "mesh" / level
    folder = args.out / level if args.level == "all" else args.out
    if folder.exists() and not folder.is_dir():
        raise InputError(f"--out {args.out}: {folder} is a file; valid is a folder")
    taken = [p for p in (folder / f"{stem}.stl", folder / f"{stem}_section.csv") if p.exists()]
    if taken:
        raise InputError(f"--out {args.out}: {taken[0]} exists; valid is a folder without "
                         "it (nothing is overwritten)")
    return folder


def _domain_file(args, level: str) -> Path | None:
    """The .msh of ``level``: --out (with the level in its name with --level all), else None
    (the build folder's). A file that exists is refused."""
    out = args.out
    if out is None:
        return None
    if out.suffix != ".msh":  # gmsh writes the format its name ends in
        raise InputError(f"--out {args.out}: valid is a file name ending in .msh")
    if args.level == "all":
        out = out.with_name(f"{out.stem}_{level}{out.suffix}")
    if out.exists():
        raise InputError(f"--out {args.out}: {out} exists; valid is a new file (nothing is "
                         "overwritten)")
    if not out.parent.is_dir():
        raise InputError(f"--out {args.out}: no folder {out.parent}; valid is a file in an "
                         "existing folder")
    return out


def run_domain(args) -> int:
    from floatfoam.foam.meshcheck import convert_and_check
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.meshing.domains import build_domain, format_domain

    case = load_case(args.case, args.overrides)
    eq = equilibrium(case)
    if args.pose == "release":
        check_release(case, eq)  # the release inside the tank, as run checks it
    results = []
    outs = {level: _domain_file(args, level) for level in _levels(args.level)}
    for level, out in outs.items():
        result = build_domain(case, level, args.kind, args.pose, out, equilibrium=eq)
        if args.check:
            msh = Path(result["path"])
            result["checkMesh"] = convert_and_check(msh, msh.with_name(f"foam_{msh.stem}"))
        results.append(result)
        if not args.json:
            print(format_domain(result))
            if args.check:
                q = result["checkMesh"]
                print(f"  checkMesh: {'Mesh OK' if q['mesh_ok'] else 'FAILED'}, max "
                      f"non-orthogonality {q['max_non_orthogonality']:.3g}° (average "
                      f"{q['average_non_orthogonality']:.3g}°), max skewness "
                      f"{q['max_skewness']:.3g}; log {q['log']}")
    if args.json:
        print(dump_json(results))
    return 0 if all(r.get("checkMesh", {}).get("mesh_ok", True) for r in results) else 1


def run_table(args) -> int:
    from floatfoam.foam.meshcheck import convert_and_check
    from floatfoam.meshing.table import level_rows, markdown

    names = args.cases or [folder.name for folder in layout.list_cases()]
    rows = []
    for name in names:
        rows += level_rows(load_case(name), domains=args.domains,
                           check=convert_and_check if args.check and args.domains else None,
                           scratch=layout.build_dir() / "mesh_table")
    print(dump_json(rows) if args.json else markdown(rows))
    return 0


def script_main(prog: str, doc: str, add_arguments, run, argv=None) -> int:
    """Entry point of a meshes/ script: parse, run, one-line errors (exit 2 for bad input,
    1 for a failed OpenFOAM check), tracebacks only with --debug."""
    import argparse
    import sys

    from floatfoam.errors import InputError
    from floatfoam.foam.runner import RunError

    parser = argparse.ArgumentParser(prog=prog, description=doc.strip().splitlines()[0])
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    add_arguments(parser)
    args = parser.parse_args(argv)
    try:
        return run(args)
    except (InputError, RunError) as err:
        if args.debug:
            raise
        print(f"{prog}: error: {err}", file=sys.stderr)
        return 2 if isinstance(err, InputError) else 1
