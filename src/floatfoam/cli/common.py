"""Helpers shared by the CLI commands: the CASE and --set arguments, JSON output."""

from __future__ import annotations

import json
import math


def add_case_arguments(parser) -> None:
    """The CASE positional and the repeatable --set of every per-case command."""
    parser.add_argument("case", metavar="CASE", help="a folder name under cases/ or a path")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE", help="override a case value, e.g. mass.density=500")


def dump_json(data) -> str:
    """JSON with NaN/inf written as null (JSON has neither)."""
    def clean(x):
        if isinstance(x, float) and not math.isfinite(x):
            return None
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, (list, tuple)):
            return [clean(v) for v in x]
        return x

    return json.dumps(clean(data), indent=2)
