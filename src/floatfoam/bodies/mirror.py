"""Mirror symmetry of a body given by triangles: which vertical planes through its origin it is
symmetric about (:func:`mirror_planes`), its half on one side of such a plane
(:func:`clip_half`) and the normals its half's prism layers take (:func:`corner_normals`).

A body symmetric about x = 0 (or y = 0), with G on that plane and a motion that keeps it, is
meshed in half the tank with a symmetry patch there (:mod:`floatfoam.meshing.domains`): half
the cells for the same answer.
"""

from __future__ import annotations

import numpy as np

from floatfoam.bodies.expression import compile_expression

#: a mirrored vertex may lie this far from the surface, × the body's smallest extent, for the
#: body to count as symmetric: 1.2 % of a coarse 3D body cell (12 across that extent), and
#: above the round-off of an STL's single-precision coordinates (~1e-7 relative)
SYMMETRY_TOLERANCE = 1e-3


def mirror_planes(vertices: np.ndarray, faces: np.ndarray, expression: str | None = None
                  ) -> tuple[str, ...]:
    """The planes x = 0 and y = 0 (as "x", "y") the body is mirror symmetric about, in its
    own frame. A body given by an implicit ``expression`` F is symmetric when F takes the same
    value at each vertex and its mirror image (to the tolerance, as a distance: the change over
    |∇F|); one given by triangles alone when each mirrored vertex lies on its triangles (within
    :data:`SYMMETRY_TOLERANCE` × its smallest extent)."""
    extent = vertices.max(axis=0) - vertices.min(axis=0)
    tol = SYMMETRY_TOLERANCE * float(extent.min())
    found = []
    for axis, name in ((0, "x"), (1, "y")):
        mirrored = vertices * np.where(np.arange(3) == axis, -1.0, 1.0)
        if expression is not None:
            far = _implicit_distance(expression, vertices, mirrored, tol)
        else:
            far = _surface_distance(vertices, faces, mirrored, tol)
        if float(far.max()) <= tol:
            found.append(name)
    return tuple(found)


def _implicit_distance(expression: str, points: np.ndarray, mirrored: np.ndarray,
                       step: float) -> np.ndarray:
    """|F(mirrored) − F(points)| / |∇F| at ``points``: to first order, how far apart the level
    sets of F through a point and through its mirror image lie (0 for an F symmetric about the
    plane, wherever the points are: marching cubes' lie on F's trilinear interpolation)."""
    func = compile_expression(expression)
    h = 1e-3 * step
    grad = np.column_stack([(func(*(points + h * e).T) - func(*(points - h * e).T)) / (2 * h)
                            for e in np.eye(3)])
    change = np.abs(func(*mirrored.T) - func(*points.T))
    return change / np.maximum(np.linalg.norm(grad, axis=1), 1e-300)


