#!/usr/bin/env python3
"""`postprocess/analyse.py ...`: the same as `floatfoam analyse ...`."""

import sys

from floatfoam.cli import main

if __name__ == "__main__":
    sys.exit(main(["analyse", *sys.argv[1:]]))
