"""Case files: ``cases/<name>/case.toml`` holds every number of a case.

Tables: [case] (title, description, and ``extends``: the name of a case this one takes every
table from, overriding only what it sets — a roll release of a body whose heave case exists),
[body] (shape and dimensions), [mass] (mass or density,
centre of gravity, radii of gyration), [fluid], [release], optional [reference], and the tables
later stages read ([domain], [mesh], [run], [potential]). Any value can be overridden with
``--set table.key=value`` (a TOML value; repeatable).
"""

from __future__ import annotations

import copy
import difflib
import hashlib
import math
import os
import sys
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from floatfoam import fields, settings
from floatfoam.bodies import shapes
from floatfoam.bodies.tables import OPTIONAL_BODY, SHAPES, make_body
from floatfoam.dofs import RELEASE_KEYS, check_free
from floatfoam.errors import InputError, table_number, table_vector
from floatfoam.layout import CASES_DIR, list_cases

# Keys a case file (or --set) may hold, table by table (the stages' tables from their typed
# settings, floatfoam.settings). None: free-form table.
SCHEMA = {
    "case": {"title", "description", "extends"},
    "body": {"shape", *{k for keys in SHAPES.values() for k in keys},
             *{k for keys in OPTIONAL_BODY.values() for k in keys}},
    "mass": {"mass", "density", "cog", "gyradius"},
    "fluid": {"rho", "nu", "g", "depth", "rho_air", "nu_air"},
    "release": set(RELEASE_KEYS),
    "reference": None,
    **{table: set(fields.keys(cls)) for table, cls in settings.TABLES.items()},
}
# What each key of the tables above the stages' means, with its unit (the stages' keys carry
# theirs in floatfoam.settings); the documentation's reference is generated from both.
KEY_DOCS = {
    "case": {"title": "a one-line title (text)", "description": "what the case is (text)",
             "extends": "the name of a case whose tables this one takes, changing what it sets"},
    "body": {
        "shape": "one of " + ", ".join(SHAPES),
        "radius": "m: circular_cylinder, sphere, vertical_cylinder",
        "length": "m along x: the 2D sections (volumes, areas and masses are for this length)",
        "half_beam": "m: elliptic_cylinder, parabolic_cylinder (half the width at the deck)",
        "half_height": "m: elliptic_cylinder", "height": "m, keel to deck: "
        "parabolic_cylinder, conic_cylinder, box, vertical_cylinder",
        "n": "m: conic_cylinder, y² = n·x + m·x²",
        "m": "conic_cylinder's m (dimensionless): < 0 ellipse, 0 parabola, > 0 hyperbola",
        "beam": "m: box", "bilge_radius": "m: box (optional, default 0: sharp bilges)",
        "semi_axes": "[a, b, c] in m: ellipsoid",
        "expression": "implicit: F(x, y, z) in m, negative inside",
        "bounds": "implicit: [[x0, y0, z0], [x1, y1, z1]] in m, a box holding the body",
        "resolution": "implicit: marching-cubes points per side (optional)",
        "path": "stl: the STL file, relative to case.toml", "scale": "stl: factor to metres "
        "(optional, default 1)"},
    "mass": {"mass": "kg (or density): the body's mass, for a 2D section per its length",
             "density": "kg/m³ (or mass): a homogeneous body's",
             "cog": "[x, y, z] in m: the centre of gravity G from the body's geometric centre "
                    "(an stl body's: in the file's coordinates, default its volume's "
                    "centroid)",
             "gyradius": "[kx, ky, kz] in m: radii of gyration about axes through G"},
    "fluid": {"rho": "kg/m³, water (default 1000)", "nu": "m²/s, water (default 1e-6)",
              "g": "m/s² (default 9.81)", "depth": "m, the water's depth (default inf: deep)",
              "rho_air": "kg/m³ (default 1)", "nu_air": "m²/s (default 1.48e-5)"},
    "release": {"heave": "m above the equilibrium", "heel": "degrees from the equilibrium "
                "attitude, −180 < heel ≤ 180", "trim": "degrees, −90 ≤ trim ≤ 90"},
    "reference": {"<name>": "a measurement: {value, uncertainty, source}, or a record "
                  "<name>_record = {file, source} (a CSV beside case.toml)"},
}
#: ``mass.cog`` of an STL body that does not give it: the centroid of its volume.
CENTROID = "centroid"

