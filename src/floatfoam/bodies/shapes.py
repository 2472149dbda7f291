"""Floating bodies: the memoir's shapes and any closed surface.

Every body lives in its own frame (docs/conventions.md): origin at the geometric centre (the
centre of the bounding box for the primitives; for an STL, its volume's centroid in x and y
and the middle of its height: :func:`floatfoam.bodies.surfaces.centred`), x along the long
axis, z up. A body gives

* ``surface_mesh()``: a closed, outward-oriented triangle mesh (every body);
* ``section_polygon()``: its (y, z) section, counter-clockwise (2D sections only);
* ``contains(point)``: whether a body-frame point is inside.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from floatfoam.bodies.geometry import extrude_polygon, icosphere, mesh_volume, winding_number

SECTION_POINTS = 2048  # polygon vertices of a 2D section: area error ~ (2π²/3)/N² ≈ 2e-6
SPHERE_LEVEL = 5  # icosphere subdivisions: 20480 triangles, volume error ≈ 0.1 %


class Body:
    """Base class; subclasses set ``lo``/``hi`` (bounding box, body frame)."""

    is_section = False
    length: float | None = None
    lo: np.ndarray
    hi: np.ndarray

    @property
    def size(self) -> float:
        return float(np.max(self.hi - self.lo))

    @property
    def keel_z(self) -> float:
        """Height of the keel (lowest point of the upright body) in the body frame."""
        return float(self.lo[2])

    #: the planes x = 0 and y = 0 ("x", "y") the body is mirror symmetric about, for a half
    #: domain in 3D (:func:`floatfoam.plan.kind.half_plane`); none unless a shape says
    mirror_planes: tuple[str, ...] = ()
    #: the body is its own triangles (an STL or an implicit surface): meshers take them as they
    #: are, with prism layers by default (settings.TRIANGLE_LAYERS)
    given_by_triangles = False
    #: an exact solid that takes prism layers when a case asks (meshing.surface3d)
    takes_layers = False

    @property
    def is_axisymmetric(self) -> bool:
        """A body of revolution about its vertical (z) axis (a wedge can hold it)."""
        return False

    @property
    def memoir_family(self) -> tuple | None:
        """Which of Le Barbier's (1817) families the body is, with its parameters:
        ("circle", a) the circular cylinder of radius a, ("conic", n, m) the cylinder on
        y² = n x + m x² (x up from the vertex), ("sphere", a), ("revolution", a, c) the
        ellipsoid of revolution about z of semi-axes a, a, c; None outside them."""
        return None

    def surface_mesh(self, resolution=None):
        raise NotImplementedError

    def volume(self) -> float:
        v, f = self.surface_mesh()
        return mesh_volume(v, f)

    def contains(self, point) -> bool:
        v, f = self.surface_mesh()
        return winding_number(v, f, np.asarray(point, dtype=float)) > 0.5


class SectionBody(Body):
    """A horizontal prism of length L along x with a (y, z) section."""

    is_section = True

    def section_polygon(self, resolution=None) -> np.ndarray:
        raise NotImplementedError

    def surface_mesh(self, resolution=None):
        return extrude_polygon(self.section_polygon(resolution), self.length)

    def section_area(self) -> float:
        y, z = self.section_polygon().T
        return 0.5 * float(np.sum(y * np.roll(z, -1) - np.roll(y, -1) * z))

    def volume(self) -> float:
        return self.section_area() * self.length

    def contains(self, point) -> bool:
        x, y, z = point
        return abs(x) <= self.length / 2 and _inside_polygon(self.section_polygon(), y, z)


class EllipticCylinder(SectionBody):
    """Horizontal cylinder on an ellipse of semi-axes b (half beam, y) and c (half height, z);
    the circle is b = c. In the memoir's form y² = n x + m x², n = 2b²/c, m = −b²/c²."""

    def __init__(self, half_beam: float, half_height: float, length: float):
        self.b, self.c, self.length = half_beam, half_height, length
        self.lo = np.array([-length / 2, -half_beam, -half_height])
        self.hi = -self.lo

    @property
    def memoir_family(self) -> tuple:
        """The circle ("circle", b) when b = c, else the ellipse as a conic ("conic", n, m)."""
        if self.b == self.c:
            return ("circle", self.b)
        return ("conic", 2 * self.b**2 / self.c, -(self.b**2) / self.c**2)

    def section_polygon(self, resolution=None):
        t = np.linspace(0.0, 2 * np.pi, resolution or SECTION_POINTS, endpoint=False)
        return np.column_stack([self.b * np.sin(t), -self.c * np.cos(t)])

    def section_area(self):
        return math.pi * self.b * self.c

    def contains(self, point):
        x, y, z = point
        return abs(x) <= self.length / 2 and (y / self.b) ** 2 + (z / self.c) ** 2 <= 1.0


