"""Small geometry helpers shared by the bodies and the hydrostatics engine."""

from __future__ import annotations

from functools import lru_cache

import numpy as np


def rotation(heel: float, trim: float) -> np.ndarray:
    """Rotation matrix ``R = R_y(trim) @ R_x(heel)`` (radians), see docs/conventions.md."""
    cp, sp = np.cos(heel), np.sin(heel)
    ct, st = np.cos(trim), np.sin(trim)
    r_x = np.array([[1.0, 0.0, 0.0], [0.0, cp, -sp], [0.0, sp, cp]])
    r_y = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    return r_y @ r_x


def to_earth(points: np.ndarray, z_c: float, heel: float, trim: float) -> np.ndarray:
    """Place body-frame points (N, 3) in the earth frame at the given attitude."""
    return points @ rotation(heel, trim).T + np.array([0.0, 0.0, z_c])


@lru_cache(maxsize=8)
def icosphere(subdivisions: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit sphere triangulated by subdividing an icosahedron; faces oriented outward.

    Cached: treat the returned arrays as read-only."""
    t = (1.0 + 5.0**0.5) / 2.0
    verts = [
        (-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
        (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
        (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1),
    ]
    faces = [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
        (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
        (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
        (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]
    v = np.array(verts, dtype=float)
    v /= np.linalg.norm(v, axis=1)[:, None]
    f = np.array(faces, dtype=np.int64)
    for _ in range(subdivisions):
        v, f = _subdivide(v, f)
    return v, f


def _subdivide(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    unique, inverse = np.unique(edges, axis=0, return_inverse=True)
    mid = v[unique[:, 0]] + v[unique[:, 1]]
    mid /= np.linalg.norm(mid, axis=1)[:, None]
    idx = inverse.reshape(3, -1).T + len(v)  # midpoints of edges 01, 12, 20
    a, b, c = f[:, 0], f[:, 1], f[:, 2]
    ab, bc, ca = idx[:, 0], idx[:, 1], idx[:, 2]
    new_faces = np.concatenate(
        [np.stack(t, axis=1) for t in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))]
    )
    return np.concatenate([v, mid]), new_faces


def extrude_polygon(polygon: np.ndarray, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Closed prism mesh of a convex (y, z) CCW polygon extruded along x over [-L/2, L/2]."""
    k = len(polygon)
    centre = polygon.mean(axis=0)
    ring = np.concatenate([polygon, centre[None, :]])
    back = np.column_stack([np.full(k + 1, -length / 2), ring])
    front = np.column_stack([np.full(k + 1, length / 2), ring])
    verts = np.concatenate([back, front])
    i = np.arange(k)
    j = (i + 1) % k
    cb, cf = k, 2 * k + 1
    # The section is CCW in (y, z), i.e. its normal is +x: the front cap keeps that order.
    front_cap = np.column_stack([np.full(k, cf), i + k + 1, j + k + 1])
    back_cap = np.column_stack([np.full(k, cb), j, i])
    sides = np.concatenate(
        [np.column_stack([i, j, j + k + 1]), np.column_stack([i, j + k + 1, i + k + 1])]
    )
    return verts, np.concatenate([front_cap, back_cap, sides])


def mesh_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Signed volume of a closed triangle mesh (positive when faces point outward)."""
    a, b, c = (vertices[faces[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def open_edges(faces: np.ndarray) -> int:
    """Number of directed edges without their opposite: 0 for a closed, consistently
    oriented (watertight) triangle mesh."""
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    forward = {tuple(e) for e in directed.tolist()}
    return sum((b, a) not in forward for a, b in forward) + (len(directed) - len(forward))


def winding_number(vertices: np.ndarray, faces: np.ndarray, point: np.ndarray) -> float:
    """Generalised winding number of a closed mesh about a point (1 inside, 0 outside).

    Sum of the signed solid angles of the triangles (Van Oosterom & Strackee 1983).
    """
    a, b, c = (vertices[faces[:, i]] - point for i in range(3))
    la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
    num = np.einsum("ij,ij->i", a, np.cross(b, c))
    den = (
        la * lb * lc
        + np.einsum("ij,ij->i", a, b) * lc
        + np.einsum("ij,ij->i", b, c) * la
        + np.einsum("ij,ij->i", c, a) * lb
    )
    return float(2.0 * np.arctan2(num, den).sum() / (4.0 * np.pi))