DEFAULTS = {
    "fluid": {"rho": 1000.0, "nu": 1.0e-6, "g": 9.81, "rho_air": 1.0, "nu_air": 1.48e-5},
    "release": dict.fromkeys(RELEASE_KEYS, 0.0),
    "mass": {"cog": [0.0, 0.0, 0.0]},
}


@dataclass
class Case:
    """A loaded, validated case. Angles in ``release`` stay in degrees (as in the file);
    ``settings`` are the stages' typed tables ([run], [mesh], [domain], [potential]); ``raw``
    is the merged case file, kept only as the run's fingerprint."""

    name: str
    path: Path
    raw: dict
    body: shapes.Body
    mass: float
    cog: np.ndarray
    gyradius: np.ndarray
    rho: float
    nu: float
    g: float
    depth: float
    release: dict = field(default_factory=dict)
    rho_air: float = 1.0
    nu_air: float = 1.48e-5
    settings: settings.Settings = field(default_factory=settings.Settings)
    title: str = ""
    description: str = ""
    reference: dict = field(default_factory=dict)

    @property
    def displacement(self) -> float:
        """Displaced volume at equilibrium, M / ρ (m³)."""
        return self.mass / self.rho


def case_dir(name_or_path: str) -> Path:
    """A case folder, absolute (symbolic links kept: a linked case is named after its link).

    A path (it holds a ``/`` or starts with ``.``: ``./sphere``, ``../x``, ``/data/body``)
    names that folder, or the folder of a ``case.toml`` it names. A bare name is a built-in
    case under cases/, or else a folder of that name here. Where a bare name is both, the
    built-in case is taken, and a note says how to name the folder instead; where a path names
    a folder that is also a built-in case's name, a note says the folder is taken."""
    text = str(name_or_path)
    given = Path(text)
    explicit = "/" in text or text.startswith(".")
    builtin = CASES_DIR / text
    if not explicit and (builtin / "case.toml").is_file():
        if (given / "case.toml").is_file() and given.resolve() != builtin.resolve():
            print(f"note: {text!r} is the built-in case cases/{text}; ./{text} names the folder "
                  "here", file=sys.stderr)
        return builtin
    if (given / "case.toml").is_file():
        if explicit and (CASES_DIR / given.name / "case.toml").is_file() \
                and given.resolve() != (CASES_DIR / given.name).resolve():
            print(f"note: {text} is the folder {os.path.abspath(given)}, not the built-in case "
                  f"{given.name}", file=sys.stderr)
        return Path(os.path.abspath(given))
    if given.name == "case.toml" and given.is_file():
        return Path(os.path.abspath(given.parent))
    names = [folder.name for folder in list_cases()]
    raise InputError(f"case {text!r} not found; valid are a folder with a case.toml "
                     f"or one of: {', '.join(names)}")


def build_name(folder: Path) -> str:
    """The name of a case's folder under the build folder: a built-in case's own name (reached
    by its folder or a link to it); any other case's name — its folder's, or its link's —
    with 8 hex digits of its absolute path, so that two cases of one name in two places
    (``a/cyl``, ``b/cyl``, or a folder named like a built-in case) never share a build
    folder."""
    folder = Path(os.path.abspath(folder))
    if folder.resolve().parent == CASES_DIR.resolve():
        return folder.resolve().name
    digest = hashlib.sha256(str(folder).encode()).hexdigest()[:8]
    return f"{folder.name}-{digest}"


def load_case(name_or_path: str, overrides=()) -> Case:
    """Read ``case.toml``, apply ``overrides`` ("table.key=value") and validate."""
    folder = case_dir(name_or_path)
    raw = _read_toml(folder, [])
    for item in overrides:
        apply_override(raw, item)
    merged = copy.deepcopy(DEFAULTS)
    for table, values in raw.items():
        merged.setdefault(table, {}).update(values)
    if merged["body"].get("shape") == "stl" and "cog" not in raw.get("mass", {}):
        merged["mass"]["cog"] = CENTROID  # a homogeneous body's G, where the file has it
    return _build(folder, merged)


