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


def volume_centroid(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """The centroid of the volume a closed, outward triangle mesh encloses (its tetrahedra from
    a point inside its box, weighted by their signed volumes): on every plane of symmetry of
    the triangles and on their axis of revolution, whatever the facets' parity."""
    ref = (vertices.min(axis=0) + vertices.max(axis=0)) / 2.0
    a, b, c = (vertices[faces[:, k]] - ref for k in range(3))
    volumes = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    return ref + (volumes[:, None] * (a + b + c)).sum(axis=0) / (4.0 * volumes.sum())


def enclosed_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """The volume a closed surface of outward triangles encloses, by ∮ z n_z dA: a half surface
    open along a vertical plane x = 0 or y = 0 too (n_z vanishes on that plane)."""
    return float(np.sum(_z_flux(vertices, faces)) / 2.0)


def _z_flux(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Each triangle's 2·∫ z n_z dA."""
    c = vertices[faces]
    cross = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])  # 2·area·n
    return cross[:, 2] * c[:, :, 2].mean(axis=1)


def outward_pieces(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``faces`` (each separate piece consistently oriented in itself) with every piece turned
    outwards, the volume it encloses (:func:`enclosed_volume`) positive, and each face's
    piece (0, 1, ...): faces sharing an edge are of one piece (two shells touching at a
    vertex are two). One piece's orientation says nothing of another's: two hulls, one
    mirrored from the other."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = len(faces)
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]),
                    axis=1)
    _, edge = np.unique(edges, axis=0, return_inverse=True)
    edge = edge.ravel()
    graph = coo_matrix((np.ones(3 * n), (np.tile(np.arange(n), 3), edge + n)),
                       shape=(n + int(edge.max()) + 1,) * 2)
    _, label = connected_components(graph, directed=False)
    _, piece = np.unique(label[:n], return_inverse=True)
    inward = np.bincount(piece, weights=_z_flux(vertices, faces))[piece] < 0.0
    return np.where(inward[:, None], faces[:, ::-1], faces), piece


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


def self_intersection(vertices: np.ndarray, faces: np.ndarray, *, tolerance: float = 1e-9):
    """Two triangles of a mesh that meet without sharing a vertex (the first pair found), or
    None.

    In a closed 2-manifold two triangles without a common vertex are apart, so any contact
    between them (crossing, touching, overlapping in one plane) is a defect; triangles that
    share a vertex or an edge are not tested. Candidates are the pairs whose bounding boxes,
    widened by ``tolerance`` × the mesh's size, overlap (:func:`overlapping_boxes`; the
    triangles about one vertex, labelled by their vertex of most triangles, are never paired,
    so a fan of thousands costs nothing). Two triangles meet when an edge of one comes within
    that distance of the other (:func:`_segments_meet_triangles`): the common segment of
    non-coplanar triangles ends on their edges, and coplanar ones overlap only if an edge of
    one crosses the other. Measured: 1.3 ms for cases/stl_pontoon (32 triangles), ~0.1 s for
    20k triangles of similar size, ~0.3 s for 20k of a gmsh section's long ones.

    Returns
    -------
    (i, j, point) or None
        Indices of the triangles (i < j) and a point where they meet.
    """
    if not len(faces):
        return None
    tri = vertices[faces]
    lo, hi = tri.min(axis=1), tri.max(axis=1)
    size = float(np.max(hi.max(axis=0) - lo.min(axis=0), initial=0.0))
    tol = tolerance * max(size, np.finfo(float).tiny)
    valence = np.bincount(faces.ravel())
    hub = faces[np.arange(len(faces)), np.argmax(valence[faces], axis=1)]
    for pairs in overlapping_boxes(lo - tol, hi + tol, hub):  # a fan's triangles: one hub
        shared = (faces[pairs[:, 0], :, None] == faces[pairs[:, 1], None, :]).any(axis=(1, 2))
        pairs = pairs[~shared]
        meet, point = _triangles_meet(tri[pairs[:, 0]], tri[pairs[:, 1]], tol)
        if np.any(meet):
            k = int(np.argmax(meet))
            i, j = sorted(int(t) for t in pairs[k])
            return i, j, point[k]
    return None


_CHILDREN = np.array([[0, 0], [0, 1], [1, 0], [1, 1]])  # the child pairs of a node pair


def overlapping_boxes(lo: np.ndarray, hi: np.ndarray, label: np.ndarray | None = None, *,
                      chunk: int = 1 << 17):
    """Pairs of axis-aligned boxes [lo, hi] (N, 3) that overlap, every pair once, in arrays
    (K, 2) of at most ``chunk``; boxes with one ``label`` (N,) are not paired.

    A bounding-volume hierarchy over the boxes in Morton order of their centres (the linear
    BVH of Lauterbach et al. 2009), traversed against itself a level at a time, all node
    pairs of a level at once: a node pair whose boxes are apart, or whose boxes all have one
    label, is dropped with everything below it. The work grows with the overlapping pairs of
    nodes, about N log N for a mesh of triangles of similar size (20k triangles: ~0.1 s).
    """
    label = np.arange(len(lo)) if label is None else np.asarray(label)
    order = _morton_order(0.5 * (lo + hi))
    levels = _hierarchy(lo[order], hi[order], label[order])
    stack = [(len(levels) - 1, np.zeros((1, 2), dtype=np.int64))]
    while stack:
        level, pairs = stack.pop()
        if len(pairs) > chunk:
            stack.append((level, pairs[chunk:]))
            pairs = pairs[:chunk]
        if level == 0:
            yield order[pairs[pairs[:, 0] != pairs[:, 1]]]
            continue
        kids = (2 * pairs[:, None, :] + _CHILDREN).reshape(-1, 2)
        kids = kids[(kids[:, 0] <= kids[:, 1]) & (kids[:, 1] < len(levels[level - 1][0]))]
        stack.append((level - 1, kids[_may_pair(kids, *levels[level - 1])]))


