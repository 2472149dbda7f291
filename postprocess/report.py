#!/usr/bin/env python3
"""`postprocess/report.py ...`: the same as `floatfoam report ...`."""

import sys

from floatfoam.cli import main

if __name__ == "__main__":
    sys.exit(main(["report", *sys.argv[1:]]))
