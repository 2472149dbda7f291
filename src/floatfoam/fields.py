"""A typed settings table (:mod:`floatfoam.settings`): a field's spec — its default, range,
words and stamp flags (:func:`spec`) —, a table parsed from TOML with a one-line error naming
the key (:func:`parse_table`, :func:`unknown_key`), and what a run's stamp keeps of the tables
(:func:`stamped`).

A field's range is in its metadata: ``minimum`` (exclusive unless ``closed``), ``maximum``
(inclusive), ``kind`` (float, int, bool, str, or tuple: a list of names); ``added`` marks a
field (or a whole table) added after runs were made whose default leaves them as they were,
``inert`` the value at which a field changes nothing, ``extent`` a field that says only how far
a run goes (run.end_time: a longer one continues the run, :mod:`floatfoam.foam.extension`);
:func:`stamped` leaves all three out of a run's stamp."""

from __future__ import annotations

import difflib
from dataclasses import field, fields, is_dataclass

from floatfoam.errors import InputError, number

_NONE = object()


def spec(default, *, kind=float, minimum=None, closed=False, maximum=None, doc="",
          added=False, inert=_NONE, extent=False, too_many=None):
    """A settings field: its default and the range :func:`_value` checks. ``added``: a field
    added later, whose default changes nothing that was run before it; ``inert``: a value at
    which the field changes nothing (as 0 prism layers); ``extent``: a field that says only how
    far a run goes, not what it computes; ``too_many``: the words, from the value, that the
    error of a value over the maximum adds (what it would cost)."""
    return field(default=default, metadata={"kind": kind, "minimum": minimum, "closed": closed,
                                            "maximum": maximum, "doc": doc, "added": added,
                                            "inert": inert, "extent": extent,
                                            "too_many": too_many})


def stamped(settings) -> dict:
    """The settings as a run's stamp holds them (``dataclasses.asdict`` without the fields
    marked ``added`` that are at their default, nor those at their ``inert`` value, nor the
    ``extent`` ones): a field added with a default that changes nothing must not make every
    run made before it look as of other settings, nor a later run.end_time a finished run
    (the run's own end time is in its info.json)."""
    out = {}
    for item in fields(settings):
        value = getattr(settings, item.name)
        if hasattr(value, "__dataclass_fields__"):
            inner = stamped(value)
            if inner or not item.metadata.get("added"):  # an added table at its defaults
                out[item.name] = inner  # is left out whole
        elif not ((item.metadata.get("added") and value == item.default)
                  or _is_inert(value, item.metadata.get("inert", _NONE))
                  or item.metadata.get("extent")):
            out[item.name] = value
    return out


def _is_inert(value, inert) -> bool:
    """``value`` is the field's inert one, of its type too (False is not 0 layers)."""
    return type(value) is type(inert) and value == inert


def keys(cls) -> list[str]:
    """The keys a settings table accepts."""
    return [f.name for f in fields(cls)]


def unknown_key(name: str, key: str, valid) -> InputError:
    """The error for an unknown key: the valid ones and the nearest, if any is near."""
    valid = sorted(valid)
    near = difflib.get_close_matches(key, valid, n=1) or [
        name for name in valid if len(key) > 2 and (name.startswith(key) or key in name)][:1]
    hint = f" (did you mean {name}.{near[0]}?)" if near else ""
    return InputError(f"{name}.{key} is unknown{hint}; valid keys in [{name}] are "
                      f"{', '.join(valid)}")


def _value(value, name: str, meta: dict):
    kind = meta["kind"]
    if kind is bool:
        if not isinstance(value, bool):
            raise InputError(f"{name} = {value!r}: valid is true or false (a TOML boolean)")
        return value
    if kind is str:
        if not isinstance(value, str) or not value:
            raise InputError(f"{name} = {value!r}: valid is a non-empty string")
        return value
    if kind is tuple:
        if not (isinstance(value, list) and value
                and all(isinstance(v, str) and v for v in value)):
            raise InputError(f"{name} = {value!r}: valid is a non-empty list of names, "
                             f"e.g. [\"heave\", \"roll\"]")
        return tuple(value)
    low = meta["minimum"]
    result = number(value, name, minimum=None if meta["closed"] else low,
                    integer=kind is int)
    if meta["closed"] and low is not None and result < low:
        what = "a whole number" if kind is int else "a number"
        raise InputError(f"{name} = {value!r}: valid is {what} ≥ {low:g}")
    high = meta["maximum"]
    if high is not None and result > high:
        lo_text = "" if low is None else f"{low:g} {'≤' if meta['closed'] else '<'} "
        what = "a whole number" if kind is int else "a number"
        cells = f" ({meta['too_many'](result)})" if meta.get("too_many") else ""
        raise InputError(f"{name} = {value!r}: valid is {what} {lo_text}x ≤ {high:g}{cells}")
    return result


def parse_table(cls, given, name: str):
    """The settings ``cls`` of the table ``name`` (a dict from the case file)."""
    if given is None:
        given = {}
    if not isinstance(given, dict):
        raise InputError(f"[{name}] = {given!r}: valid is a table of {', '.join(keys(cls))}")
    specs = {f.name: f for f in fields(cls)}
    values = {}
    for key, value in given.items():
        spec = specs.get(key)
        if spec is None:
            raise unknown_key(name, key, specs)
        if is_dataclass(spec.default_factory):  # a table within the table ([mesh.gmsh])
            values[key] = parse_table(spec.default_factory, value, f"{name}.{key}")
        else:
            values[key] = _value(value, f"{name}.{key}", spec.metadata)
    settings = cls(**values)
    settings.check()
    return settings
