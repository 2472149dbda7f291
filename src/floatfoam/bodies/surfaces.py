"""Closed bodies from an implicit surface F(x, y, z) = 0 or from an STL file."""

from __future__ import annotations

import ast
import struct
from pathlib import Path

import numpy as np

from floatfoam.bodies.geometry import mesh_volume, open_edges
from floatfoam.bodies.shapes import MeshBody
from floatfoam.errors import InputError

_FUNCTIONS = {
    name: getattr(np, name)
    for name in ("sin", "cos", "tan", "exp", "log", "sqrt", "abs", "arctan2", "minimum",
                 "maximum", "sinh", "cosh", "tanh", "arcsin", "arccos", "arctan")
}
_CONSTANTS = {"pi": np.pi, "e": np.e}
_ALLOWED_NODES = (ast.Expression, ast.BinOp, ast.UnaryOp, ast.Call, ast.Name, ast.Load,
                  ast.Constant, ast.operator, ast.unaryop)


def compile_expression(text: str, key: str = "body.expression"):
    """Compile ``text`` (an expression in x, y, z, numbers, + − * / ** and numpy functions
    such as sqrt, abs, sin) into a vectorised function F(x, y, z)."""
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError as err:
        raise InputError(f"{key} = {text!r} is not a valid expression ({err.msg})") from None
    allowed = {"x", "y", "z", *_FUNCTIONS, *_CONSTANTS}
    for node in ast.walk(tree):
        if not isinstance(node, _ALLOWED_NODES):
            raise InputError(f"{key} = {text!r}: only arithmetic in x, y, z and functions "
                             f"{', '.join(sorted(_FUNCTIONS))} are valid")
        if isinstance(node, ast.Name) and node.id not in allowed:
            raise InputError(f"{key} = {text!r}: unknown name {node.id!r}; valid names are "
                             "x, y, z, pi, e and " + ", ".join(sorted(_FUNCTIONS)))
    code = compile(tree, "<expression>", "eval")
    namespace = {"__builtins__": {}, **_FUNCTIONS, **_CONSTANTS}
    return lambda x, y, z: eval(code, namespace, {"x": x, "y": y, "z": z})  # noqa: S307


def implicit_body(expression: str, bounds, resolution: int = 96) -> MeshBody:
    """Mesh the surface F = 0 (inside F < 0) by marching cubes on a regular grid spanning
    ``bounds`` = [[x0, y0, z0], [x1, y1, z1]] with ``resolution`` points per axis.

    The surface must be closed inside the bounds: F > 0 on every face of the box.
    """
    from skimage.measure import marching_cubes

    lo, hi = (np.asarray(b, dtype=float) for b in bounds)
    if lo.shape != (3,) or hi.shape != (3,) or np.any(hi <= lo):
        raise InputError(f"body.bounds = {bounds!r}: valid is [[x0, y0, z0], [x1, y1, z1]] "
                         "with x1 > x0, y1 > y0, z1 > z0")
    func = compile_expression(expression)
    axes = [np.linspace(lo[i], hi[i], resolution) for i in range(3)]
    x, y, z = np.meshgrid(*axes, indexing="ij")
    values = np.broadcast_to(np.asarray(func(x, y, z), dtype=float), x.shape)
    if not np.all(np.isfinite(values)):
        raise InputError(f"body.expression = {expression!r} is not finite everywhere in "
                         "body.bounds")
    shell = np.concatenate([values[[0, -1]].ravel(), values[:, [0, -1]].ravel(),
                            values[:, :, [0, -1]].ravel()])
    if np.any(shell <= 0.0) or not np.any(values < 0.0):
        raise InputError(f"body.expression = {expression!r} is not a closed surface inside "
                         f"body.bounds = {bounds!r}: valid is F < 0 inside the body and F > 0 "
                         "on the whole boundary of the bounds")
    spacing = tuple((hi - lo) / (resolution - 1))
    verts, faces, _, _ = marching_cubes(values, level=0.0, spacing=spacing)
    verts = verts + lo
    faces = faces.astype(np.int64)
    if mesh_volume(verts, faces) < 0:
        faces = faces[:, ::-1]
    return MeshBody(verts, faces, expression)


def stl_body(path: Path, scale: float = 1.0) -> MeshBody:
    """Read a closed triangle mesh from a binary or ASCII STL file (units: m × ``scale``)."""
    if not path.is_file():
        raise InputError(f"body.path = {str(path)!r} does not exist; valid is an STL file")
    data = path.read_bytes()
    triangles = _read_binary_stl(data)
    if triangles is None:
        triangles = _read_ascii_stl(data.decode("ascii", errors="replace"), path)
    verts, faces = _weld(triangles * scale)
    if open_edges(faces):
        raise InputError(f"body.path = {str(path)!r} is not a closed surface: valid is a "
                         "watertight, consistently oriented STL")
    if mesh_volume(verts, faces) < 0:
        faces = faces[:, ::-1]
    return MeshBody(verts, faces)


def _read_binary_stl(data: bytes):
    if len(data) < 84:
        return None
    (count,) = struct.unpack_from("<I", data, 80)
    if len(data) != 84 + 50 * count:
        return None
    records = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)),
                                                  ("a", "<u2")]), count=count, offset=84)
    return records["v"].astype(float)


def _read_ascii_stl(text: str, path: Path):
    coords = [line.split()[1:4] for line in text.splitlines()
              if line.strip().startswith("vertex")]
    if not coords or len(coords) % 3:
        raise InputError(f"body.path = {str(path)!r} is not a readable STL file")
    return np.array(coords, dtype=float).reshape(-1, 3, 3)


def _weld(triangles: np.ndarray, decimals: int = 9):
    points = np.round(triangles.reshape(-1, 3), decimals)
    verts, inverse = np.unique(points, axis=0, return_inverse=True)
    return verts, inverse.reshape(-1, 3).astype(np.int64)