class ConicCylinder(SectionBody):
    """Horizontal cylinder on the memoir's conic base y² = n x + m x² (x up from the vertex,
    the keel), closed by a flat deck at height h: m = 0 parabola, m > 0 hyperbola, m < 0 an
    ellipse cut below its top (use :class:`EllipticCylinder` for the whole ellipse)."""

    def __init__(self, n: float, m: float, height: float, length: float):
        self.n, self.m, self.h, self.length = n, m, height, length
        widest = height if m >= 0 else min(height, -n / (2 * m))
        self.half_beam = self.half_width(widest)
        self.lo = np.array([-length / 2, -self.half_beam, -height / 2])
        self.hi = np.array([length / 2, self.half_beam, height / 2])

    @property
    def memoir_family(self) -> tuple:
        return ("conic", self.n, self.m)

    def half_width(self, x):
        return np.sqrt(np.maximum(self.n * x + self.m * x * x, 0.0))

    def section_polygon(self, resolution=None):
        k = (resolution or SECTION_POINTS) // 2
        x = self.h * np.linspace(0.0, 1.0, k) ** 2  # dense near the vertex, where w ~ √x
        right = np.column_stack([self.half_width(x), x - self.h / 2])
        left = right[::-1].copy()
        left[:, 0] *= -1
        return np.concatenate([right, left[:-1]])

    def contains(self, point):
        x, y, z = point
        xi = z + self.h / 2
        return abs(x) <= self.length / 2 and 0 <= xi <= self.h and abs(y) <= self.half_width(xi)


