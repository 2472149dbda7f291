"""Closed bodies from an implicit surface F(x, y, z) = 0 (its expression compiled by
:func:`floatfoam.bodies.expression.compile_expression`, never ``eval``) or from an STL file."""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

from floatfoam.bodies.expression import compile_expression
from floatfoam.bodies.geometry import (
    open_edges,
    outward_pieces,
    self_intersection,
    volume_centroid,
    winding_number,
)
from floatfoam.bodies.shapes import MeshBody
from floatfoam.errors import InputError


def implicit_body(expression: str, bounds, resolution: int = 96) -> MeshBody:
    """Mesh the surface F = 0 (inside F < 0) by marching cubes on a regular grid spanning
    ``bounds`` = [[x0, y0, z0], [x1, y1, z1]] with ``resolution`` points per axis.

    The surface must be closed inside the bounds: F > 0 on every face of the box. Separate
    pieces are each turned outwards; a cavity (a piece inside another) is refused.
    """
    from skimage.measure import marching_cubes

    lo, hi = (np.asarray(b, dtype=float) for b in bounds)
    if lo.shape != (3,) or hi.shape != (3,) or np.any(hi <= lo):
        raise InputError(f"body.bounds = {bounds!r}: valid is [[x0, y0, z0], [x1, y1, z1]] "
                         "with x1 > x0, y1 > y0, z1 > z0")
    func = compile_expression(expression)
    axes = [np.linspace(lo[i], hi[i], resolution) for i in range(3)]
    x, y, z = np.meshgrid(*axes, indexing="ij")
    values = func(x, y, z)
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
    faces = _outward(verts, faces.astype(np.int64), f"body.expression = {expression!r}")
    return MeshBody(verts, faces, expression)


#: G within this fraction of an STL body's span or coordinates of its frame's vertical
#: planes x = 0 and y = 0 is on them: a centre typed in the file's coordinates, the frame's
#: origin computed from them, which a binary STL holds in single precision (6e-8 of them)
MID_PLANE_ROUNDING = 1e-6


def centred(body: MeshBody, cog) -> tuple[MeshBody, np.ndarray]:
    """An STL body moved from its file's coordinates so that its frame's origin lies on the
    vertical through the centroid of its volume, halfway up its height, and G (``cog``, in the
    file's coordinates) with it: a body of revolution or a mirror-symmetric hull drawn anywhere
    in its file is then one about the z axis, or about x = 0 and y = 0, and meets the wedge or
    the half tank (:func:`floatfoam.plan.kind.default_kind`); its heel and trim turn it about
    that origin. G's x and y within :data:`MID_PLANE_ROUNDING` of the frame's vertical planes
    are put on them. A file whose origin lies there already (within that) is left as it is."""
    cog = np.asarray(cog, dtype=float)
    centroid = volume_centroid(body.vertices, body.faces)
    origin = np.array([centroid[0], centroid[1], (body.lo[2] + body.hi[2]) / 2.0])
    rounding = MID_PLANE_ROUNDING * max(float(np.max(body.hi - body.lo)),
                                        float(np.max(np.abs(body.vertices))))
    if np.all(np.abs(origin) <= rounding):
        return body, cog
    moved = cog - origin
    moved[:2][np.abs(moved[:2]) <= rounding] = 0.0
    return body.moved(-origin), moved


def stl_body(path: Path, scale: float = 1.0) -> MeshBody:
    """Read a closed triangle mesh from a binary or ASCII STL file (units: m × ``scale``).

    The file must hold finite coordinates and a watertight, consistently oriented surface
    that does not cross itself (no two triangles coincide or meet unless they share a vertex
    or an edge); anything else is an InputError naming the file. A surface of separate pieces
    (two hulls) has each turned outwards, as a CAD's mirrored copy may come inwards; a piece
    inside another is refused.
    """
    name = f"body.path = {str(path)!r}"
    if not path.is_file():
        raise InputError(f"{name} does not exist; valid is an STL file")
    triangles = _read_stl(path.read_bytes(), name)
    _check_finite(triangles, name)
    with np.errstate(over="ignore", invalid="ignore"):
        verts, faces = _weld(triangles * scale)
    if not np.all(np.isfinite(verts)):
        raise InputError(f"body.scale = {scale!r} takes the coordinates of {name} beyond "
                         "float range: valid is a smaller scale")
    _check_coincident(verts, faces, name)
    if open_edges(faces):
        raise InputError(f"{name} is not a closed surface: valid is a watertight, "
                         "consistently oriented STL")
    _check_self_intersection(verts, faces, name)
    return MeshBody(verts, _outward(verts, faces, name))  # each hull, whichever way it came


