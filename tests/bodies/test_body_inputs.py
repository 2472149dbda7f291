"""Bad bodies are refused in one line, exit code 2, before anything is written: implicit-surface
expressions (evaluated by floatfoam's own AST walker, never Python's eval), STL files (unreadable,
empty, truncated, non-finite, crossing themselves) and case files that are not UTF-8 TOML."""

from __future__ import annotations

import builtins
import shutil
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from bodycases import torus

from floatfoam.bodies.expression import (
    MAX_EXPRESSION_DEPTH,
    MAX_EXPRESSION_LENGTH,
    compile_expression,
)
from floatfoam.bodies.geometry import (
    icosphere,
    mesh_volume,
    overlapping_boxes,
    self_intersection,
)
from floatfoam.bodies.surfaces import implicit_body, stl_body
from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.errors import InputError
from floatfoam.layout import CASES_DIR

PONTOON = CASES_DIR / "stl_pontoon" / "pontoon.stl"
BOUNDS = [[-0.32, -0.22, -0.17], [0.32, 0.22, 0.17]]  # cases/superellipsoid_buoy
SUPERELLIPSOID = "(x/0.3)**4 + (y/0.2)**4 + (z/0.15)**4 - 1"
STL_CASES = sorted(p.parent.name for p in CASES_DIR.glob("*/case.toml")
                   if 'shape = "stl"' in p.read_text())


def refused(call, *words) -> str:
    """The one-line InputError ``call`` raises, checked to name each of ``words``."""
    with pytest.raises(InputError) as info:
        call()
    message = str(info.value)
    assert "\n" not in message
    for word in words:
        assert word in message
    return message


def one_error_line(capsys, argv, *words) -> str:
    """Run the CLI: exit code 2 and exactly one line on stderr naming each of ``words``."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    for word in words:
        assert word in err
    return err


# --- implicit-surface expressions ----------------------------------------------------------

POWER_TOWER = "x**2+y**2+z**2-0.01+0*9**9**9"  # a Python int 9**387420489: never finishes


def test_a_power_tower_is_inf_at_once_not_a_hang():
    """Run apart, with a time limit: with Python's integer arithmetic it would never return."""
    code = ("from floatfoam.bodies.expression import compile_expression\n"
            "from floatfoam.bodies.surfaces import implicit_body\n"
            "from floatfoam.errors import InputError\n"
            "print(compile_expression('9**9**9')(0.0, 0.0, 0.0))\n"
            f"try: implicit_body({POWER_TOWER!r}, {BOUNDS!r}, 24)\n"
            "except InputError as err: print(err)\n")
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)
    assert time.perf_counter() - start < 30
    lines = proc.stdout.splitlines()
    assert proc.returncode == 0 and proc.stderr == ""
    assert lines == ["inf", f"body.expression = {POWER_TOWER!r} is not finite everywhere in "
                     "body.bounds"]


def test_a_power_tower_from_the_command_line_is_one_line_exit_2():
    argv = [sys.executable, "-m", "floatfoam.cli", "theory", "superellipsoid_buoy", "--set",
            f'body.expression="{POWER_TOWER}"']
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "body.expression" in proc.stderr


def test_division_by_zero_is_not_finite(capsys):
    refused(lambda: implicit_body("1/0 + x", BOUNDS, 16), "body.expression", "not finite")
    one_error_line(capsys, ["theory", "superellipsoid_buoy", "--set",
                            'body.expression="x**2 + y**2 + z**2 - 0.01 + 1/0"'],
                   "body.expression", "not finite everywhere in body.bounds")


def test_sqrt_of_a_negative_is_refused_without_numpy_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's RuntimeWarning would fail the test
        refused(lambda: implicit_body("sqrt(x - 1)", BOUNDS, 16), "body.expression",
                "not finite")
        assert np.isinf(compile_expression("exp(1000) * x + 1/y")(1.0, 1.0, 1.0))
        assert compile_expression("log(x)")(0.0, 0.0, 0.0) == -np.inf


@pytest.mark.parametrize("expression, words", [
    ("sin(x, y)", ["sin(x, y)", "2 arguments", "valid is sin(u)"]),
    ("arctan2(x)", ["1 argument", "valid is arctan2(u, v)"]),
    ("maximum()", ["0 arguments", "maximum(u, v)"]),
    ("sqrt(x=1)", ["keyword arguments", "sqrt(u)"]),
])
def test_a_function_with_the_wrong_number_of_arguments(capsys, expression, words):
    refused(lambda: compile_expression(expression), "body.expression", *words)
    one_error_line(capsys, ["theory", "superellipsoid_buoy", "--set",
                            f'body.expression="{expression}"'], "body.expression", *words)


