"""A run's record: what the driver wrote of a run when it rendered it
(``<run>/.floatfoam/info.json``), and what the analysis, the pictures and the cluster's
summary read of it (:class:`RunRecord`, :func:`read_record`, :func:`write_record`)."""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass
from pathlib import Path

from floatfoam import layout
from floatfoam.errors import InputError

NAME = "info.json"


@dataclass(frozen=True)
class RunRecord:
    """What a run is, as rendered (lengths in m, times in s, angles in rad; earth frame).
    A field the record does not hold is None.

    end_time : the simulated time it goes to (a continued run's, once continued)
    cells : its cell count; mesh : the kind of domain ("ogrid", "2d", "wedge", "3d",
        "3d-half")
    immersed_error : the body patch's immersed volume against the exact body's, relative
    release : the case's [release] table as run (heave m, heel and trim degrees)
    heel, trim : the release's heel and trim; centre_z : z of the body frame's origin there
    cog : G at release; orientation : the attitude there, a rotation tensor
    z_G_equilibrium, equilibrium_orientation : the theory's equilibrium (the motion series'
        reference)
    equilibrium_shift : how far the discrete body at the run's level settles from the exact
        one's equilibrium, in z of G (:func:`floatfoam.foam.render.equilibrium_shift`)
    mesh_offset : the move from the pose the mesh is made at to the release (a mesh made at
        equilibrium)
    body_size : the body's size (`floatfoam analyse`'s default DoFs); case_path : the case's
        folder (for analyse's model)
    """

    end_time: float | None = None
    cells: int | None = None
    mesh: str | None = None
    immersed_error: float | None = None
    release: dict | None = None
    heel: float | None = None
    trim: float | None = None
    centre_z: float | None = None
    cog: list | None = None
    orientation: list | None = None
    z_G_equilibrium: float | None = None  # noqa: N815 - the key info.json keeps
    equilibrium_orientation: list | None = None
    equilibrium_shift: float | None = None
    mesh_offset: list | None = None
    body_size: float | None = None
    case_path: str | None = None

    @classmethod
    def from_dict(cls, values: dict) -> RunRecord:
        """The record of a JSON object (keys it does not know are left out)."""
        known = {f.name for f in dataclasses.fields(cls)}
        return cls(**{key: value for key, value in values.items() if key in known})

    def to_dict(self) -> dict:
        """The JSON object of the record: arrays as lists, the fields it holds."""
        return {key: value.tolist() if hasattr(value, "tolist") else value
                for key, value in dataclasses.asdict(self).items() if value is not None}


def record_path(run: Path) -> Path:
    """Where a run folder keeps its record."""
    return Path(run) / layout.MARKERS / NAME


def has_record(run: Path) -> bool:
    """Whether ``run`` holds a run's record (a folder that ``floatfoam run`` rendered)."""
    return record_path(run).is_file()


def read_record(run: Path) -> RunRecord:
    """The record of the run in ``run``; an InputError naming it when it is missing or
    unreadable."""
    path = record_path(run)
    try:
        values = json.loads(path.read_text())
    except (OSError, ValueError) as err:
        raise InputError(f"run record {path}: {err}; valid is the {NAME} `floatfoam run` "
                         "writes") from None
    if not isinstance(values, dict):
        raise InputError(f"run record {path}: not a JSON object; valid is the {NAME} "
                         "`floatfoam run` writes")
    return RunRecord.from_dict(values)


def record_or_none(run: Path) -> RunRecord | None:
    """The record of the run in ``run``, None when it has none or it is unreadable."""
    try:
        return read_record(run)
    except InputError:
        return None


def write_record(run: Path, record: RunRecord) -> None:
    """Write the run's record whole (a new file moved over the old: never half written)."""
    path = record_path(run)
    fresh = path.with_name(path.name + ".new")
    fresh.write_text(json.dumps(record.to_dict(), indent=2))
    fresh.replace(path)
