"""The bodies as exact OpenCASCADE geometry in the current gmsh model.

* :func:`add_section`: the (y, z) section of a 2D body as closed curves in the plane x = x0,
  counter-clockwise seen from +x (circle, ellipse, box with bilge arcs, conic arc + deck);
* :func:`add_meridian`: the meridian (r, z) of a body of revolution about z, in the plane y = 0
  (an ellipsoid's arc, a vertical cylinder's three lines, splines through a body of
  revolution's triangles' meridian; both ends on the axis);
* :func:`add_solid`: the body as an OpenCASCADE volume (ellipsoids by dilating a sphere,
  sections by extruding their section along x, the vertical cylinder as one).

The conic section y² = n x + m x² (x up from the vertex) is exact: each half is a rational
quadratic Bézier arc (a conic arc for any weight; weight 1 is the parabola), from the vertex,
where the tangent is horizontal, to the deck corner, with its middle control point where the
two tangents meet (Piegl & Tiller 1997, The NURBS Book, §7.3).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from floatfoam.bodies import shapes as bodies


def add_section(body, x0: float = 0.0) -> list[int]:
    """Curves of ``body``'s section in the plane x = x0, in counter-clockwise order."""
    import gmsh

    return _section(body, gmsh.model.occ, x0)


@functools.singledispatch
def _section(body, occ, x0: float) -> list[int]:
    """The section's curves, from the builder its shape registers; other bodies have none."""
    raise TypeError(f"{type(body).__name__} has no 2D section")


@_section.register(bodies.EllipticCylinder)
def _ellipse(body: bodies.EllipticCylinder, occ, x0: float) -> list[int]:
    b, c = body.b, body.c
    if b == c:
        return [occ.addCircle(x0, 0.0, 0.0, b, zAxis=[1, 0, 0], xAxis=[0, 1, 0])]
    # OpenCASCADE wants r1 ≥ r2 along its x-axis; both choices run counter-clockwise
    major = [0, 1, 0] if b > c else [0, 0, 1]
    return [occ.addEllipse(x0, 0.0, 0.0, max(b, c), min(b, c), zAxis=[1, 0, 0], xAxis=major)]


def add_meridian(body) -> list[int]:
    """Curves of the meridian of an ellipsoid of revolution about z (semi-axes a, a, c), of a
    vertical cylinder or of a body of revolution given by triangles, in the (x = r, z)
    half-plane y = 0, from the keel (r = 0) to the top."""
    import gmsh

    if not body.is_axisymmetric:
        raise TypeError(f"{type(body).__name__} is not a body of revolution about z")
    occ = gmsh.model.occ
    if isinstance(body, bodies.MeshBody):
        return _profile_curves(occ, body.meridian)
    if isinstance(body, bodies.VerticalCylinder):  # keel, bottom rim, top rim, top
        corners = [occ.addPoint(r, 0.0, z) for r, z in
                   ((0.0, -body.h / 2), (body.r, -body.h / 2), (body.r, body.h / 2),
                    (0.0, body.h / 2))]
        return [occ.addLine(corners[i], corners[i + 1]) for i in range(3)]
    a, c = float(body.axes[0]), float(body.axes[2])
    if a == c:
        # circle in the x-z plane, local x-axis along x and local y-axis along z
        return [occ.addCircle(0.0, 0.0, 0.0, a, angle1=-math.pi / 2, angle2=math.pi / 2,
                              zAxis=[0, -1, 0], xAxis=[1, 0, 0])]
    if a > c:
        return [occ.addEllipse(0.0, 0.0, 0.0, a, c, angle1=-math.pi / 2, angle2=math.pi / 2,
                               zAxis=[0, -1, 0], xAxis=[1, 0, 0])]
    # major axis along z: local x = z, local y = x; angle 0 is the top, π the keel
    return [occ.addEllipse(0.0, 0.0, 0.0, c, a, angle1=0.0, angle2=math.pi,
                           zAxis=[0, 1, 0], xAxis=[0, 0, 1])]


