"""Helpers shared by the CLI commands: the CASE, --set, --level and --np arguments, the RUN of
the commands on a run (one way to name it everywhere), JSON output."""

from __future__ import annotations

from floatfoam.jsonfile import dump_json  # noqa: F401 - the commands' JSON output


def add_case_arguments(parser) -> None:
    """The CASE positional and the repeatable --set of every per-case command."""
    parser.add_argument("case", metavar="CASE", help="a folder name under cases/ or a path")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE", help="override a case value, e.g. mass.density=500")


def add_level_argument(parser) -> None:
    """The --level of a command on one run (its mesh level), with its default in the help."""
    from floatfoam.layout import LEVELS

    parser.add_argument("--level", default=LEVELS[0],
                        help=f"mesh level: {', '.join(LEVELS)} (default {LEVELS[0]})")


def add_np_argument(parser, what: str = "MPI ranks of the run") -> None:
    """The --np of a command that runs the solver: one default rule everywhere
    (:func:`floatfoam.foam.ranks.default_ranks`), said in the help with its value here."""
    from floatfoam.foam.ranks import DEFAULT_RANKS_CAP, default_ranks

    ranks = default_ranks()
    parser.add_argument("--np", type=int, default=ranks,
                        help=f"{what} (default: the cores of this machine, at most "
                             f"{DEFAULT_RANKS_CAP}: {ranks} here)")


def add_run_argument(parser, *, csv: bool = False) -> None:
    """RUN, the one way every command on a run names it: a run folder of floatfoam run
    (``<build>/<case>/<level>``), or a CASE whose run at ``--level`` (default coarse) is meant;
    ``csv``: a motion CSV too (analyse). Resolved by :func:`resolve_run`."""
    from floatfoam.layout import LEVELS

    what = "a run folder (<build>/<case>/<level>), or a CASE (a name under cases/ or a path) " \
           "whose run at --level is meant" + (", or a motion CSV" if csv else "")
    parser.add_argument("run", metavar="RUN_OR_CSV" if csv else "RUN", help=what)
    parser.add_argument("--level", default=None,
                        help=f"with a CASE: its run's mesh level, {', '.join(LEVELS)} "
                             f"(default {LEVELS[0]})")


def resolve_run(text: str, level: str | None, *, csv: bool = False):
    """The path RUN names (:func:`add_run_argument`): a motion CSV (``csv``) as given; a case
    (a folder holding case.toml, or a bare name of a built-in case, as CASE everywhere:
    :func:`floatfoam.case.case_dir`): its run at ``level`` in the build folder; any other
    folder: a run folder, as given (the command checks it is one). An InputError naming
    --level when it is given with a run folder or is no level."""
    from pathlib import Path

    from floatfoam import layout
    from floatfoam.errors import InputError

    text = text.rstrip("/") or text
    path = Path(text)
    if path.name == "case.toml" and path.is_file():  # a case file names its case
        text, path = str(path.parent), path.parent
    if csv and path.is_file():
        if level is not None:
            raise InputError(f"--level {level}: {text} is a motion CSV, whose level is its "
                             "own; valid is --level with a CASE only")
        return path.resolve()
    bare = path.name == text and text not in (".", "..")
    is_case = (path / "case.toml").is_file() or (
        bare and (layout.CASES_DIR / text / "case.toml").is_file())
    if not is_case and path.is_dir():
        if level is not None:
            raise InputError(f"--level {level}: {text} is a run folder, whose level is its "
                             "own; valid is --level with a CASE only")
        return path.resolve()  # its case and level are read from its name
    level = level or layout.LEVELS[0]
    if level not in layout.LEVELS:
        raise InputError(f"--level {level!r}: valid levels are {', '.join(layout.LEVELS)}")
    from floatfoam.case import load_case

    try:
        case = load_case(text)
    except InputError as err:
        kinds = "a motion CSV, a run folder" if csv else "a run folder"
        raise InputError(f"RUN {text}: neither {kinds} nor a case ({err})") from None
    run = layout.run_dir(case.name, level)
    if not run.is_dir():
        raise InputError(f"{text} --level {level}: no run in {run} yet; valid is a case run "
                         f"first (floatfoam run {text} --level {level})")
    return run