@pytest.mark.parametrize("expression, piece", [
    ("__import__('os')", "'__import__' is not a function"),
    ("x.real", "'x.real' is not valid"),
    ("x << 2", "'x << 2' is not valid"),
    ("x // 2", "'x // 2' is not valid"),
    ("x % 2", "'x % 2' is not valid"),
    ("x @ y", "'x @ y' is not valid"),
    ("(lambda: 1)()", "'lambda: 1' is not a function"),
    ("x if y else z", "'x if y else z' is not valid"),
    ("x < y", "'x < y' is not valid"),
    ("not x", "'not x' is not valid"),
    ("~x", "'~x' is not valid"),
    ("[x][0]", "'[x][0]' is not valid"),
    ("1j + x", "'1j' is not valid"),
    ("True + x", "'True' is not valid"),
    ("'a' + x", "\"'a'\" is not valid"),
    ("w + x", "unknown name 'w'"),
    ("x(1)", "'x' is not a function"),
    ("sin + 1", "unknown name 'sin'"),
    ("x +", "not a valid expression"),
    ("", "not a valid expression"),
    ("x\0", "not a valid expression"),
])
def test_only_arithmetic_and_the_listed_functions_are_valid(expression, piece):
    refused(lambda: compile_expression(expression), "body.expression", piece, "valid")


def test_length_and_depth_are_bounded():
    long_sum = "x" + "+x" * (MAX_EXPRESSION_DEPTH + 10)
    refused(lambda: compile_expression(long_sum), "body.expression", "more than 100 deep")
    refused(lambda: compile_expression("-" * 1999 + "x"), "more than 100 deep")
    refused(lambda: compile_expression("sqrt(" * 101 + "x" + ")" * 101), "more than 100 deep")
    refused(lambda: compile_expression("x" * (MAX_EXPRESSION_LENGTH + 1)), "body.expression",
            f"{MAX_EXPRESSION_LENGTH + 1} characters", "at most 2000")
    grouped = "+".join(f"({'+'.join(['x'] * 40)})" for _ in range(20))  # 800 terms, 40 deep
    assert compile_expression(grouped)(1.0, 0.0, 0.0) == 800.0


def test_numbers_are_float64_and_the_surface_is_numpys(monkeypatch):
    """Never Python's eval: with eval and exec gone the expression still works, and gives
    numpy's numbers for the superellipsoid's arrays."""
    def forbidden(*args, **kwargs):
        raise AssertionError("eval/exec called")

    monkeypatch.setattr(builtins, "eval", forbidden)
    monkeypatch.setattr(builtins, "exec", forbidden)
    rng = np.random.default_rng(3)
    x, y, z = rng.uniform(-0.4, 0.4, (3, 50))
    got = compile_expression(SUPERELLIPSOID)(x, y, z)
    assert np.array_equal(got, (x / 0.3) ** 4 + (y / 0.2) ** 4 + (z / 0.15) ** 4 - 1)
    f = compile_expression("7/2 + 2**1000 - 2**1000 + 10**400 * 0 + pi - e + abs(-x)")
    assert np.isnan(f(1.0, 0.0, 0.0))  # 10**400 is inf, as the float64 1e400 is
    assert compile_expression(" 7/2 + (2**-1)\n - x ")(0.5, 0.0, 0.0) == 3.5
    assert compile_expression("1")(np.zeros((2, 3)), 0.0, 0.0).shape == (2, 3)


# --- STL files ------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def pontoon() -> np.ndarray:
    """The pontoon's triangles (N, 3, 3), as cases/stl_pontoon reads them."""
    body = stl_body(PONTOON)
    return body.vertices[body.faces]


def write_ascii(path: Path, triangles: np.ndarray, text=None) -> Path:
    """An ASCII STL of ``triangles``; ``text`` (facet, vertex) → string replaces a vertex."""
    lines = ["solid test"]
    for k, tri in enumerate(triangles):
        lines += ["  facet normal 0 0 0", "    outer loop"]
        for m, p in enumerate(tri):
            vertex = f"{p[0]:.9e} {p[1]:.9e} {p[2]:.9e}"
            lines.append(f"      vertex {(text or {}).get((k, m), vertex)}")
        lines += ["    endloop", "  endfacet"]
    path.write_text("\n".join([*lines, "endsolid test", ""]))
    return path


