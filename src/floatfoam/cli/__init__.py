"""Command-line entry point: ``floatfoam <command> ...``.

Each command lives in ``floatfoam.cli.<name>`` and exposes ``register(subparsers)``,
which adds its parser and sets ``func`` (called with the parsed args, returns an exit code).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import sys

from floatfoam.errors import ComputationError, InputError
from floatfoam.interrupts import SignalInterruptError, signals_interrupt

COMMANDS = ["theory", "gz", "mesh", "run", "batch", "analyse", "report", "potential",
            "decay_model", "validate", "pictures"]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="floatfoam",
        description="Oscillation and stability of floating bodies: theory, potential flow, CFD.",
    )
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in COMMANDS:
        importlib.import_module(f"floatfoam.cli.{name}").register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run one command. Every error is one line on stderr, never a traceback (unless --debug):
    exit 2 for bad input (and a case or build folder that cannot be used), 1 for a failure,
    128 + signal when interrupted (130 Ctrl-C, 143 SIGTERM, 129 SIGHUP), 141 when the reader of
    the output went away (``| head``); ``run`` adds 75 (floatfoam.cli.run)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    prog = f"floatfoam {args.command}"
    try:
        with signals_interrupt():  # a signal stops the command: one line, 128 + signal
            return int(args.func(args) or 0)
    except SignalInterruptError as err:
        with contextlib.suppress(OSError):  # a closed terminal (SIGHUP) takes stderr too
            print(f"{prog}: interrupted ({err})", file=sys.stderr)
        return err.exit_code
    except InputError as err:
        if args.debug:
            raise
        print(f"{prog}: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        # the reader closed the pipe (floatfoam theory X | head): stop quietly, like cat does
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 141
    except (PermissionError, NotADirectoryError, IsADirectoryError) as err:
        if args.debug:
            raise
        print(f"{prog}: error: cannot use {err.filename}: {err.strerror}; valid is a readable "
              "case and a writable build folder (FLOATFOAM_BUILD names another)",
              file=sys.stderr)
        return 2
    except OSError as err:  # a missing program, a full disk, an I/O error: not the input
        if args.debug:
            raise
        where = f" ({err.filename})" if err.filename else ""
        print(f"{prog}: failed: {err.strerror or err}{where}", file=sys.stderr)
        return 1
    except ComputationError as err:  # a solver failed (floatfoam mesh, potential ...): one line
        if args.debug:
            raise
        print(f"{prog}: {err}", file=sys.stderr)
        return 1
    except Exception as err:  # noqa: BLE001 - the last guard against a traceback
        if args.debug:
            raise
        print(f"{prog}: internal error: {type(err).__name__}: {err} (rerun with --debug for "
              "the traceback, and please report it)", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
