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


# Every number of a case lies within these magnitudes (SI units: a body from a micrometre to
# a thousand kilometres, ν from 1e-12 m²/s): products of a few of them (a volume, an inertia)
# stay far from float64's overflow and underflow, which a radius of 1e300 reaches.
SMALLEST, LARGEST = 1e-12, 1e9


def table_number(cfg: dict, table: str, key: str, *, positive: bool = True) -> float:
    """``cfg[table][key]``, a required number within :data:`SMALLEST`–:data:`LARGEST` (> 0
    when ``positive``); else an InputError naming ``table.key``."""
    if key not in cfg[table]:
        raise InputError(f"{table}.{key} is missing; it is required here")
    value = number(cfg[table][key], f"{table}.{key}", minimum=0.0 if positive else None)
    return in_range(value, f"{table}.{key}", positive)


def in_range(value: float, name: str, positive: bool) -> float:
    """``value`` if its magnitude is within [SMALLEST, LARGEST] (0 allowed when signed)."""
    size = abs(value)
    if size > LARGEST or (size < SMALLEST and (positive or size > 0.0)):
        window = (f"between {SMALLEST:g} and {LARGEST:g}" if positive else
                  f"0 or of magnitude between {SMALLEST:g} and {LARGEST:g}")
        raise InputError(f"{name} = {value!r}: valid is a number {window} (SI units)")
    return value


def table_vector(cfg: dict, table: str, key: str, *, positive: bool = False):
    """``cfg[table][key]``, three numbers [x, y, z] within :data:`SMALLEST`–:data:`LARGEST`
    (> 0 when ``positive``), as a float array; else an InputError naming ``table.key``."""
    import numpy as np

    value = cfg[table].get(key)
    ok = isinstance(value, list) and len(value) == 3 and all(is_number(v) for v in value)
    if not ok or (positive and min(value) <= 0):
        kind = "three numbers > 0" if positive else "three numbers"
        raise InputError(f"{table}.{key} = {value!r}: valid is [x, y, z], {kind}")
    for v in value:
        in_range(float(v), f"{table}.{key}", positive)
    return np.array(value, dtype=float)


def required(value, name: str):
    """A setting the CFD case cannot do without: an InputError naming it when absent."""
    if value is None:
        raise InputError(f"{name} is missing; the CFD case needs it")
    return value
