#!/usr/bin/env python3
"""Period and damping of a free-decay record: ``postprocess/analyse.py RUN_DIR_OR_CSV ...``.

Same arguments as ``floatfoam analyse`` (see floatfoam.commands.analyse).
"""

import argparse
import sys

from floatfoam.commands import analyse
from floatfoam.errors import InputError


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="analyse.py", description=__doc__.splitlines()[0])
    analyse.add_arguments(parser)
    args = parser.parse_args(argv)
    try:
        return analyse.run(args)
    except InputError as err:
        print(f"analyse.py: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
