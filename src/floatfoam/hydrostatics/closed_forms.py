"""Closed-form hydrostatics of the memoir's bodies.

* Ellipses (the circle included) and ellipsoids (the sphere included) at **any** attitude: an
  ellipsoid is the image of the unit ball under D = diag(semi-axes), a plane stays a plane, so
  the immersed part is the image of a spherical cap (a circular segment in 2D). Volumes scale
  by det D, centroids map through D, and the waterplane is the image of the cap's base circle.
* Horizontal cylinders on the conic base y² = n·x + m·x² (x up from the vertex, Le Barbier
  1817) and boxes with a bilge radius, **upright**, from the integrals of the half-width.
* The vertical circular cylinder, **upright**: a disc's waterplane over a prism.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from floatfoam.bodies import shapes
from floatfoam.bodies.geometry import rotation
from floatfoam.hydrostatics.immersed_part import Immersed, nothing_immersed


@functools.singledispatch
def for_body(body, z_c: float, heel: float, trim: float) -> Immersed | None:
    """The exact immersed part of ``body`` at this attitude where a closed form is known,
    else None: elliptic cylinders at any heel (no trim), conic cylinders, boxes and vertical
    cylinders upright, ellipsoids at any attitude. Each shape registers its own; other bodies
    have none."""
    return None


@for_body.register(shapes.EllipticCylinder)
def _elliptic_cylinder(body, z_c: float, heel: float, trim: float) -> Immersed | None:
    return None if trim != 0.0 else ellipse_section(body.b, body.c, body.length, z_c, heel)


@for_body.register(shapes.Ellipsoid)
def _ellipsoid(body, z_c: float, heel: float, trim: float) -> Immersed | None:
    return ellipsoid(body.axes, z_c, heel, trim)


@for_body.register(shapes.ConicCylinder)
def _conic_cylinder(body, z_c: float, heel: float, trim: float) -> Immersed | None:
    if heel != 0.0 or trim != 0.0:
        return None
    depth = min(max(body.h / 2 - z_c, 0.0), body.h)
    i0, i1, w = conic_integrals(body.n, body.m, depth)
    return _upright(body, i0, i1, w, full=depth >= body.h, z_c=z_c)


@for_body.register(shapes.Box)
def _box(body, z_c: float, heel: float, trim: float) -> Immersed | None:
    if heel != 0.0 or trim != 0.0:
        return None
    depth = min(max(body.height / 2 - z_c, 0.0), body.height)
    i0, i1, w = box_integrals(body.beam, body.r, depth)
    return _upright(body, i0, i1, w, full=depth >= body.height, z_c=z_c)


@for_body.register(shapes.VerticalCylinder)
def _vertical_cylinder(body, z_c: float, heel: float, trim: float) -> Immersed | None:
    if heel != 0.0 or trim != 0.0:
        return None
    depth = min(max(body.h / 2 - z_c, 0.0), body.h)
    if depth <= 0.0:
        return nothing_immersed(exact=True)
    area = math.pi * body.r**2
    inertia = math.pi * body.r**4 / 4.0
    waterplane = depth < body.h  # none when fully submerged
    return Immersed(
        volume=area * depth,
        centroid=np.array([0.0, 0.0, z_c - body.h / 2 + depth / 2]),
        waterplane_area=area if waterplane else 0.0,
        waterplane_centroid=np.zeros(2),
        waterplane_inertia=np.array([inertia, inertia, 0.0]) if waterplane else np.zeros(3),
        exact=True,
    )


def _upright(body, i0: float, i1: float, w: float, *, full: bool, z_c: float) -> Immersed:
    """The upright prism of ``body`` from its half-section integrals (no waterplane when
    fully submerged)."""
    if full:
        w = 0.0
    return upright_section(2 * i0, 2 * i1, w, body.length, body.keel_z, z_c)


def ellipse_section(half_beam: float, half_height: float, length: float, z_c: float,
                    heel: float) -> Immersed:
    """Prism of elliptic section (semi-axes b along y, c along z, centre at the origin),
    heeled by ``heel`` about x, centre at height z_c.

    The wet region Z = sinφ·y + cosφ·z + z_c < 0 is, with (y, z) = (b u, c v), the part
    n·u < s of the unit disk with n = v/|v|, v = (b sinφ, c cosφ), s = −z_c/|v|. That circular
    segment has area α = arccos(−s) + s√(1−s²) and centroid −n·(2/3)(1−s²)^{3/2}/α.
    """
    d = np.array([half_beam, half_height])
    v = d * np.array([math.sin(heel), math.cos(heel)])
    r = float(np.linalg.norm(v))
    n = v / r
    s = min(max(-z_c / r, -1.0), 1.0)
    area_u = math.acos(-s) + s * math.sqrt(1.0 - s * s)
    if area_u <= 0.0:
        return nothing_immersed(exact=True)
    cen_u = -n * (2.0 / 3.0) * (1.0 - s * s) ** 1.5 / area_u
    rot = np.array([[math.cos(heel), -math.sin(heel)], [math.sin(heel), math.cos(heel)]])
    centroid = rot @ (d * cen_u) + np.array([0.0, z_c])
    half_chord = math.sqrt(1.0 - s * s)
    ends = [rot @ (d * (s * n + t * half_chord * np.array([-n[1], n[0]]))) for t in (-1, 1)]
    y_lo, y_hi = sorted(e[0] for e in ends)
    width = y_hi - y_lo
    return Immersed(
        volume=area_u * half_beam * half_height * length,
        centroid=np.array([0.0, centroid[0], centroid[1]]),
        waterplane_area=width * length,
        waterplane_centroid=np.array([0.0, 0.5 * (y_lo + y_hi)]),
        waterplane_inertia=np.array([width**3 * length / 12.0, width * length**3 / 12.0, 0.0]),
        exact=True,
    )


def ellipsoid(semi_axes, z_c: float, heel: float, trim: float) -> Immersed:
    """Ellipsoid of semi-axes (a_x, a_y, a_z) centred at the body origin.

    In the unit ball (p = D u) the wet part is the cap n·u < s, n = v/|v|, v = D Rᵀ e_z,
    s = −z_c/|v|, of height h = 1 + s: volume π h²(3 − h)/3, centroid −n·3(2 − h)²/(4(3 − h)).
    The waterplane is the image of the base circle (centre s n, radius ρ = √(1 − s²)): an
    ellipse with conjugate semi-diameters P_i = ρ R D e_i, area π|P₁ × P₂| and second-moment
    tensor (area/4)(P₁P₁ᵀ + P₂P₂ᵀ).
    """
    d = np.asarray(semi_axes, dtype=float)
    rot = rotation(heel, trim)
    v = d * rot[2, :]
    r = float(np.linalg.norm(v))
    n = v / r
    s = min(max(-z_c / r, -1.0), 1.0)
    h = 1.0 + s
    vol_u = math.pi * h * h * (3.0 - h) / 3.0
    if vol_u <= 0.0:
        return nothing_immersed(exact=True)
    cen_u = -n * 3.0 * (2.0 - h) ** 2 / (4.0 * (3.0 - h))
    centroid = rot @ (d * cen_u) + np.array([0.0, 0.0, z_c])
    rho = math.sqrt(max(1.0 - s * s, 0.0))
    e1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    p1, p2 = (rho * (rot @ (d * e)) for e in (e1, e2))
    area = math.pi * float(np.linalg.norm(np.cross(p1, p2)))
    tensor = area / 4.0 * (np.outer(p1, p1) + np.outer(p2, p2))
    centre = rot @ (d * s * n) + np.array([0.0, 0.0, z_c])
    return Immersed(
        volume=vol_u * float(np.prod(d)),
        centroid=centroid,
        waterplane_area=area,
        waterplane_centroid=centre[:2],
        waterplane_inertia=np.array([tensor[1, 1], tensor[0, 0], tensor[0, 1]]),
        exact=True,
    )


def conic_integrals(n: float, m: float, depth: float) -> tuple[float, float, float]:
    """∫₀ᵈ w dx, ∫₀ᵈ x·w dx and w(d) for the half-width w(x) = √(n x + m x²).

    m = 0 (parabola): (2/3)√n d^{3/2}, (2/5)√n d^{5/2}. m ≠ 0: with u = x + n/(2m),
    w² = m(u² − c²), c = n/(2m), the standard integrals of √(u² − c²) (hyperbola, m > 0) or
    √(c² − u²) (ellipse, m < 0).
    """
    d = depth
    w_d = math.sqrt(max(n * d + m * d * d, 0.0))
    if d <= 0.0:
        return 0.0, 0.0, 0.0
    if m == 0.0:
        return (2 / 3) * math.sqrt(n) * d**1.5, (2 / 5) * math.sqrt(n) * d**2.5, w_d
    c = n / (2.0 * m)  # u = x + c
    r2 = c * c
    if m > 0.0:
        def f0(u):
            root = math.sqrt(max(u * u - r2, 0.0))
            return 0.5 * (u * root - r2 * math.log(u + root))

        def f1(u):
            return max(u * u - r2, 0.0) ** 1.5 / 3.0
    else:
        radius = abs(c)

        def f0(u):
            root = math.sqrt(max(r2 - u * u, 0.0))
            return 0.5 * (u * root + r2 * math.asin(max(min(u / radius, 1.0), -1.0)))

        def f1(u):
            return -max(r2 - u * u, 0.0) ** 1.5 / 3.0
    u0, u1 = c, d + c
    k = math.sqrt(abs(m))
    i0 = k * (f0(u1) - f0(u0))
    i1 = k * (f1(u1) - f1(u0)) - c * i0  # ∫ x w = ∫ (u − c) w
    return i0, i1, w_d


def upright_section(area: float, first_moment: float, half_width: float, length: float,
                    keel_z: float, z_c: float) -> Immersed:
    """Upright prism from a section's immersed area and first moment about the keel."""
    if area <= 0.0:
        return nothing_immersed(exact=True)
    width = 2.0 * half_width
    return Immersed(
        volume=area * length,
        centroid=np.array([0.0, 0.0, z_c + keel_z + first_moment / area]),
        waterplane_area=width * length,
        waterplane_centroid=np.zeros(2),
        waterplane_inertia=np.array([width**3 * length / 12.0, width * length**3 / 12.0, 0.0]),
        exact=True,
    )