def _outward(verts: np.ndarray, faces: np.ndarray, name: str) -> np.ndarray:
    """``faces`` with each separate piece turned outwards (:func:`outward_pieces`); a piece
    inside another (a cavity, or a body within a body), which displaces no water of its own,
    refused, naming it."""
    faces, piece = outward_pieces(verts, faces)
    count = int(piece.max()) + 1
    if count == 1:
        return faces
    parts = [faces[piece == k] for k in range(count)]
    boxes = [(verts[part].min(axis=(0, 1)), verts[part].max(axis=(0, 1))) for part in parts]
    for inner, part in enumerate(parts):
        point = verts[part[0, 0]]
        for outer, (lo, hi) in enumerate(boxes):
            if outer != inner and np.all(point >= lo) and np.all(point <= hi) \
                    and winding_number(verts, parts[outer], point) > 0.5:
                raise InputError(f"{name} holds a closed surface inside another (piece "
                                 f"{inner + 1} of {count}, by its first triangle's corner "
                                 f"{np.round(point, 6).tolist()}): valid is a body's outer "
                                 "surface alone, each separate piece outside the others")
    return faces


def _read_stl(data: bytes, name: str) -> np.ndarray:
    """The (N, 3, 3) triangles of a binary STL, else of an ASCII one (starting "solid")."""
    triangles = _read_binary_stl(data, name)
    if triangles is not None:
        return triangles
    if data.lstrip()[:5].lower() == b"solid":
        return _read_ascii_stl(data.decode("ascii", errors="replace"), name)
    if len(data) < 84:
        raise InputError(f"{name} is not an STL file ({len(data)} bytes): valid is a binary "
                         "STL (84 bytes and more) or an ASCII one (starting 'solid')")
    (count,) = struct.unpack_from("<I", data, 80)
    raise InputError(f"{name} is not a complete binary STL: its header declares {count} "
                     f"triangles (84 + 50 × {count} = {84 + 50 * count} bytes) and it has "
                     f"{len(data)} bytes; valid is a whole binary STL or an ASCII one")


def _read_binary_stl(data: bytes, name: str):
    """Triangles of a binary STL (80-byte header, count, 50 bytes a triangle), None if the
    size does not match its count, an InputError if it has no triangles."""
    if len(data) < 84:
        return None
    (count,) = struct.unpack_from("<I", data, 80)
    if len(data) != 84 + 50 * count:
        return None
    if count == 0:
        raise InputError(f"{name} is a binary STL of 0 triangles: valid is a closed surface "
                         "(4 triangles or more)")
    records = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)),
                                                  ("a", "<u2")]), count=count, offset=84)
    return records["v"].astype(float)


def _read_ascii_stl(text: str, name: str) -> np.ndarray:
    """Triangles of an ASCII STL: every ``vertex x y z`` line, three a facet."""
    vertices = [(number, line.split()) for number, line in enumerate(text.splitlines(), 1)
                if line.lstrip()[:6].lower() == "vertex"]
    if not vertices or len(vertices) % 3:
        raise InputError(f"{name} is not a readable STL file ({len(vertices)} 'vertex' "
                         "lines): valid is an ASCII STL of facets of three vertices each, or "
                         "a binary STL")
    coords = []
    for number, words in vertices:
        try:
            coords.append([float(w) for w in words[1:]])
        except ValueError:
            coords.append([])
        if len(coords[-1]) != 3 or words[0].lower() != "vertex":
            raise InputError(f"{name}, line {number}: {' '.join(words)[:60]!r} is not a vertex: "
                             "valid is 'vertex' and three numbers")
    return np.array(coords).reshape(-1, 3, 3)


def _check_finite(triangles: np.ndarray, name: str) -> None:
    """Refuse a file with a NaN or infinite coordinate, naming the first triangle that has one."""
    bad = ~np.isfinite(triangles).all(axis=(1, 2))
    if np.any(bad):
        k = int(np.argmax(bad))
        raise InputError(f"{name}: triangle {k} (counted from 0) has the vertices "
                         f"{triangles[k].tolist()}: valid are finite coordinates")


def _check_coincident(verts: np.ndarray, faces: np.ndarray, name: str) -> None:
    """Refuse two triangles on the same three vertices (a surface given twice)."""
    _, group, counts = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True,
                                 return_counts=True)
    repeated = np.flatnonzero(counts[group.ravel()] > 1)
    if repeated.size:
        i, j = repeated[group.ravel()[repeated] == group.ravel()[repeated[0]]][:2]
        where = ", ".join(f"{c:.6g}" for c in verts[faces[i]].mean(axis=0))
        raise InputError(f"{name} crosses itself: triangles {i} and {j} (counted from 0) "
                         f"coincide at ({where}) m; valid is a closed surface that does not "
                         "cross itself")


def _check_self_intersection(verts: np.ndarray, faces: np.ndarray, name: str) -> None:
    """Refuse a surface two of whose triangles meet without sharing a vertex."""
    hit = self_intersection(verts, faces)
    if hit is not None:
        i, j, point = hit
        where = ", ".join(f"{c:.6g}" for c in point)
        raise InputError(f"{name} crosses itself: triangles {i} and {j} (counted from 0) "
                         f"meet at ({where}) m; valid is a closed surface that does not cross "
                         "itself")


def _weld(triangles: np.ndarray, decimals: int = 9):
    """Shared vertices (rounded to ``decimals``) and the faces indexing them, in file order."""
    points = np.round(triangles.reshape(-1, 3), decimals)
    verts, inverse = np.unique(points, axis=0, return_inverse=True)
    return verts, inverse.reshape(-1, 3).astype(np.int64)