def write_binary(path: Path, triangles: np.ndarray) -> Path:
    records = np.zeros(len(triangles), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)),
                                              ("a", "<u2")])
    records["v"] = triangles
    path.write_bytes(b"\0" * 80 + np.uint32(len(triangles)).tobytes() + records.tobytes())
    return path


def case_with_stl(tmp_path: Path, write) -> Path:
    """A copy of cases/stl_pontoon whose pontoon.stl is written by ``write(path)``."""
    folder = tmp_path / "case"
    folder.mkdir()
    shutil.copy(CASES_DIR / "stl_pontoon" / "case.toml", folder)
    write(folder / "pontoon.stl")
    return folder


@pytest.mark.parametrize("shift", [(2.5, -1.3, 0.4), (137.12, -81.37, 0.4)])
def test_an_stl_drawn_away_from_its_origin_is_the_same_body(tmp_path, pontoon, shift):
    """The pontoon's STL moved in its file by ``shift`` m (a CAD's origin at a corner, or far
    away), G moved with it: the body frame's origin is the volume's centroid in x and y, so G
    lands on its planes x = 0 and y = 0 (within the binary STL's single precision of the
    coordinates), the hull is found symmetric about them and takes the half tank, and the
    hydrostatics are the centred file's."""
    from floatfoam.hydrostatics.theory import equilibrium, theory_summary
    from floatfoam.plan.kind import half_plane
    from floatfoam.tank import pose

    folder = case_with_stl(tmp_path, lambda p: write_binary(p, pontoon + shift))
    toml = folder / "case.toml"
    toml.write_text(toml.read_text().replace(
        "cog = [0.0, 0.0, -0.03]", f"cog = [{shift[0]}, {shift[1]}, {shift[2] - 0.03}]"))
    moved, centred = load_case(str(folder)), load_case("stl_pontoon")
    assert moved.cog[:2].tolist() == [0.0, 0.0]
    assert moved.cog[2] == pytest.approx(-0.03, abs=1e-5)
    assert (moved.body.lo + moved.body.hi) / 2 == pytest.approx(np.zeros(3), abs=1e-4)
    assert set(moved.body.mirror_planes) == {"x", "y"}
    here, there = theory_summary(moved), theory_summary(centred)
    assert here.draft == pytest.approx(there.draft, rel=1e-5)  # measured 2e-8, 2e-7 (far)
    for dof in ("heave", "roll"):
        assert here.period(dof) == pytest.approx(there.period(dof), rel=1e-5)  # ≤ 3e-7
    assert half_plane(moved, pose(moved, "release", equilibrium(moved))) == "x"
    assert here.file_origin == pytest.approx(shift, abs=1e-4)  # the theory prints it
    assert there.file_origin is None


def test_an_stl_without_cog_takes_its_volume_s_centroid(tmp_path, pontoon):
    """An STL case that gives no mass.cog has G at its volume's centroid (a homogeneous
    body's), wherever the file's origin is: the pontoon drawn from a corner, without cog, is
    the centred pontoon with G at its centre; a body whose centroid lies outside it (a ring)
    is refused in one line asking for mass.cog."""
    shift = np.array([0.6, 0.25, 0.12])  # the file's origin at the hull's corner
    folder = case_with_stl(tmp_path, lambda p: write_binary(p, pontoon + shift))
    toml = folder / "case.toml"
    toml.write_text(toml.read_text().replace("cog = [0.0, 0.0, -0.03]\n", ""))
    case = load_case(str(folder))
    assert case.cog == pytest.approx(np.zeros(3), abs=1e-5)  # single-precision coordinates
    assert load_case(str(folder), ["mass.cog=[0.6, 0.25, 0.09]"]).cog[2] == \
        pytest.approx(-0.03, abs=1e-5)  # given: in the file's coordinates
    vertices, faces = torus(0.3, 0.05, 32, 16)  # a ring: its centroid in the hole
    (tmp_path / "ring").mkdir()
    folder = case_with_stl(tmp_path / "ring", lambda p: write_binary(p, vertices[faces]))
    toml = folder / "case.toml"
    toml.write_text(toml.read_text().replace("cog = [0.0, 0.0, -0.03]\n", ""))
    refused(lambda: load_case(str(folder)), "mass.cog", "centroid", "outside")