def _surface_distance(vertices: np.ndarray, faces: np.ndarray, points: np.ndarray,
                      tol: float) -> np.ndarray:
    """Each point's distance to the nearest of the triangles, measured exactly only where it
    could be within ``tol``, a chunk of points at a time until one is found farther (the rest
    are then left at infinity: one point off the surface decides). A point that coincides with
    a vertex is at 0; the others are measured against the triangles whose centres lie within
    their largest reach (centre to corner) plus ``tol`` of them, found in a k-d tree."""
    from scipy.spatial import cKDTree

    near, _ = cKDTree(vertices).query(points)
    distance = np.where(near <= tol, near, np.inf)
    corners = vertices[faces]
    centres = corners.mean(axis=1)
    reach = float(np.linalg.norm(corners - centres[:, None, :], axis=2).max()) + tol
    tree = cKDTree(centres)
    todo = np.flatnonzero(distance > tol)
    for chunk in np.array_split(todo, max(1, len(todo) // CHUNK)):
        found = tree.query_ball_point(points[chunk], reach)
        counts = np.array([len(c) for c in found])
        if counts.sum():
            which = np.repeat(chunk, counts)
            pairs = _point_triangle(points[which], corners[np.concatenate(found).astype(int)])
            starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
            has = counts > 0
            distance[chunk[has]] = np.minimum.reduceat(pairs, starts[has])
        if (distance[chunk] > tol).any():
            break
    return distance


#: points measured together by :func:`_surface_distance` (a few MB of candidate pairs)
CHUNK = 2000


def _point_triangle(p: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """The distances from point ``p`` (3,), or from each of points (T, 3), to triangles ``tri``
    (T, 3, 3): the nearest point of each, on its face, an edge or a corner (Ericson, Real-Time
    Collision Detection, 5.1.5, written here as the minimum of the face's projection, where it
    falls inside, and the three edges' segments)."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(b - a, c - a)
    area2 = np.einsum("ij,ij->i", n, n)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.einsum("ij,ij->i", p - a, n) / area2
        q = p - t[:, None] * n  # p projected onto the triangle's plane
        inside = np.ones(len(tri), dtype=bool)
        for u, v in ((a, b), (b, c), (c, a)):
            inside &= np.einsum("ij,ij->i", np.cross(v - u, q - u), n) >= 0.0
    best = np.where(inside & (area2 > 0), np.abs(t) * np.sqrt(area2), np.inf)
    for u, v in ((a, b), (b, c), (c, a)):
        d = v - u
        length2 = np.einsum("ij,ij->i", d, d)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.clip(np.einsum("ij,ij->i", p - u, d) / length2, 0.0, 1.0)
        s = np.where(length2 > 0, s, 0.0)
        best = np.minimum(best, np.linalg.norm(p - (u + s[:, None] * d), axis=1))
    return best


def clip_half(vertices: np.ndarray, faces: np.ndarray, axis: int
              ) -> tuple[np.ndarray, np.ndarray]:
    """The part of a closed triangle mesh where coordinate ``axis`` ≥ 0: triangles across the
    plane cut along it (the cut's points exactly on it, shared by neighbours), those wholly
    below dropped. Returns (vertices, faces), the faces keeping their orientation; the cut
    leaves an open edge loop in the plane."""
    v = np.array(vertices, dtype=float)
    s = v[:, axis]
    span = float(np.ptp(v, axis=0).max())
    s[np.abs(s) <= 1e-12 * span] = 0.0  # round-off off the plane: on it
    v[:, axis] = s
    points = list(v)
    cut: dict[tuple[int, int], int] = {}

    def crossing(i: int, j: int) -> int:
        key = (min(i, j), max(i, j))
        if key not in cut:
            t = s[i] / (s[i] - s[j])
            point = v[i] + t * (v[j] - v[i])
            point[axis] = 0.0
            cut[key] = len(points)
            points.append(point)
        return cut[key]

    kept = []
    for tri in np.asarray(faces):
        if (s[tri] >= 0.0).all():
            kept.append(tuple(tri))
            continue
        if (s[tri] <= 0.0).all():
            continue
        polygon = []  # Sutherland–Hodgman against the half-space s ≥ 0
        for k in range(3):
            i, j = int(tri[k]), int(tri[(k + 1) % 3])
            if s[i] >= 0.0:
                polygon.append(i)
            if (s[i] > 0.0 > s[j]) or (s[i] < 0.0 < s[j]):
                polygon.append(crossing(i, j))
        kept += [(polygon[0], polygon[k], polygon[k + 1]) for k in range(1, len(polygon) - 1)]
    out = np.array(points)
    tris = np.array(kept, dtype=np.int64).reshape(-1, 3)
    if len(tris):  # none lying flat in the plane
        tris = tris[~(out[tris][:, :, axis] == 0.0).all(axis=1)]
    used = np.unique(tris)
    index = np.full(len(out), -1, dtype=np.int64)
    index[used] = np.arange(len(used))
    return out[used], index[tris]


def corner_normals(vertices: np.ndarray, faces: np.ndarray, feature_angle: float,
                   plane: int | None = None) -> np.ndarray:
    """Unit normals at each triangle's corners (T, 3, 3): the area-weighted mean of the
    normals of the triangles around the corner's vertex that turn less than
    ``feature_angle`` (radians) from this triangle's, so a sharp edge keeps each side's
    normal. At a vertex in the plane ``plane`` = 0 (axis index) the component across it is
    removed: there the whole symmetric body's normal lies in the plane, and the half's
    one-sided mean would lean out of it."""
    corners = vertices[faces]
    weighted = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    unit = weighted / np.maximum(np.linalg.norm(weighted, axis=1), 1e-300)[:, None]
    around: dict[int, list[int]] = {}
    for t, tri in enumerate(faces):
        for vertex in tri:
            around.setdefault(int(vertex), []).append(t)
    cos_limit = np.cos(feature_angle)
    normals = np.empty(corners.shape)
    for t, tri in enumerate(faces):
        for k, vertex in enumerate(tri):
            ring = np.array(around[int(vertex)])
            smooth = ring[unit[ring] @ unit[t] >= cos_limit]
            normals[t, k] = weighted[smooth].sum(axis=0)
    normals /= np.maximum(np.linalg.norm(normals, axis=2), 1e-300)[:, :, None]
    return normals if plane is None else into_plane(normals, corners, plane)


def into_plane(normals: np.ndarray, corners: np.ndarray, plane: int) -> np.ndarray:
    """Unit corner normals (T, 3, 3) with the component across the plane ``plane`` = 0 (axis
    index) removed where the corner (``corners``, the same shape) lies in that plane."""
    laid = normals.copy()
    laid[..., plane] = np.where(corners[..., plane] == 0.0, 0.0, laid[..., plane])
    return laid / np.maximum(np.linalg.norm(laid, axis=2), 1e-300)[:, :, None]
