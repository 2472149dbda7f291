"""Generated bad input never gets a traceback, a hang or exit 1 (issue 37).

Hypothesis throws generated ``--set`` values, whole case tables, raw case files and STL files at
``theory``, ``gz``, ``potential`` and ``run``'s up-front validation. Every answer must be exit 0,
or exit 2 with exactly one line on stderr. Each example runs under an alarm: one that takes
longer than :data:`HANG` seconds is a hang, and fails.
"""

from __future__ import annotations

import contextlib
import io
import math
import signal
import struct

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.errors import InputError
from floatfoam.foam.driver import check_run
from floatfoam.hydrostatics.theory import equilibrium

# The slowest valid answer among these commands is a 2D potential-flow solve, ~6 s on this
# machine; 60 s is ten times that, so an example over it is stuck, not slow.
HANG = 60
COMMON = dict(deadline=None, derandomize=True, database=None,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
# keys every case takes, and each case's own body keys (a key of another shape is refused at
# once, which would leave the physics untried)
KEYS = ["mass.density", "mass.mass", "mass.cog", "mass.gyradius", "fluid.rho", "fluid.g",
        "fluid.depth", "fluid.nu", "release.heave", "release.heel", "release.trim",
        "run.end_time", "run.write_interval", "run.max_delta_t", "run.inner_distance",
        "run.outer_distance", "mesh.refinement_ratio", "domain.depth", "domain.half_length",
        "case.extends", "nosuch.key", "body"]
BODY_KEYS = {"sphere": ["body.radius"], "box_bilge": ["body.beam", "body.height",
                                                     "body.bilge_radius"],
             "cylinder_heave": ["body.radius", "body.length"],
             "superellipsoid_buoy": ["body.expression", "body.bounds", "body.resolution"],
             "stl_pontoon": ["body.path", "body.scale"], "ellipsoid": ["body.semi_axes"]}
NUMBERS = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**30, 10**30),
                    st.sampled_from([0, -1, 1e-300, 1e300, 0.5, 1e-9, 1e9]))
PLAUSIBLE = st.floats(min_value=1e-3, max_value=10.0).map(repr)  # values a body could take
TOML_VALUES = st.one_of(
    PLAUSIBLE, PLAUSIBLE, PLAUSIBLE,
    NUMBERS.map(lambda v: repr(v) if not (isinstance(v, float) and not math.isfinite(v))
                else {"nan": "nan", "inf": "inf", "-inf": "-inf"}[repr(v)]),
    st.text(max_size=30).map(lambda s: '"' + s.replace("\\", "").replace('"', "") + '"'),
    st.lists(NUMBERS.filter(lambda v: isinstance(v, int) or math.isfinite(v)), max_size=4)
    .map(lambda xs: "[" + ", ".join(repr(x) for x in xs) + "]"),
    st.sampled_from(["true", "false", "[]", "{}", '"x**2+y**2+z**2-0.01"', '"1/0"',
                     '"sqrt(x-1)"', '"__import__(\'os\')"', '"9**9**9"', "[[0,0,0],[1,1,1]]"]),
    st.text(max_size=20),  # not TOML at all
)


def overrides(case: str):
    """1–3 ``key=value`` items, a key of ``case``'s own body at least half the time."""
    keys = st.one_of(st.sampled_from(BODY_KEYS[case]), st.sampled_from(KEYS))
    return st.lists(st.tuples(keys, TOML_VALUES).map("=".join), min_size=1, max_size=3)


CASE_AND_OVERRIDES = st.sampled_from(sorted(BODY_KEYS)).flatmap(
    lambda case: st.tuples(st.just(case), overrides(case)))


class HangError(Exception):
    pass


@contextlib.contextmanager
def alarm(seconds: int):
    def ring(signum, frame):
        raise HangError(f"no answer within {seconds} s")

    previous = signal.signal(signal.SIGALRM, ring)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def answer(argv: list[str]) -> tuple[int, list[str]]:
    """Exit code and stderr lines of ``floatfoam argv`` run in this process."""
    err = io.StringIO()
    with alarm(HANG), contextlib.redirect_stdout(io.StringIO()), \
            contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as stop:  # argparse
            code = stop.code
    return code, err.getvalue().strip().splitlines()


def assert_clean(argv: list[str]) -> None:
    code, lines = answer(argv)
    assert code in (0, 2), (argv, code, lines)
    if code == 2:
        assert len(lines) == 1 and "Traceback" not in lines[0], (argv, lines)


@pytest.fixture(autouse=True)
def build(tmp_path, monkeypatch):
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / "build"))
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))  # scratch folders and their sweep


def set_args(items: list[str]) -> list[str]:
    return [arg for item in items for arg in ("--set", item)]


@settings(max_examples=60, **COMMON)
@given(case_items=CASE_AND_OVERRIDES, command=st.sampled_from(["theory", "gz"]))
def test_set_values_theory_and_gz(case_items, command):
    case, items = case_items
    assert_clean([command, case, *set_args(items)])


@settings(max_examples=3, **COMMON)
@given(items=overrides("box_bilge"))
def test_set_values_potential(items):
    assert_clean(["potential", "box_bilge", *set_args(items)])


@settings(max_examples=60, **COMMON)
@given(case_items=CASE_AND_OVERRIDES)
def test_set_values_run_validation(case_items):
    """``run``'s up-front checks (what it refuses before it writes), in the library."""
    case, items = case_items
    with alarm(HANG):
        try:
            loaded = load_case(case, items)
            check_run(loaded, "coarse", 1, equilibrium(loaded))
        except InputError as err:
            assert "\n" not in str(err), str(err)