def box_integrals(beam: float, bilge_radius: float, depth: float) -> tuple[float, float, float]:
    """Half-section integrals ∫₀ᵈ w dx, ∫₀ᵈ x w dx and w(d) of a box of beam B with bilge
    radius r: w(x) = B/2 − r + √(r² − (r − x)²) for x < r, B/2 above."""
    r, half = bilge_radius, beam / 2.0
    lower = min(depth, r)
    flat = half - r
    i0 = flat * lower
    i1 = flat * lower**2 / 2.0
    if r > 0.0 and lower > 0.0:
        # √(r² − u²) with u = r − x, from u = r − lower to u = r.
        def g0(u):
            root = math.sqrt(max(r * r - u * u, 0.0))
            return 0.5 * (u * root + r * r * math.asin(min(u / r, 1.0)))

        def g1(u):
            return -max(r * r - u * u, 0.0) ** 1.5 / 3.0

        a, b = r - lower, r
        j0 = g0(b) - g0(a)
        j1 = g1(b) - g1(a)  # ∫ u √ du
        i0 += j0
        i1 += r * j0 - j1  # x = r − u
    upper = max(depth - r, 0.0)
    i0 += half * upper
    i1 += half * (depth**2 - min(depth, r) ** 2) / 2.0
    if depth >= r:
        w = half
    else:
        w = flat + math.sqrt(max(r * r - (r - depth) ** 2, 0.0))
    return i0, i1, w

