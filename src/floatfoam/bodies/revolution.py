"""Bodies of revolution given by triangles: whether a closed triangle mesh is one about its
vertical (z) axis, and its meridian (:func:`meridian`).

Such a body, upright and in heave, is meshed as an axisymmetric wedge
(:func:`floatfoam.plan.kind.default_kind`) like the shapes of revolution (a sphere, an
ellipsoid of revolution, a vertical cylinder): a fraction of the 3D tank's cells, and none of
the tetrahedral free surface's error ([docs/studies/cases/superellipsoid_buoy.md]).

The meridian is found from horizontal cross-sections of the triangles: each must be one closed
loop about the axis whose points all lie within :data:`REVOLUTION_TOLERANCE` × the body's
largest radius of the radius r of the circle of the loop's own area, πr² = A. The meridian
goes through those radii: the body of revolution it makes has the triangles' cross-sectional
areas, hence their volume and waterplane, which the theory takes (an STL's polygon of N sides
has a cross-section (N/2π)·sin(2π/N) of its circumscribed circle's: 0.16 % less at 64 sides).
"""

from __future__ import annotations

import math

import numpy as np

#: a cross-section's points may lie this far from its equal-area circle, × the body's largest
#: radius, for the body to count as one of revolution: a regular polygon of 24 sides lies
#: within 0.6 % of its circle, one of 16 within 1.3 %
REVOLUTION_TOLERANCE = 0.01
#: the most cross-sections taken at the heights of a body's vertices (an STL of revolution
#: has its vertices in rings); above it (an implicit surface's triangles) they are taken at
#: :data:`LEVELS` heights, closer together near the keel and the top
RINGS = 200
LEVELS = 161
#: a meridian point this near the axis (× the largest radius) is left out: the end on the
#: axis stands for it
AXIS_ROOM = 1e-3
#: the radii a ring's cross-sections give from below and from above, each extrapolated to the
#: ring, differ by more than this (× the largest radius) where the profile steps (a flange)
STEP = 1e-3


