"""Helpers shared by the CLI commands: the CASE and --set arguments, JSON output."""

from __future__ import annotations

from floatfoam.jsonfile import dump_json  # noqa: F401 - the commands' JSON output


def add_case_arguments(parser) -> None:
    """The CASE positional and the repeatable --set of every per-case command."""
    parser.add_argument("case", metavar="CASE", help="a folder name under cases/ or a path")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE", help="override a case value, e.g. mass.density=500")
