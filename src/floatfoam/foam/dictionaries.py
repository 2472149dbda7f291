"""The one writer of OpenFOAM dictionaries and field files (foamlib's ``FoamFile``).

foamlib edits an existing file entry by entry; these helpers start the file afresh with its
``FoamFile`` header, so a rendered dictionary holds exactly the entries given.
"""

from __future__ import annotations

from pathlib import Path

from foamlib import FoamFieldFile, FoamFile


def write_dict(path: Path, entries: dict, cls: str = "dictionary") -> None:
    """Write ``entries`` as a new OpenFOAM dictionary of class ``cls`` (replacing the file)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("")  # foamlib edits an existing file: start from an empty one
    with FoamFile(path) as dictionary:
        dictionary["FoamFile"] = {"version": 2.0, "format": "ascii", "class": cls,
                                  "object": path.name}
        for key, value in entries.items():
            dictionary[key] = value


def write_list(path: Path, values, cls: str) -> None:
    """Write ``values`` (a list or array) as the whole body of a new OpenFOAM file of class
    ``cls`` (a mesh's ``points``), whole or not at all: written beside it, then moved in."""
    path = Path(path)
    part = path.with_name(path.name + ".part")
    part.write_text("")
    with FoamFile(part) as file:
        file["FoamFile"] = {"version": 2.0, "format": "ascii", "class": cls, "object": path.name}
        file[None] = values
    part.replace(path)


def write_field(path: Path, cls: str, dimensions, internal, boundary: dict) -> None:
    """Write a new field file: its class, dimensions, uniform internal value and patches."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("")
    field = FoamFieldFile(path)
    field["FoamFile"] = {"version": 2.0, "format": "ascii", "class": cls, "object": path.name}
    field.dimensions = dimensions
    field.internal_field = internal
    field.boundary_field = boundary