#: a meridian given by points turns at a corner where its chords turn by more than this
CORNER_DEGREES = 30.0
#: a chord this many times longer than a neighbouring one, and longer than this share of the
#: meridian's size, is a straight stretch (a wall between the last ring of a rounded keel and
#: the deck), drawn as a line (shorter ones, where cross-sections crowd at a rounded rim, would
#: cut the meridian into curves too short for the body's cells)
STRAIGHT_RATIO = 3.0
STRAIGHT_SHARE = 0.02


def _profile_curves(occ, profile: np.ndarray) -> list[int]:
    """The meridian through the points (r, z) of a body of revolution given by triangles
    (:func:`floatfoam.bodies.revolution.meridian`), in the half-plane y = 0: a spline through
    each run of points between corners (a turn of the chords above :data:`CORNER_DEGREES`; the
    ends on the axis), a line through each straight stretch (a chord :data:`STRAIGHT_RATIO` ×
    longer than a neighbour and longer than :data:`STRAIGHT_SHARE` of the meridian) and where
    a run has two points; no curve shorter than that share. Through an STL's rings the spline
    is a smooth curve, a little larger than their facets (a hemisphere of 12 rings: 0.4 %,
    which the run's volume line reports)."""
    size = float(np.ptp(profile, axis=0).max())
    chords = np.diff(profile, axis=0)
    keep = np.concatenate([[True], np.hypot(*chords.T) > 1e-9 * size])
    keep[-1] = True  # the end on the axis
    profile = profile[keep]
    chords = np.diff(profile, axis=0)
    length = np.hypot(*chords.T)
    heading = np.arctan2(chords[:, 1], chords[:, 0])
    turn = np.abs((np.diff(heading) + math.pi) % (2.0 * math.pi) - math.pi)
    breaks = set(np.flatnonzero(turn > math.radians(CORNER_DEGREES)) + 1)
    # a chord long beside a neighbour is a straight stretch (a wall between a rounded keel's
    # last ring and the deck): a line, so that no spline bows across it
    straight = set()
    for k in range(len(length)):
        if length[k] > max(STRAIGHT_RATIO * length[max(k - 1, 0):k + 2].min(),
                           STRAIGHT_SHARE * size):
            straight |= {k, k + 1}
    # no curve shorter than STRAIGHT_SHARE of the meridian (gmsh keeps every curve's ends as
    # nodes: a corner a hair from another, as at a chamfered rim, would make a skewed cell);
    # of two such corners the straight stretch's end is kept
    arc = np.concatenate([[0.0], np.cumsum(length)])
    last = len(profile) - 1
    corners = [0]
    for k in sorted((breaks | straight) - {0, last}):
        if arc[k] - arc[corners[-1]] >= STRAIGHT_SHARE * size:
            corners.append(k)
        elif k in straight and corners[-1] not in straight and corners[-1] != 0:
            corners[-1] = k
    if len(corners) > 1 and arc[last] - arc[corners[-1]] < STRAIGHT_SHARE * size:
        corners.pop()
    corners.append(last)
    tags = [occ.addPoint(float(r), 0.0, float(z)) for r, z in profile]
    curves = []
    for start, end in zip(corners[:-1], corners[1:], strict=True):
        run = tags[start:end + 1]
        curves.append(occ.addLine(*run) if len(run) == 2 else occ.addSpline(run))
    return curves


def add_solid(body) -> int:
    """``body`` as an OpenCASCADE volume in its own frame; returns the volume tag."""
    import gmsh

    return _solid(body, gmsh.model.occ)


@functools.singledispatch
def _solid(body, occ) -> int:
    """A section extruded along x, or the solid its shape registers; other bodies have none."""
    if body.is_section:
        loop = occ.addCurveLoop(add_section(body, -body.length / 2))
        face = occ.addPlaneSurface([loop])
        out = occ.extrude([(2, face)], body.length, 0.0, 0.0)
        return next(tag for dim, tag in out if dim == 3)
    raise TypeError(f"{type(body).__name__} has no OpenCASCADE solid; use its triangles")