TABLES = st.dictionaries(
    st.sampled_from(["case", "body", "mass", "fluid", "release", "run", "mesh", "x"]),
    st.dictionaries(st.sampled_from(["shape", "radius", "density", "mass", "cog", "depth",
                                     "heave", "heel", "end_time", "semi_axes", "extends",
                                     "beam", "height", "length", "gyradius", "title"]),
                    st.one_of(TOML_VALUES.filter(lambda v: v.startswith(("[", '"')) or
                                                 v[:1].isdigit() or v[:1] == "-"),
                              st.sampled_from(['"sphere"', '"box"', '"ellipsoid"', '"stl"',
                                               '"implicit"']))),
    max_size=5)


def toml_text(tables: dict) -> str:
    return "".join(f"[{name}]\n" + "".join(f"{k} = {v}\n" for k, v in keys.items())
                   for name, keys in tables.items())


@settings(max_examples=40, **COMMON)
@given(tables=TABLES, command=st.sampled_from(["theory", "gz"]))
def test_generated_case_tables(tmp_path_factory, tables, command):
    folder = tmp_path_factory.mktemp("case")
    (folder / "case.toml").write_text(toml_text(tables))
    assert_clean([command, str(folder)])


@settings(max_examples=15, **COMMON)
@given(data=st.binary(max_size=200))
def test_case_files_of_random_bytes(tmp_path_factory, data):
    folder = tmp_path_factory.mktemp("case")
    (folder / "case.toml").write_bytes(data)
    assert_clean(["theory", str(folder)])


_UNIT = [((0, 0, 0), (1, 1, 0), (1, 0, 0)), ((0, 0, 0), (0, 1, 0), (1, 1, 0)),
         ((0, 0, 1), (1, 0, 1), (1, 1, 1)), ((0, 0, 1), (1, 1, 1), (0, 1, 1)),
         ((0, 0, 0), (1, 0, 0), (1, 0, 1)), ((0, 0, 0), (1, 0, 1), (0, 0, 1)),
         ((0, 1, 0), (1, 1, 1), (1, 1, 0)), ((0, 1, 0), (0, 1, 1), (1, 1, 1)),
         ((0, 0, 0), (0, 0, 1), (0, 1, 1)), ((0, 0, 0), (0, 1, 1), (0, 1, 0)),
         ((1, 0, 0), (1, 1, 0), (1, 1, 1)), ((1, 0, 0), (1, 1, 1), (1, 0, 1))]
# a cube of 1 m about the origin, outward normals: G at its centre by default
CUBE = [tuple(tuple(c - 0.5 for c in v) for v in tri) for tri in _UNIT]
COORD = st.one_of(st.floats(-2, 2), st.sampled_from([math.nan, math.inf, 0.0, 1.0]))
TRIANGLE = st.tuples(*[st.tuples(COORD, COORD, COORD)] * 3)
SOUPS = st.one_of(st.lists(TRIANGLE, max_size=12),
                  st.lists(st.sampled_from(CUBE), max_size=24),  # cubes with holes or twins
                  st.just(CUBE))


def binary_stl(triangles) -> bytes:
    body = b"".join(struct.pack("<12fH", 0, 0, 0, *[c for v in tri for c in v], 0)
                    for tri in triangles)
    return b"\0" * 80 + struct.pack("<I", len(triangles)) + body


def ascii_stl(triangles) -> bytes:
    facets = "".join("facet normal 0 0 0\n outer loop\n" + "".join(
        f"  vertex {x!r} {y!r} {z!r}\n" for x, y, z in tri) + " endloop\nendfacet\n"
        for tri in triangles)
    return f"solid s\n{facets}endsolid s\n".encode()


@settings(max_examples=40, **COMMON)
@given(triangles=SOUPS, binary=st.booleans(), cut=st.integers(0, 40), scale=st.sampled_from(
    ["0.2", "1", "-1", "0", "1e-12"]))
def test_generated_stl_files(tmp_path_factory, triangles, binary, cut, scale):
    """A cube of 1 m scaled, its faces dropped or doubled, random triangles, NaN vertices and
    files cut short: a closed, valid body or one line."""
    folder = tmp_path_factory.mktemp("stl")
    data = binary_stl(triangles) if binary else ascii_stl(triangles)
    (folder / "body.stl").write_bytes(data[:len(data) - cut] if cut < 20 else data)
    (folder / "case.toml").write_text(
        f'[body]\nshape = "stl"\npath = "body.stl"\nscale = {scale}\n'
        '[mass]\ndensity = 500.0\ngyradius = [0.08, 0.08, 0.08]\n[fluid]\ndepth = 2.0\n')
    assert_clean(["theory", str(folder)])


def test_the_cube_alone_is_a_valid_body(tmp_path):
    """The generator's base body is accepted (so the STL examples are not all refusals)."""
    (tmp_path / "body.stl").write_bytes(binary_stl(CUBE))
    (tmp_path / "case.toml").write_text('[body]\nshape = "stl"\npath = "body.stl"\n'
                                        'scale = 0.2\n[mass]\ndensity = 500.0\n'
                                        'gyradius = [0.08, 0.08, 0.08]\n')
    assert answer(["theory", str(tmp_path)])[0] == 0
