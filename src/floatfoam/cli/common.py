"""Helpers shared by the CLI commands: the CASE, --set, --level and --np arguments, JSON
output."""

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
