"""User-facing errors: one line, exit code 2."""


class InputError(ValueError):
    """Bad input from the user (case file, --set, command line).

    The message is one line naming the parameter, its value and what would be valid.
    The CLI prints it without a traceback and exits with code 2.
    """


class ComputationError(RuntimeError):
    """A computation that could not be done (a solver failed, diverged, crashed or ran out of
    its time): one line naming what failed and what to change; the CLI exits with code 1."""


def is_number(value) -> bool:
    """Whether ``value`` is a finite number (a boolean is not one)."""
    import math

    return isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(value)


def number(value, name: str, *, minimum: float | None = None, integer: bool = False) -> float:
    """``value`` as a float if it is a finite number (not a boolean), greater than ``minimum``
    when one is given and whole when ``integer``; else an InputError naming ``name``, the value
    and what is valid. The one number check of every input (case files, --set, options)."""
    ok = is_number(value)
    ok = ok and (minimum is None or value > minimum) and (not integer or value == int(value))
    if not ok:
        kind = ("a whole number" if integer else
                "a finite number" if minimum is None else "a number")
        bound = "" if minimum is None else f" > {minimum:g}"
        raise InputError(f"{name} = {value!r}: valid is {kind}{bound}")
    return int(value) if integer else float(value)
