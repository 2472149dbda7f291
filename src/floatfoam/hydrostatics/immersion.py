"""Hydrostatics engine: immersed volume, centre of buoyancy and waterplane of any body.

Two paths give the same quantities:

* the **closed forms** of the memoir's bodies (see :mod:`floatfoam.hydrostatics.closed_forms`);
* a **numeric** path for any body: a polygon clipped at the free surface for 2D sections, a
  closed triangle mesh clipped at the free surface for 3D bodies.

The numeric path never builds the waterplane cap. It uses the divergence theorem with vector
fields that vanish on the plane z = 0, so the wetted part of the surface is enough:

    V = ∫ z n_z dS,  ∫ x dV = ∫ x z n_z dS,  ∫ y dV = ∫ y z n_z dS,  ∫ z dV = ∫ z²/2 n_z dS,

and, since a divergence-free field f(x, y) e_z has zero flux through a closed surface, the
waterplane moments are  ∫_wp f dA = −∫_wet f n_z dS  for f = 1, x, y, x², y², xy.
All integrands are at most quadratic on each flat facet, so the edge-midpoint rule is exact and
the only error is the discretisation of the body's surface.
"""

from __future__ import annotations

import numpy as np

from floatfoam.bodies.geometry import to_earth
from floatfoam.hydrostatics import closed_forms
from floatfoam.hydrostatics.immersed_part import Immersed, nothing_immersed


def immersed(body, z_c: float, heel: float = 0.0, trim: float = 0.0, *, method: str = "auto",
             resolution: int | None = None) -> Immersed:
    """Immersed volume, centre of buoyancy and waterplane of ``body`` at an attitude.

    Parameters
    ----------
    body : a :class:`floatfoam.bodies.shapes.Body`
    z_c : height of the body-frame origin (geometric centre) above the free surface, m
    heel, trim : rotations about x then y, radians (docs/conventions.md)
    method : "auto" (closed form when the body has one at this attitude, else numeric),
        "closed" (raise if none) or "numeric"
    resolution : numeric resolution (polygon vertices or mesh level), body default if None
    """
    if method in ("auto", "closed"):
        exact = closed_forms.for_body(body, z_c, heel, trim)
        if exact is not None:
            return exact
        if method == "closed":
            raise ValueError(f"{type(body).__name__} has no closed form at this attitude")
    if body.is_section and trim == 0.0:
        return section_immersed(body.section_polygon(resolution), body.length, z_c, heel)
    vertices, faces = body.surface_mesh(resolution)
    return mesh_immersed(vertices, faces, z_c, heel, trim)


def section_immersed(polygon: np.ndarray, length: float, z_c: float, heel: float) -> Immersed:
    """Immersed part of a prism of CCW section ``polygon`` (y, z) and length L, heeled by
    ``heel`` about x, by Green's theorem on the wetted part of the section's boundary:

        A = ∮ Y dZ,  ∫ Y dA = ∮ Y²/2 dZ,  ∫ Z dA = ∮ Y Z dZ,  (all zero on Z = 0),
        waterline moments ∫ Y^k dY = Σ_wet (Y_q^{k+1} − Y_p^{k+1}) / (k + 1).
    """
    c, s = np.cos(heel), np.sin(heel)
    y = c * polygon[:, 0] - s * polygon[:, 1]
    z = s * polygon[:, 0] + c * polygon[:, 1] + z_c
    p = np.column_stack([y, z])
    q = np.roll(p, -1, axis=0)
    p, q = _clip_segments(p, q)
    dz = q[:, 1] - p[:, 1]
    m = 0.5 * (p + q)
    # Simpson's rule is exact for the quadratic integrands along each straight edge.
    def simpson(f):
        return float(((f(p) + 4.0 * f(m) + f(q)) / 6.0 * dz).sum())

    area = simpson(lambda r: r[:, 0])
    if area <= 0.0:
        return nothing_immersed()
    y_b = simpson(lambda r: 0.5 * r[:, 0] ** 2) / area
    z_b = simpson(lambda r: r[:, 0] * r[:, 1]) / area
    width = float((q[:, 0] - p[:, 0]).sum())
    first = float((q[:, 0] ** 2 - p[:, 0] ** 2).sum() / 2.0)
    second = float((q[:, 0] ** 3 - p[:, 0] ** 3).sum() / 3.0)
    y_f = first / width if width > 0 else 0.0
    i_xx = (second - width * y_f**2) * length
    i_yy = width * length**3 / 12.0
    return Immersed(
        volume=area * length,
        centroid=np.array([0.0, y_b, z_b]),
        waterplane_area=width * length,
        waterplane_centroid=np.array([0.0, y_f]),
        waterplane_inertia=np.array([i_xx, i_yy, 0.0]),
    )