def with_overrides(case: Case, overrides) -> Case:
    """The same case with more ``table.key=value`` applied (a time-step study's smaller
    steps, say), validated as a loaded case is."""
    raw = copy.deepcopy(case.raw)
    for item in overrides:
        apply_override(raw, item)
    return _build(case.path, raw)


def _read_toml(folder: Path, seen: list[Path]) -> dict:
    """The case file of ``folder``, with the tables of the case it ``extends`` beneath it
    (table by table: a key it sets replaces the base's; the files the base names are read
    from the base's folder)."""
    if folder in seen:
        chain = " → ".join(p.name for p in [*seen, folder])
        raise InputError(f"case.extends: the cases extend one another in a loop ({chain}); "
                         "valid is a chain ending in a case without extends")
    path = folder / "case.toml"
    data = path.read_bytes()
    try:
        raw = tomllib.loads(data.decode("utf-8"))
    except UnicodeDecodeError as err:  # random bytes, UTF-16, Latin-1 …
        raise InputError(f"{path}: not valid TOML (not UTF-8 text: byte "
                         f"0x{data[err.start]:02x} at offset {err.start}); valid is a TOML "
                         "file saved as UTF-8") from None
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"{path}: not valid TOML ({err})") from None
    except RecursionError:  # tomllib recurses once per nested array or inline table
        raise InputError(f"{path}: not valid TOML (arrays or tables nested too deep); valid "
                         "is a case file of tables of keys") from None
    base_name = raw.get("case", {}).get("extends")
    _check_tables(raw, complete=base_name is None)
    if base_name is None:
        return raw
    if not isinstance(base_name, str):
        raise InputError(f"case.extends = {base_name!r} in {folder / 'case.toml'}: valid is the "
                         "name of another case (a string)")
    base = case_dir(base_name)
    merged = _rebased(_read_toml(base, [*seen, folder]), base, folder)
    merged.get("case", {}).pop("extends", None)
    for table, values in raw.items():
        if isinstance(values, dict):
            target = merged.setdefault(table, {})
            for key, value in values.items():
                if isinstance(value, dict) and isinstance(target.get(key), dict):
                    target[key] = {**target[key], **value}  # [mesh.gmsh] and the like
                else:
                    target[key] = value
        else:
            merged[table] = values
    return merged


def _rebased(raw: dict, base: Path, folder: Path) -> dict:
    """The base case's tables with the files they name (``body.path``, a reference's
    ``file``), where relative to the base's folder, made relative to ``folder``, the extending
    case's: it reads them from there."""
    def moved(path):
        if not isinstance(path, str) or Path(path).is_absolute():
            return path
        return os.path.relpath(os.path.abspath(base / path), os.path.abspath(folder))

    body = raw.get("body")
    if isinstance(body, dict) and "path" in body:
        body["path"] = moved(body["path"])
    for entry in raw.get("reference", {}).values() \
            if isinstance(raw.get("reference"), dict) else ():
        if isinstance(entry, dict) and "file" in entry:
            entry["file"] = moved(entry["file"])
    return raw