class Box(SectionBody):
    """Box section of beam B (y) and height D (z), with an optional bilge radius r."""

    def __init__(self, beam: float, height: float, length: float, bilge_radius: float = 0.0):
        self.beam, self.height, self.length, self.r = beam, height, length, bilge_radius
        self.lo = np.array([-length / 2, -beam / 2, -height / 2])
        self.hi = -self.lo

    def section_polygon(self, resolution=None):
        half_b, half_d, r = self.beam / 2, self.height / 2, self.r
        if r <= 0.0:
            return np.array([[-half_b, -half_d], [half_b, -half_d], [half_b, half_d],
                             [-half_b, half_d]])
        k = max((resolution or SECTION_POINTS) // 4, 4)
        t = np.linspace(0.0, np.pi / 2, k)
        right = np.column_stack([half_b - r + r * np.sin(t), -half_d + r - r * np.cos(t)])
        left = np.column_stack([-half_b + r - r * np.cos(t), -half_d + r - r * np.sin(t)])
        corners = np.array([[half_b, half_d], [-half_b, half_d]])
        return np.concatenate([right, corners, left])

    def section_area(self):
        return self.beam * self.height - (4 - math.pi) * self.r**2 / 2

    def contains(self, point):
        x, y, z = point
        half_b, half_d, r = self.beam / 2, self.height / 2, self.r
        if abs(x) > self.length / 2 or abs(y) > half_b or abs(z) > half_d:
            return False
        dy, dz = abs(y) - (half_b - r), (z + half_d) - r
        return not (dy > 0 and dz < 0 and dy * dy + dz * dz > r * r)


class Ellipsoid(Body):
    """Triaxial ellipsoid of semi-axes (a_x, a_y, a_z); the sphere has them equal."""

    mirror_planes = ("x", "y")
    takes_layers = True

    @property
    def is_axisymmetric(self) -> bool:
        return math.isclose(self.axes[0], self.axes[1], rel_tol=1e-12)

    @property
    def memoir_family(self) -> tuple | None:
        """("sphere", a) or ("revolution", a, c) when a_x = a_y (exactly), else None."""
        if self.axes[0] != self.axes[1]:
            return None
        a, c = self.axes[0], self.axes[2]
        return ("sphere", a) if a == c else ("revolution", a, c)

    def __init__(self, semi_axes):
        self.axes = np.asarray(semi_axes, dtype=float)
        self.lo, self.hi = -self.axes, self.axes.copy()

    def surface_mesh(self, resolution=None):
        v, f = icosphere(SPHERE_LEVEL if resolution is None else resolution)
        return v * self.axes, f

    def volume(self):
        return 4.0 / 3.0 * math.pi * float(np.prod(self.axes))

    def contains(self, point):
        return float(np.sum((np.asarray(point) / self.axes) ** 2)) <= 1.0


class VerticalCylinder(Body):
    """Upright circular cylinder of radius r and height h about the vertical z axis, flat
    bottom and top (a buoy, a spar): a body of revolution, so a wedge holds its heave."""

    mirror_planes = ("x", "y")
    is_axisymmetric = True

    #: facets round the circle of the triangles the theory's numeric hydrostatics and the
    #: potential flow take off the upright (the waterplane's area 0.0025 % short)
    SEGMENTS = 512

    def __init__(self, radius: float, height: float):
        self.r, self.h = float(radius), float(height)
        self.lo = np.array([-self.r, -self.r, -self.h / 2])
        self.hi = np.array([self.r, self.r, self.h / 2])

    def surface_mesh(self, resolution=None):
        n = self.SEGMENTS if resolution is None else int(resolution)
        angle = 2.0 * math.pi * np.arange(n) / n
        circle = self.r * np.column_stack([np.cos(angle), np.sin(angle)])  # CCW from +z
        v, f = extrude_polygon(circle, self.h)  # along x: (axis, x, y) → (x, y, z), a
        return v[:, [1, 2, 0]].copy(), f  # cyclic swap, the faces still outwards

    def volume(self) -> float:
        return math.pi * self.r**2 * self.h

    def contains(self, point) -> bool:
        x, y, z = point
        return x * x + y * y <= self.r**2 and abs(z) <= self.h / 2


class MeshBody(Body):
    """Any closed body given as a triangle mesh (from an STL or an implicit surface, whose
    ``expression`` F(x, y, z) it then keeps)."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray, expression: str | None = None,
                 file_origin=None):
        self.vertices, self.faces, self.expression = vertices, faces, expression
        self.lo, self.hi = vertices.min(axis=0), vertices.max(axis=0)
        #: where the body frame's origin lies in its file's coordinates, for a body moved
        #: there (:func:`floatfoam.bodies.surfaces.centred`); None: the file's own origin
        self.file_origin = file_origin

    given_by_triangles = True
    takes_layers = True

    def surface_mesh(self, resolution=None):
        return self.vertices, self.faces

    def moved(self, shift) -> MeshBody:
        """The same body with every vertex moved by ``shift`` (m): its frame's origin at
        −``shift`` in the file's coordinates (``file_origin``)."""
        if self.expression is not None:  # F(x, y, z) is in the unmoved coordinates
            raise ValueError("an implicit body is not moved: its expression's frame is its own")
        shift = np.asarray(shift, dtype=float)
        return MeshBody(self.vertices + shift, self.faces, file_origin=-shift)

    @cached_property
    def pieces(self) -> int:
        """How many separate closed pieces the surface has (two hulls: 2)."""
        from floatfoam.bodies.geometry import outward_pieces

        return int(outward_pieces(self.vertices, self.faces)[1].max()) + 1

    @cached_property
    def meridian(self) -> np.ndarray | None:
        """The meridian (r, z) of a body of revolution about z, keel to top, each end on the
        axis; None when the triangles are not one (:func:`floatfoam.bodies.revolution.meridian`)."""
        from floatfoam.bodies.revolution import meridian

        return meridian(self.vertices, self.faces)

    @property
    def is_axisymmetric(self) -> bool:
        return self.meridian is not None

    @cached_property
    def mirror_planes(self) -> tuple[str, ...]:
        """The planes x = 0 and y = 0 ("x", "y") the body is mirror symmetric about
        (:func:`floatfoam.bodies.mirror.mirror_planes`)."""
        from floatfoam.bodies.mirror import mirror_planes

        return mirror_planes(self.vertices, self.faces, self.expression)


def _inside_polygon(poly: np.ndarray, y: float, z: float) -> bool:
    """Even-odd rule point-in-polygon test."""
    y0, z0 = poly[:, 0], poly[:, 1]
    y1, z1 = np.roll(y0, -1), np.roll(z0, -1)
    crosses = (z0 > z) != (z1 > z)
    with np.errstate(divide="ignore", invalid="ignore"):
        y_cross = y0 + (z - z0) * (y1 - y0) / (z1 - z0)
    return bool(np.count_nonzero(crosses & (y < y_cross)) % 2)
