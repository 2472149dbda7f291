#!/usr/bin/env python3
"""Write build/report/ (index.html, index.md): ``postprocess/report.py [--out DIR]``.

Same arguments as ``floatfoam report`` (see floatfoam.commands.report).
"""

import argparse
import sys

from floatfoam.commands import report
from floatfoam.errors import InputError


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="report.py", description=__doc__.splitlines()[0])
    report.add_arguments(parser)
    args = parser.parse_args(argv)
    try:
        return report.run(args)
    except InputError as err:
        print(f"report.py: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