@_solid.register(bodies.Ellipsoid)
def _ellipsoid(body: bodies.Ellipsoid, occ) -> int:
    """A sphere, or the unit sphere dilated by the semi-axes."""
    axes = [float(a) for a in body.axes]
    if axes[0] == axes[1] == axes[2]:
        return occ.addSphere(0.0, 0.0, 0.0, axes[0])
    tag = occ.addSphere(0.0, 0.0, 0.0, 1.0)
    occ.dilate([(3, tag)], 0.0, 0.0, 0.0, *axes)
    return tag


@_solid.register(bodies.VerticalCylinder)
def _vertical_cylinder(body: bodies.VerticalCylinder, occ) -> int:
    return occ.addCylinder(0.0, 0.0, -body.h / 2, 0.0, 0.0, body.h, body.r)


@_section.register(bodies.Box)
def _box(body: bodies.Box, occ, x0: float) -> list[int]:
    hb, hd, r = body.beam / 2, body.height / 2, body.r

    def point(y, z):
        return occ.addPoint(x0, y, z)

    if r <= 0.0:
        corners = [point(-hb, -hd), point(hb, -hd), point(hb, hd), point(-hb, hd)]
        return [occ.addLine(corners[i], corners[(i + 1) % 4]) for i in range(4)]
    keel_r, keel_l = point(hb - r, -hd), point(-hb + r, -hd)
    side_r, side_l = point(hb, -hd + r), point(-hb, -hd + r)
    deck_r, deck_l = point(hb, hd), point(-hb, hd)
    centre_r, centre_l = point(hb - r, -hd + r), point(-hb + r, -hd + r)
    return [
        occ.addLine(keel_l, keel_r),
        occ.addCircleArc(keel_r, centre_r, side_r),
        occ.addLine(side_r, deck_r),
        occ.addLine(deck_r, deck_l),
        occ.addLine(deck_l, side_l),
        occ.addCircleArc(side_l, centre_l, keel_l),
    ]


@_section.register(bodies.ConicCylinder)
def _conic(body: bodies.ConicCylinder, occ, x0: float) -> list[int]:
    n, m, h = body.n, body.m, body.h
    w = float(body.half_width(h))
    z0 = -h / 2  # the vertex (keel) in the body frame
    # tangent at the deck corner (w, h) in (y, ξ = z − z0): dξ/dy = 2w / (n + 2 m h); it meets
    # the vertex tangent ξ = 0 at y1
    y1 = w - h * (n + 2.0 * m * h) / (2.0 * w)
    weight = _conic_weight(n, m, np.array([0.0, 0.0]), np.array([y1, 0.0]), np.array([w, h]))

    def point(y, xi):
        return occ.addPoint(x0, y, xi + z0)

    vertex = point(0.0, 0.0)
    ctrl_r, deck_r = point(y1, 0.0), point(w, h)
    ctrl_l, deck_l = point(-y1, 0.0), point(-w, h)
    arc = dict(degree=2, weights=[1.0, weight, 1.0], knots=[0.0, 1.0], multiplicities=[3, 3])
    return [
        occ.addBSpline([vertex, ctrl_r, deck_r], **arc),
        occ.addLine(deck_r, deck_l),
        occ.addBSpline([deck_l, ctrl_l, vertex], **arc),
    ]


def _conic_weight(n: float, m: float, p0: np.ndarray, p1: np.ndarray, p2: np.ndarray) -> float:
    """Weight w of the middle control point of the rational quadratic Bézier arc p0 → p2 with
    tangent control point p1 that lies on F(y, ξ) = y² − n ξ − m ξ² = 0.

    Its point at t = 1/2 is q + s (p1 − q), q = (p0 + p2)/2, s = w/(1 + w): solve F = 0 for s
    (a quadratic) in (0, 1)."""
    q, d = 0.5 * (p0 + p2), p1 - 0.5 * (p0 + p2)
    a = d[0] ** 2 - m * d[1] ** 2
    b = 2.0 * q[0] * d[0] - n * d[1] - 2.0 * m * q[1] * d[1]
    c = q[0] ** 2 - n * q[1] - m * q[1] ** 2
    roots = np.roots([a, b, c]) if abs(a) > 1e-300 else np.array([-c / b])
    s = next(float(r.real) for r in roots if abs(r.imag) < 1e-12 and 0.0 < r.real < 1.0)
    return s / (1.0 - s)