def apply_override(raw: dict, item: str) -> None:
    """Apply one ``table.key=value`` to the parsed case (value parsed as TOML, else a string)."""
    key, sep, text = item.partition("=")
    key = key.strip()
    table, dot, name = key.partition(".")
    if not sep or not dot or not name:
        raise InputError(f"--set {item!r}: valid is table.key=value, e.g. mass.density=500")
    allowed = SCHEMA.get(table, set())
    head = name.split(".")[0]
    gmsh = table == "mesh" and head == "gmsh" and name.count(".") == 1 \
        and name.split(".")[1] in fields.keys(settings.GmshSettings)
    known = table in SCHEMA and (allowed is None and head in raw.get(table, {})
                                 or allowed is not None and name in allowed or gmsh)
    if not known:
        everywhere = sorted(f"{t}.{k}" for t, keys in SCHEMA.items() if keys for k in keys)
        near = difflib.get_close_matches(key, everywhere, n=1)
        hint = f" (did you mean {near[0]}?)" if near else ""
        if allowed:  # a known table: its keys (the reference lists every table's)
            valid = f"valid keys in [{table}] are {', '.join(sorted(allowed))}"
        else:
            valid = f"valid tables are {', '.join(f'[{t}]' for t in SCHEMA)}"
        raise InputError(f"--set {key}: unknown key{hint}; {valid} (docs/guide/cases.md; "
                         "and keys already in the case's free-form tables)")
    try:
        value = tomllib.loads(f"v = {text.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        value = text.strip()
    target = raw.setdefault(table, {})
    *parents, leaf = name.split(".")
    for parent in parents:
        target = target.setdefault(parent, {})
    target[leaf] = value


def _check_tables(raw: dict, complete: bool = True) -> None:
    """Known tables and keys; with ``complete``, [body] and [mass] present."""
    for table, values in raw.items():
        if table not in SCHEMA:
            near = difflib.get_close_matches(table, list(SCHEMA), n=1)
            hint = f" (did you mean [{near[0]}]?)" if near else ""
            raise InputError(f"case table [{table}] is unknown{hint}; valid tables are "
                             + ", ".join(f"[{t}]" for t in SCHEMA))
        if not isinstance(values, dict):
            raise InputError(f"case entry {table} = {values!r}: valid is a table [{table}]")
        allowed = SCHEMA[table]
        shape = values.get("shape") if table == "body" else None
        if shape in SHAPES:  # the keys of its shape (the others are no body's of this case)
            allowed = {"shape", *SHAPES[shape], *OPTIONAL_BODY.get(shape, ())}
        if allowed is not None and table not in settings.TABLES:  # those: parse_settings
            for key in values:
                if key not in allowed:
                    raise fields.unknown_key(table, key, allowed)
    for table in ("body", "mass") if complete else ():
        if table not in raw:
            raise InputError(f"the case has no [{table}] table; valid is a case.toml with "
                             "[body] (shape and dimensions) and [mass] (mass or density, cog, "
                             "gyradius)")


def _build(folder: Path, cfg: dict) -> Case:
    body = make_body(cfg, folder)
    fluid = {k: table_number(cfg, "fluid", k) for k in ("rho", "nu", "g")}
    depth = cfg["fluid"].get("depth", math.inf)
    depth = math.inf if depth in (math.inf, "inf") else table_number(cfg, "fluid", "depth")
    mass = _mass(cfg, body, fluid["rho"])
    stl = cfg["body"].get("shape") == "stl"
    centroid = stl and cfg["mass"]["cog"] == CENTROID
    if centroid:
        from floatfoam.bodies.geometry import volume_centroid

        cog = volume_centroid(body.vertices, body.faces)
    else:
        cog = table_vector(cfg, "mass", "cog")
    if getattr(body, "pieces", 1) > 1:  # G of two hulls lies between them
        if np.any(cog < body.lo) or np.any(cog > body.hi):
            raise InputError(f"mass.cog = {cog.tolist()} is outside the box about the body's "
                             f"{body.pieces} pieces, {body.lo.round(6).tolist()} to "
                             f"{body.hi.round(6).tolist()}; valid is a point within it")
    elif centroid and not body.contains(cog):
        where = (cog.round(6) + 0.0).tolist()  # no −0.0
        raise InputError(f"mass.cog is not given and the centroid of the body's volume, "
                         f"{where} in the file's coordinates, is outside it; valid is "
                         "mass.cog = [x, y, z], a point inside the body")
    elif not body.contains(cog):
        frame = "in the file's coordinates" if stl else "relative to its geometric centre"
        raise InputError(f"mass.cog = {cog.tolist()} is outside the body; valid is a point "
                         f"inside it ({frame})")
    if stl:  # from the file's coordinates to its centroid (x, y) and mid-height, G with it
        from floatfoam.bodies.surfaces import centred

        body, cog = centred(body, cog)
    if "gyradius" not in cfg["mass"]:
        raise InputError("mass.gyradius is missing; valid is [kx, ky, kz] in m, the radii of "
                         "gyration about axes through G")
    gyradius = table_vector(cfg, "mass", "gyradius", positive=True)
    release = {k: table_number(cfg, "release", k, positive=False) for k in RELEASE_KEYS}
    # one pair of angles for each attitude (degrees from the equilibrium one)
    if not -180.0 < release["heel"] <= 180.0:
        raise InputError(f"release.heel = {release['heel']:g}: valid is −180 < heel ≤ 180 "
                         "(degrees from the equilibrium attitude)")
    if not -90.0 <= release["trim"] <= 90.0:
        raise InputError(f"release.trim = {release['trim']:g}: valid is −90 ≤ trim ≤ 90 "
                         "(degrees from the equilibrium attitude)")
    air = {k: table_number(cfg, "fluid", k) for k in ("rho_air", "nu_air")}
    table = cfg.get("case", {})
    text = {k: table.get(k, "") for k in ("title", "description")}
    for key, value in text.items():
        if not isinstance(value, str):
            raise InputError(f"case.{key} = {value!r}: valid is a string")
    reference = cfg.get("reference", {})
    for key, entry in reference.items():  # a measured record: its file, read when drawn
        if key.endswith("_record") and not (
                isinstance(entry, dict) and isinstance(entry.get("file"), str)
                and (folder / entry["file"]).is_file()):
            raise InputError(f"reference.{key} = {entry!r}: valid is a table with file (a CSV "
                             f"beside case.toml, in {folder}) and source")
    stages = _resolved_layers(settings.parse_settings(cfg), body, cfg["body"].get("shape"))
    check_free(stages.motion.free, release)
    tank_depth = stages.domain.depth
    if math.isfinite(depth) and tank_depth is not None and abs(tank_depth - depth) > 1e-9 * depth:
        raise InputError(f"domain.depth = {tank_depth!r} differs from fluid.depth = {depth!r}: "
                         "valid is to leave it out (the tank is the fluid's depth) or set it "
                         "equal")
    return Case(name=build_name(folder), path=folder, raw=cfg, body=body, mass=mass, cog=cog,
                gyradius=gyradius, depth=float(depth), release=release, **fluid, **air,
                settings=stages, reference=reference, **text)


def _resolved_layers(stages: settings.Settings, body: shapes.Body,
                     shape: str) -> settings.Settings:
    """``mesh.gmsh.layers_3d`` as the mesh takes it: as given, or left out
    :data:`settings.TRIANGLE_LAYERS` at a body given by triangles and 0 at an exact solid. An
    ellipsoid takes them when given (meshing.domain3d); any other solid is refused them."""
    gmsh = stages.mesh.gmsh
    triangles = body.given_by_triangles
    if gmsh.layers_3d is not None:
        if gmsh.layers_3d and not body.takes_layers:
            raise InputError(f"mesh.gmsh.layers_3d = {gmsh.layers_3d}: valid only for a body "
                             "given by triangles (body.shape stl or implicit) or an ellipsoid "
                             f"(sphere, ellipsoid); 0 for a {shape}")
        return stages
    count = settings.TRIANGLE_LAYERS if triangles else 0
    return replace(stages, mesh=replace(stages.mesh, gmsh=replace(gmsh, layers_3d=count)))


def _mass(cfg: dict, body: shapes.Body, rho: float) -> float:
    given = [k for k in ("mass", "density") if k in cfg["mass"]]
    if len(given) != 1:
        raise InputError("[mass] needs exactly one of mass.mass (kg) or mass.density (kg/m³)")
    volume = body.volume()
    if given[0] == "density":
        density = table_number(cfg, "mass", "density")
        mass = density * volume
    else:
        mass = table_number(cfg, "mass", "mass")
        density = mass / volume
    if density >= rho:
        raise InputError(f"mass.{given[0]} = {cfg['mass'][given[0]]!r} makes the body "
                         f"({density:.6g} kg/m³) at least as dense as the fluid "
                         f"(fluid.rho = {rho:g}); valid is a mean density below {rho:g} kg/m³ "
                         f"(mass below {rho * volume:.6g} kg)")
    return mass