def meridian(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray | None:
    """The meridian (r, z) of a closed, consistently oriented triangle mesh that is a body of
    revolution about the z axis (x = y = 0), from its keel on the axis to its top on the axis,
    (N, 2); None when it is not one (a cross-section of several loops, off the axis, or not
    round within :data:`REVOLUTION_TOLERANCE`)."""
    z = vertices[:, 2]
    lo, hi = float(z.min()), float(z.max())
    height = hi - lo
    largest = float(np.max(np.hypot(vertices[:, 0], vertices[:, 1])))
    if height <= 0.0 or largest <= 0.0:
        return None
    tol = REVOLUTION_TOLERANCE * largest
    spans = z[faces].min(axis=1), z[faces].max(axis=1)
    # within a triangle's edge of the keel or the top (and 5 % of the height), a cross-section
    # may cut the chamfer by which marching cubes round a sharp rim (grid-aligned: 2 % out of
    # round at a float's top rim) and is not asked to be round; its area still sets the radius
    edges = np.linalg.norm(vertices[faces] - vertices[np.roll(faces, 1, axis=1)], axis=2)
    ends = min(float(np.median(edges)), 0.05 * height)

    def radius(level):
        inside = lo + ends < level < hi - ends
        return _radius(vertices, faces, level, tol if inside else math.inf, spans)

    # heights closer than this are one ring: an STL's single-precision heights in a ring
    # scatter by ~1e-7 of its coordinates
    gap = 1e-5 * height
    heights = np.sort(z)
    starts = np.concatenate([[0], np.flatnonzero(np.diff(heights) > gap) + 1])
    points = []
    if len(starts) <= RINGS:
        rings = np.add.reduceat(heights, starts) / np.diff(np.append(starts, len(heights)))
        rings[0], rings[-1] = lo, hi
        middles = (rings[1:] + rings[:-1]) / 2.0  # between rings, round too (a prism's)
        if any(radius(level) is None for level in middles):
            return None
        for ring in rings:
            # the radius at the ring from below and from above, each extrapolated from two
            # cross-sections clear of its heights: where they differ the profile steps
            sides = []
            for sign in (-1.0, 1.0):
                near, far = ring + 2.0 * sign * gap, ring + 4.0 * sign * gap
                if not lo < far < hi:
                    continue
                pair = radius(near), radius(far)
                if None in pair:
                    return None
                sides.append(max(2.0 * pair[0] - pair[1], 0.0))
            if len(sides) == 2 and abs(sides[1] - sides[0]) > STEP * largest:
                points += [(sides[0], ring), (sides[1], ring)]
            elif sides:
                points.append((float(np.mean(sides)), ring))
    else:
        fractions = (1.0 - np.cos(np.linspace(0.0, math.pi, LEVELS))) / 2.0
        levels = np.clip(lo + fractions * height, lo + gap, hi - gap)
        for level in levels:
            r = radius(float(level))
            if r is None:
                return None
            points.append((r, float(min(max(level, lo), hi))))
        points[0] = (points[0][0], lo)
        points[-1] = (points[-1][0], hi)
    profile = [(r, zz) for r, zz in points if r > AXIS_ROOM * largest]
    return np.array([(0.0, lo), *profile, (0.0, hi)])


def _radius(vertices: np.ndarray, faces: np.ndarray, level: float, tol: float,
            spans: tuple[np.ndarray, np.ndarray] | None = None) -> float | None:
    """The radius of the circle of the cross-section's area at height ``level``, when the
    cross-section is one loop about the axis (its centroid within ``tol`` of it) whose points
    lie within ``tol`` of that circle; None otherwise."""
    loops = cross_section(vertices, faces, level, spans)
    if len(loops) != 1:
        return None
    x, y = loops[0][:, 0], loops[0][:, 1]
    cross = x * np.roll(y, -1) - np.roll(x, -1) * y
    area = 0.5 * float(cross.sum())
    if area == 0.0:
        return None
    cx = float(np.sum((x + np.roll(x, -1)) * cross)) / (6.0 * area)
    cy = float(np.sum((y + np.roll(y, -1)) * cross)) / (6.0 * area)
    r = math.sqrt(abs(area) / math.pi)
    if math.hypot(cx, cy) > tol or float(np.max(np.abs(np.hypot(x, y) - r))) > tol:
        return None
    return r


def cross_section(vertices: np.ndarray, faces: np.ndarray, level: float,
                  spans: tuple[np.ndarray, np.ndarray] | None = None) -> list[np.ndarray]:
    """The closed loops (each (n, 2), x and y) in which the plane z = ``level`` cuts a closed
    triangle mesh (none where the surface is not closed along the plane). A vertex on the
    plane counts as below it, so every cut triangle has two edges across it, each shared by
    two cut triangles. ``spans``: each face's lowest and highest vertex height, when known."""
    low, high = spans if spans is not None else (vertices[faces, 2].min(axis=1),
                                                 vertices[faces, 2].max(axis=1))
    tri = faces[(low <= level) & (high > level)]
    side = vertices[tri, 2] > level
    if len(tri) == 0:
        return []
    edges = np.stack([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]], axis=1)
    across = side != side[:, [1, 2, 0]]
    ends = np.sort(edges[across].reshape(-1, 2, 2), axis=2)  # each cut triangle: its 2 edges
    n = len(vertices)
    keys = ends[:, :, 0].astype(np.int64) * n + ends[:, :, 1]
    unique, index = np.unique(keys, return_inverse=True)
    index = index.reshape(-1, 2)
    a, b = vertices[unique // n], vertices[unique % n]
    t = (level - a[:, 2]) / (b[:, 2] - a[:, 2])
    where = a[:, :2] + t[:, None] * (b[:, :2] - a[:, :2])
    # each edge across joins two segments: walk them into loops
    partners = [[] for _ in range(len(unique))]
    for s, (e0, e1) in enumerate(index):
        partners[e0].append((s, e1))
        partners[e1].append((s, e0))
    if any(len(p) != 2 for p in partners):  # not a closed surface along this plane
        return []
    used = np.zeros(len(index), dtype=bool)
    loops = []
    for start in range(len(index)):
        if used[start]:
            continue
        chain, edge, segment = [], int(index[start][0]), start
        while not used[segment]:
            used[segment] = True
            chain.append(edge)
            edge = next(e for s, e in partners[edge] if s == segment)
            segment = next(s for s, _ in partners[edge] if s != segment)
        loops.append(where[chain])
    return loops