def test_a_case_extending_an_stl_case_elsewhere_reads_the_base_s_file(tmp_path, pontoon):
    """A case in another folder that extends an STL case takes the base's triangles from the
    base's folder (its body.path is relative to it), and the run's digest follows the file's
    triangles, not its name: a re-exported file makes the runs of the old one foreign."""
    from floatfoam.plan.stamps import settings_digest

    base = case_with_stl(tmp_path, lambda p: write_binary(p, pontoon))
    mine = tmp_path / "elsewhere" / "mine"
    mine.mkdir(parents=True)
    (mine / "case.toml").write_text(f'[case]\nextends = "{base}"\n[mass]\ndensity = 450.0\n')
    case = load_case(str(mine))
    assert case.raw["body"]["path"] == "../../case/pontoon.stl"
    assert case.body.volume() == pytest.approx(load_case(str(base)).body.volume(), rel=1e-12)
    before = settings_digest(case, "coarse")
    write_binary(base / "pontoon.stl", pontoon * [1.0, 1.0, 1.001])
    assert settings_digest(load_case(str(mine)), "coarse") != before


def test_an_ascii_stl_with_a_word_for_a_coordinate(tmp_path, pontoon, capsys):
    path = write_ascii(tmp_path / "bad.stl", pontoon, {(3, 1): "0.1 abc 0.2"})
    refused(lambda: stl_body(path), str(path), "line 26", "0.1 abc 0.2", "three numbers")
    path = write_ascii(tmp_path / "short.stl", pontoon, {(0, 0): "0.1 0.2"})
    refused(lambda: stl_body(path), "line 4", "three numbers")
    folder = case_with_stl(tmp_path, lambda p: write_ascii(p, pontoon, {(3, 1): "x y z"}))
    one_error_line(capsys, ["theory", str(folder)], "body.path", "pontoon.stl", "'vertex x y z'")


def test_a_binary_stl_of_zero_triangles(tmp_path, capsys):
    path = write_binary(tmp_path / "empty.stl", np.zeros((0, 3, 3)))
    refused(lambda: stl_body(path), "body.path", str(path), "0 triangles")
    folder = case_with_stl(tmp_path, lambda p: write_binary(p, np.zeros((0, 3, 3))))
    one_error_line(capsys, ["theory", str(folder)], "body.path", "0 triangles")


def test_a_truncated_binary_stl(tmp_path, pontoon, capsys):
    path = write_binary(tmp_path / "cut.stl", pontoon)
    path.write_bytes(path.read_bytes()[:-30])
    refused(lambda: stl_body(path), str(path), "not a complete binary STL",
            f"declares {len(pontoon)} triangles", f"{84 + 50 * len(pontoon) - 30} bytes")
    path.write_bytes(b"\x01" * 40)
    refused(lambda: stl_body(path), str(path), "not an STL file (40 bytes)")
    folder = case_with_stl(tmp_path, lambda p: p.write_bytes(write_binary(
        p, pontoon).read_bytes()[:200]))
    one_error_line(capsys, ["theory", str(folder)], "body.path", "not a complete binary STL")


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_an_stl_with_a_nan_or_infinite_coordinate(tmp_path, pontoon, value):
    path = write_ascii(tmp_path / "a.stl", pontoon, {(5, 2): f"0.1 {value} 0.0"})
    refused(lambda: stl_body(path), str(path), "triangle 5", value, "finite coordinates")
    triangles = pontoon.copy()
    triangles[7, 0, 2] = float(value)
    path = write_binary(tmp_path / "b.stl", triangles)
    refused(lambda: stl_body(path), str(path), "triangle 7", value, "finite coordinates")


def test_a_scale_that_overflows_the_coordinates(pontoon, tmp_path):
    path = write_binary(tmp_path / "p.stl", pontoon)
    refused(lambda: stl_body(path, 1e308), "body.scale", "beyond float range")


def test_two_overlapping_copies_of_the_pontoon_are_refused(tmp_path, pontoon, capsys):
    """Twice the pontoon, the second 0.3 m along x: accepted it would weigh twice as much."""
    shifted = np.concatenate([pontoon, pontoon + [0.3, 0.0, 0.0]])
    path = write_ascii(tmp_path / "two.stl", shifted)
    message = refused(lambda: stl_body(path), str(path), "crosses itself", "meet at (")
    i, j = (int(w) for w in message.split("triangles ")[1].split(" (")[0].split(" and "))
    assert i < len(pontoon) <= j  # one triangle of each copy
    point = np.array([float(c) for c in message.split("meet at (")[1].split(")")[0].split(",")])
    assert np.all(point >= [-0.3, -0.25, -0.12] - np.float64(1e-6))
    assert np.all(point <= [0.6, 0.25, 0.12] + np.float64(1e-6))  # where the copies overlap
    twice = write_binary(tmp_path / "twice.stl", np.concatenate([pontoon, pontoon]))
    refused(lambda: stl_body(twice), "crosses itself", f"triangles 0 and {len(pontoon)}",
            "coincide")
    generic = write_binary(tmp_path / "g.stl",
                           np.concatenate([pontoon, pontoon + [0.31, 0.017, 0.023]]))
    refused(lambda: stl_body(generic), "crosses itself")
    folder = case_with_stl(tmp_path, lambda p: write_ascii(p, shifted))
    one_error_line(capsys, ["theory", str(folder)], "body.path", "crosses itself")