def _clip_segments(p: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Keep the parts of segments p→q that lie below z = 0 (orientation kept)."""
    zp, zq = p[:, 1], q[:, 1]
    below_p, below_q = zp < 0.0, zq < 0.0
    keep = below_p | below_q
    p, q, zp, zq = p[keep], q[keep], zp[keep], zq[keep]
    below_p, below_q = below_p[keep], below_q[keep]
    crossing = below_p != below_q
    t = np.where(crossing, zp / np.where(crossing, zp - zq, 1.0), 0.0)
    cut = p + t[:, None] * (q - p)
    cut[:, 1] = np.where(crossing, 0.0, cut[:, 1])
    p = np.where((crossing & ~below_p)[:, None], cut, p)
    q = np.where((crossing & ~below_q)[:, None], cut, q)
    return p, q


def mesh_immersed(vertices: np.ndarray, faces: np.ndarray, z_c: float, heel: float,
                  trim: float) -> Immersed:
    """Immersed part of a closed, outward-oriented triangle mesh (body frame) at an attitude,
    by the divergence theorem on the wetted triangles (see the module docstring)."""
    tri = to_earth(vertices, z_c, heel, trim)[faces]
    wet = clip_triangles(tri)
    if len(wet) == 0:
        return nothing_immersed()
    a, b, c = wet[:, 0], wet[:, 1], wet[:, 2]
    n_z = 0.5 * np.cross(b - a, c - a)[:, 2]  # z component of the area-weighted normal
    mids = (0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a))

    def surface(f):  # ∫ f n_z dS, exact for quadratic f (edge-midpoint rule)
        return float((n_z * sum(f(m) for m in mids) / 3.0).sum())

    volume = surface(lambda r: r[:, 2])
    if volume <= 0.0:
        return nothing_immersed()
    centroid = np.array([
        surface(lambda r: r[:, 0] * r[:, 2]),
        surface(lambda r: r[:, 1] * r[:, 2]),
        surface(lambda r: 0.5 * r[:, 2] ** 2),
    ]) / volume
    area = -surface(lambda r: np.ones(len(r)))
    x_f = -surface(lambda r: r[:, 0]) / area if area > 0 else 0.0
    y_f = -surface(lambda r: r[:, 1]) / area if area > 0 else 0.0
    i_xx = -surface(lambda r: r[:, 1] ** 2) - area * y_f**2
    i_yy = -surface(lambda r: r[:, 0] ** 2) - area * x_f**2
    i_xy = -surface(lambda r: r[:, 0] * r[:, 1]) - area * x_f * y_f
    return Immersed(volume, centroid, area, np.array([x_f, y_f]), np.array([i_xx, i_yy, i_xy]))


def clip_triangles(tri: np.ndarray) -> np.ndarray:
    """Parts of triangles (T, 3, 3) below z = 0, as triangles with the same orientation."""
    below = tri[:, :, 2] < 0.0
    count = below.sum(axis=1)
    out = [tri[count == 3]]
    for n_below, lone_is_below in ((1, True), (2, False)):
        sel = tri[count == n_below]
        if len(sel) == 0:
            continue
        flags = below[count == n_below]
        # Index of the vertex that differs from the other two; rotating the vertex order
        # cyclically keeps the orientation.
        lone = np.argmax(flags if lone_is_below else ~flags, axis=1)
        order = (lone[:, None] + np.arange(3)[None, :]) % 3
        v = np.take_along_axis(sel, order[:, :, None], axis=1)
        v0, v1, v2 = v[:, 0], v[:, 1], v[:, 2]
        p01 = _cut(v0, v1)
        p02 = _cut(v0, v2)
        if lone_is_below:
            out.append(np.stack([v0, p01, p02], axis=1))
        else:
            out.append(np.stack([p01, v1, v2], axis=1))
            out.append(np.stack([p01, v2, p02], axis=1))
    return np.concatenate(out) if out else np.empty((0, 3, 3))


def _cut(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    t = a[:, 2] / (a[:, 2] - b[:, 2])
    point = a + t[:, None] * (b - a)
    point[:, 2] = 0.0
    return point