def _may_pair(pairs: np.ndarray, lo, hi, first_label, last_label) -> np.ndarray:
    """Which node pairs have overlapping boxes and more than one label between them."""
    a, b = pairs[:, 0], pairs[:, 1]
    overlap = np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)
    one_label = (first_label[a] == last_label[a]) & (first_label[b] == last_label[b]) \
        & (first_label[a] == first_label[b])
    return overlap & ~one_label


def _hierarchy(lo: np.ndarray, hi: np.ndarray, label: np.ndarray) -> list[tuple]:
    """Levels of a binary tree over boxes in order: level 0 the boxes, node k of level l the
    union of nodes 2k and 2k + 1 of level l − 1; each (lo, hi, lowest label, highest label)."""
    levels = [(lo, hi, label, label)]
    while len(levels[-1][0]) > 1:
        lo, hi, first, last = levels[-1]
        levels.append((_merge(lo, np.minimum), _merge(hi, np.maximum),
                       _merge(first, np.minimum), _merge(last, np.maximum)))
    return levels


def _merge(values: np.ndarray, combine) -> np.ndarray:
    """``combine`` of consecutive pairs of rows (an odd last row stays as it is)."""
    merged = combine(values[0:len(values) - 1:2], values[1::2])
    return np.concatenate([merged, values[len(merged) * 2:]])


def _morton_order(points: np.ndarray) -> np.ndarray:
    """The order of ``points`` (N, 3) along the Morton (Z-order) curve of a 2²¹ grid."""
    if not len(points):
        return np.zeros(0, dtype=np.int64)
    low = points.min(axis=0)
    span = float(np.max(points.max(axis=0) - low))
    grid = ((points - low) / max(span, np.finfo(float).tiny) * (2**21 - 1)).astype(np.uint64)
    code = _spread(grid[:, 0]) | (_spread(grid[:, 1]) << np.uint64(1)) \
        | (_spread(grid[:, 2]) << np.uint64(2))
    return np.argsort(code, kind="stable")


def _spread(v: np.ndarray) -> np.ndarray:
    """The 21 low bits of ``v`` moved to every third bit (bit k to bit 3k)."""
    for shift, mask in ((32, 0x1F00000000FFFF), (16, 0x1F0000FF0000FF),
                        (8, 0x100F00F00F00F00F), (4, 0x10C30C30C30C30C3),
                        (2, 0x1249249249249249)):
        v = (v | (v << np.uint64(shift))) & np.uint64(mask)
    return v


def _triangles_meet(first: np.ndarray, second: np.ndarray, tol: float):
    """Whether triangles ``first[k]`` and ``second[k]`` (M, 3, 3) come within ``tol`` of each
    other, and for those that do a point where an edge of one meets the other."""
    meet = np.zeros(len(first), dtype=bool)
    point = np.zeros((len(first), 3))
    for edges_of, target in ((first, second), (second, first)):
        for i in range(3):
            p, q = edges_of[:, i], edges_of[:, (i + 1) % 3]
            hit, t = _segments_meet_triangles(p, q, target, tol)
            new = hit & ~meet
            point[new] = (p + t[:, None] * (q - p))[new]
            meet |= hit
    return meet, point


def _segments_meet_triangles(p: np.ndarray, q: np.ndarray, tri: np.ndarray, tol: float):
    """Whether segments pq (M, 3) come within ``tol`` of triangles ``tri`` (M, 3, 3), and the
    middle parameter t of the part of pq that does.

    Liang–Barsky clipping (Foley et al. 1990, §3.12.4) of X(t) = p + t (q − p), 0 ≤ t ≤ 1,
    against five half-spaces, each linear in t: the slab |n·(X − a)| ≤ tol about the plane
    of the triangle (unit normal n) and the three in-plane edge half-planes moved out by tol.
    A degenerate (zero-area) triangle is never met.
    """
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    normal = np.cross(b - a, c - a)
    area2 = np.linalg.norm(normal, axis=1)
    valid = area2 > tol * tol
    n = normal / np.where(valid, area2, 1.0)[:, None]
    height_p, height_q = _dot(n, p - a), _dot(n, q - a)
    limits = [(tol - height_p, tol - height_q), (tol + height_p, tol + height_q)]
    for u, v in ((a, b), (b, c), (c, a)):
        inward = np.cross(n, v - u)
        inward /= np.maximum(np.linalg.norm(inward, axis=1), np.finfo(float).tiny)[:, None]
        limits.append((_dot(inward, p - u) + tol, _dot(inward, q - u) + tol))
    t0, t1 = np.zeros(len(p)), np.ones(len(p))
    with np.errstate(divide="ignore", invalid="ignore"):
        for g_p, g_q in limits:
            valid &= (g_p >= 0) | (g_q >= 0)
            cross = g_p / (g_p - g_q)
            t0 = np.where((g_p < 0) & (g_q >= 0), np.maximum(t0, cross), t0)
            t1 = np.where((g_q < 0) & (g_p >= 0), np.minimum(t1, cross), t1)
    return valid & (t0 <= t1), 0.5 * (t0 + t1)


def _dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Row-wise dot products of two (M, 3) arrays."""
    return np.einsum("ij,ij->i", u, v)