def test_copies_apart_or_a_closed_mesh_do_not_cross():
    v, f = icosphere(3)
    assert self_intersection(v, f) is None
    apart = np.concatenate([v, v + [2.5, 0.0, 0.0]]), np.concatenate([f, f + len(v)])
    assert self_intersection(*apart) is None
    near = np.concatenate([v, v + [1.999, 0.0, 0.0]]), np.concatenate([f, f + len(v)])
    hit = self_intersection(*near)
    assert hit is not None and hit[0] < len(f) <= hit[1]
    assert hit[2][0] == pytest.approx(1.0, abs=1e-3)


def test_two_hulls_are_each_turned_outwards(tmp_path, pontoon):
    """Two pontoons side by side, the second mirrored about its own y = 0 plane as a CAD's
    mirrored copy is, its triangles then wound inwards: each piece is turned outwards, and the
    body displaces twice the pontoon (read as one surface turned as a whole, the two would
    cancel)."""
    single = stl_body(PONTOON).volume()
    mirrored = pontoon * [1.0, -1.0, 1.0] + [0.0, 1.0, 0.0]  # corners kept: wound inwards
    path = write_binary(tmp_path / "two.stl", np.concatenate([pontoon, mirrored]))
    body = stl_body(path)
    assert mesh_volume(body.vertices, body.faces) == pytest.approx(2.0 * single, rel=1e-6)


def test_two_hulls_carry_g_between_them(tmp_path, pontoon, capsys):
    """A body of two pieces (two half-size pontoons 0.6 m apart, the second a mirrored copy):
    G between them is valid (inside the box about both), the body displaces both hulls; G
    beyond the box is refused in one line naming it."""
    half = pontoon * 0.5
    hulls = np.concatenate([half + [0.0, -0.3, 0.0], half * [1.0, -1.0, 1.0] + [0.0, 0.3, 0.0]])
    folder = tmp_path / "cat"
    folder.mkdir()
    write_binary(folder / "cat.stl", hulls)
    text = ('[body]\nshape = "stl"\npath = "cat.stl"\n[mass]\ndensity = 400.0\n'
            'cog = [0.0, 0.0, -0.015]\ngyradius = [0.2, 0.2, 0.25]\n')
    (folder / "case.toml").write_text(text)
    case = load_case(str(folder))
    assert case.body.pieces == 2
    assert case.body.volume() == pytest.approx(2 * stl_body(PONTOON).volume() / 8, rel=1e-6)
    (folder / "case.toml").write_text(text.replace("[0.0, 0.0, -0.015]", "[0.0, 0.5, 0.0]"))
    one_error_line(capsys, ["theory", str(folder)], "mass.cog = [0.0, 0.5, 0.0] is outside "
                   "the box about the body's 2 pieces")


def test_an_implicit_shell_with_a_cavity_is_refused():
    """An implicit body negative in a spherical shell 0.09–0.11 m: marching cubes give its
    outer surface and its cavity's, and the cavity displaces no water: refused as an STL's."""
    expression = "abs(sqrt(x**2 + y**2 + z**2) - 0.1) - 0.01"
    refused(lambda: implicit_body(expression, [[-0.12] * 3, [0.12] * 3], 64),
            f"body.expression = {expression!r}", "closed surface inside another",
            "piece 2 of 2")


def test_a_piece_inside_another_is_refused(tmp_path, capsys):
    """A closed surface inside the body's (a cavity, a sphere within a sphere) displaces no
    water of its own: refused in one line naming the file and the piece."""
    v, f = icosphere(3)
    inner = (v * 0.5)[f][:, ::-1]  # a cavity's surface, wound as a cavity's is
    path = write_binary(tmp_path / "hollow.stl", np.concatenate([v[f], inner]))
    refused(lambda: stl_body(path), str(path), "closed surface inside another",
            "piece 2 of 2")


