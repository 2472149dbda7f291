"""Command-line entry point: ``floatfoam <command> ...``.

Each command lives in ``floatfoam.cli.<name>`` and exposes ``register(subparsers)``,
which adds its parser and sets ``func`` (called with the parsed args, returns an exit code).
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import importlib
import os
import sys

from floatfoam import scratch
from floatfoam.errors import ComputationError, InputError
from floatfoam.interrupts import RECEIVED, SignalInterruptError, signals_interrupt

COMMANDS = ["theory", "gz", "mesh", "run", "batch", "status", "analyse", "report", "potential",
            "decay_model", "roll_damping", "validate", "pictures", "export"]


class OneLineParser(argparse.ArgumentParser):
    """argparse's parser whose errors are one line (argparse prints the usage first), exit 2;
    its subcommands' parsers are of this class too."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message}; see `{self.prog} --help`\n")


class VersionAction(argparse.Action):
    """``--version``: print ``floatfoam <version>`` and exit 0 (the version looked up only
    when asked for: :func:`floatfoam.package_version`)."""

    def __call__(self, parser, namespace, values, option_string=None):
        from floatfoam import package_version

        print(f"floatfoam {package_version()}")
        parser.exit(0)


# errors of a path the user gave or chose (the build folder, --out, --plot): bad input, exit 2
PATH_ERRNOS = {errno.EEXIST, errno.ENAMETOOLONG, errno.EROFS, errno.ENOTDIR, errno.EISDIR,
               errno.EACCES, errno.EPERM, errno.ENOENT, errno.ENOTEMPTY}
FULL_ERRNOS = {errno.ENOSPC, errno.EDQUOT}


def os_error_line(err: OSError) -> tuple[str, int]:
    """The one line and exit code of an OSError: a path that cannot be used is bad input (2)
    — but a program not found (ENOENT of a bare name) is not —; a full disk says so (1)."""
    name = err.filename
    if err.errno in FULL_ERRNOS:
        where = f" holding {name}" if name else ""
        return (f"failed: no space left on the disk{where}: free some space, then run the same "
                "command again (a run resumes where it stopped)", 1)
    path_like = name is not None and (err.errno != errno.ENOENT or "/" in str(name))
    if err.errno in PATH_ERRNOS and path_like:
        return (f"error: cannot use {name}: {err.strerror}; valid is a path in an existing, "
                "writable folder, at most 255 bytes a name, and a new file where one is written "
                "(nothing is overwritten; FLOATFOAM_BUILD names another build folder)", 2)
    where = f" ({name})" if name else ""
    return f"failed: {err.strerror or err}{where}", 1


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="floatfoam",
        description="Oscillation and stability of floating bodies: theory, potential flow, CFD.",
    )
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    parser.add_argument("--version", action=VersionAction, nargs=0,
                        help="print floatfoam's version and exit")
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
    scratch.sweep()  # scratch folders of commands killed with SIGKILL
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
    except OSError as err:  # a path that cannot be used, a full disk, a missing program
        if args.debug:
            raise
        line, code = os_error_line(err)
        print(f"{prog}: {line}", file=sys.stderr)
        return code
    except ComputationError as err:  # a solver failed (floatfoam mesh, potential ...): one line
        if args.debug:
            raise
        print(f"{prog}: {err}", file=sys.stderr)
        return 1
    except Exception as err:  # noqa: BLE001 - the last guard against a traceback
        if RECEIVED:  # the signal came back wrapped by a C library's call (interrupts.py)
            interrupted = SignalInterruptError(RECEIVED[-1])
            with contextlib.suppress(OSError):
                print(f"{prog}: interrupted ({interrupted})", file=sys.stderr)
            return interrupted.exit_code
        if args.debug:
            raise
        print(f"{prog}: internal error: {type(err).__name__}: {err} (rerun with --debug for "
              "the traceback, and please report it)", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