def test_overlapping_boxes_are_every_overlapping_pair_once():
    rng = np.random.default_rng(11)
    for n, chunk in [(1, 5), (2, 1), (60, 7), (400, 1 << 17)]:
        lo = rng.random((n, 3))
        hi = lo + rng.random((n, 3)) ** 3 * 0.4
        label = rng.integers(0, max(1, n // 4), n)
        found = np.concatenate([np.zeros((0, 2), dtype=np.int64),
                                *overlapping_boxes(lo, hi, label, chunk=chunk)])
        pairs = [tuple(sorted(p)) for p in found.tolist()]
        overlap = np.all((lo[:, None] <= hi[None]) & (lo[None] <= hi[:, None]), axis=2)
        want = {(i, j) for i in range(n) for j in range(i + 1, n)
                if overlap[i, j] and label[i] != label[j]}
        assert len(pairs) == len(set(pairs)) and set(pairs) == want


def test_triangles_meet_as_a_linear_program_says():
    """Two triangles meet iff some convex combination of the corners of one equals one of
    the other: a feasibility problem scipy's HiGHS solves exactly, here for 300 random pairs,
    a quarter of them in one plane."""
    from scipy.optimize import linprog

    rng = np.random.default_rng(5)
    first, second = rng.random((300, 3, 3)), rng.random((300, 3, 3)) * 0.8 + 0.2
    first[:75, :, 2] = second[:75, :, 2] = 0.5
    faces = np.arange(6 * 300).reshape(-1, 3)
    meets = []
    for a, b in zip(first, second, strict=True):
        lonely = np.concatenate([a, b])
        meets.append(self_intersection(lonely, faces[:2], tolerance=1e-12) is not None)
        a_eq = np.zeros((5, 6))
        a_eq[0, :3] = a_eq[1, 3:] = 1.0
        a_eq[2:, :3], a_eq[2:, 3:] = a.T, -b.T
        lp = linprog(np.zeros(6), A_eq=a_eq, b_eq=[1, 1, 0, 0, 0], bounds=[(0, None)] * 6)
        assert meets[-1] == (lp.status == 0)
    assert 50 < sum(meets) < 250  # both answers are tested


def test_a_closed_icosphere_does_not_cross_itself():
    """20,480 triangles sharing vertices and edges everywhere: no false alarm. (Its time is a
    benchmark's matter: ~0.1 s measured, 1.3 ms for the pontoon's 32 triangles.)"""
    v, f = icosphere(5)
    assert self_intersection(v, f) is None


def test_there_are_stl_cases():
    assert STL_CASES


@pytest.mark.parametrize("name", STL_CASES)
def test_every_stl_case_still_loads(name, capsys):
    case = load_case(name)
    assert len(case.body.faces) >= 4
    assert main(["theory", name]) == 0
    if name == "stl_pontoon":  # the pontoon's hydrostatics (its README's numbers)
        out = capsys.readouterr().out
        assert "displaced volume V        0.0465536" in out
        assert "roll period                0.621517" in out


def test_a_binary_copy_of_the_pontoon_reads_as_the_ascii_file(tmp_path, pontoon):
    body = stl_body(write_binary(tmp_path / "p.stl", pontoon))
    assert body.volume() == pytest.approx(stl_body(PONTOON).volume(), rel=1e-6)  # float32


# --- case files -----------------------------------------------------------------------------

def case_file(tmp_path: Path, data: bytes) -> Path:
    folder = tmp_path / "case"
    folder.mkdir()
    (folder / "case.toml").write_bytes(data)
    return folder


@pytest.mark.parametrize("data, words", [
    (bytes(np.random.default_rng(2).integers(0, 256, 4000, dtype=np.uint8)),
     ["not UTF-8 text"]),
    ((CASES_DIR / "sphere" / "case.toml").read_text().encode("utf-16"),
     ["not UTF-8 text", "byte 0xff at offset 0"]),
    (b"[case]\ntitle = \"a\x00\"\n", ["Illegal character"]),
    (b"a = " + b"[" * 5000 + b"]" * 5000, ["nested too deep"]),
])
def test_a_case_file_that_is_not_utf8_toml(tmp_path, capsys, data, words):
    folder = case_file(tmp_path, data)
    refused(lambda: load_case(str(folder)), f"{folder / 'case.toml'}: not valid TOML", *words)
    one_error_line(capsys, ["theory", str(folder)], "case.toml: not valid TOML", *words)
