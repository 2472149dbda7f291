"""2D and axisymmetric fluid domains: a block layout in one plane, one cell thick.

The plane is (u, v) = (y, z) for a 2D section, extruded one cell along x (patches
``frontAndBack``, OpenFOAM ``empty``); it is (u, v) = (r, z) for a body of revolution about z,
revolved ±θ/2 about the z axis in one cell (patches ``wedge0``/``wedge1``, OpenFOAM ``wedge``).

Blocks (u columns × v rows)::

        air     | graded ↑      | graded ↑      | graded ↑
        core    | graded ←, h ↕ | body (hole)   | graded →, h ↕
        water   | graded ↓      | graded ↓      | graded ↓

The core block holds the body's polygon (the same nodes as the discrete body of the level,
:mod:`floatfoam.meshing.body_surface`) and is meshed with unstructured quadrangles of size h;
it spans the body with a margin and the free-surface band |z| ≤ b. The other blocks are
structured (transfinite) quadrangles: size h across the core's rows and columns, growing
geometrically (ratio ≤ ``growth``) away from them, so the free-surface band keeps its vertical
size h out to the tank's ends while the cells stretch horizontally into a numerical beach.
Gmsh's smoother is kept off the structured blocks (it would skew their grading: 47° of
non-orthogonality instead of 0°) and on for the core.

A wedge has the axis on its left, then a strip one cell wide along the axis (so that every
cell touching the axis does so by an edge and revolves into a prism, never into a degenerate
hexahedron), the core's column and the far column.

Every level refines all counts by r at the same spacing function (:func:`divisions`), so the
cell count grows by r² per level. Patches: ``body``, ``bottom``, ``atmosphere`` (top),
``sides`` (the tank's ends; a wedge's outer cylinder), ``frontAndBack`` or ``wedge0``/``wedge1``,
and the volume ``fluid``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from floatfoam import gmshio
from floatfoam.errors import InputError
from floatfoam.meshing import body_surface
from floatfoam.meshing.levels import MeshSpec
from floatfoam.tank import Pose, Tank

WEDGE_ANGLE = 5.0  # degrees, the usual OpenFOAM wedge (≤ 5° keeps the wedge cells near-square)


def progression(length: float, first: float, growth: float) -> tuple[int, float]:
    """Cells n and ratio q ≤ ``growth`` of a geometric progression whose first cell is
    ``first`` and which fills ``length``: first (q^n − 1)/(q − 1) = length."""
    if length <= first * growth:
        return max(1, round(length / first)), 1.0
    n = math.ceil(math.log(1.0 + length * (growth - 1.0) / first) / math.log(growth))
    if n * first >= length:
        return max(1, round(length / first)), 1.0

    def excess(q):
        return first * (q**n - 1.0) / (q - 1.0) - length

    return n, brentq(excess, 1.0 + 1e-12, growth, xtol=1e-14)


@dataclass(frozen=True)
class Division:
    """One column or row of blocks: extent [lo, hi], cells, progression ratio q (≥ 1, cells
    growing away from the core), and whether it lies before the core (q runs backwards)."""

    lo: float
    hi: float
    cells: int
    ratio: float
    before_core: bool

    def gmsh_coef(self) -> float:
        """gmsh's Progression coefficient for a curve running from lo to hi."""
        return 1.0 / self.ratio if self.before_core else self.ratio


def divisions(edges: list[float], core: int, spec: MeshSpec) -> list[Division]:
    """Divisions between the breakpoints ``edges``; ``core`` is the index of the core's
    division. Coarse counts from the coarse cell size, then refined by r at constant spacing
    function (n → round(n r^k), q → q^(n₀/n))."""
    coarse_h = spec.body_size * spec.ratio**spec.index
    out = []
    for i, (lo, hi) in enumerate(zip(edges[:-1], edges[1:], strict=True)):
        if i == core:
            n0, q0 = max(1, round((hi - lo) / coarse_h)), 1.0
        else:
            n0, q0 = progression(hi - lo, coarse_h, spec.growth)
        n = spec.refine(n0)
        out.append(Division(lo, hi, n, q0 ** (n0 / n), i < core))
    return out


def core_bounds(radius: float, where: Pose, spec: MeshSpec, tank: Tank) -> tuple[float, ...]:
    """The core block: half-width c and rows [v_lo, v_hi] around the body (any heel, swayed
    by y_c) and the free-surface band; checked against the tank."""
    c = radius + abs(where.y_c) + spec.margin
    v_lo = min(where.z_c - radius - spec.margin, -tank.band)
    v_hi = max(where.z_c + radius + spec.margin, tank.band)
    checks = [("half_length", tank.half_length, c), ("depth", tank.depth, -v_lo),
              ("air_height", tank.air_height, v_hi)]
    for key, value, need in checks:
        if value <= need + spec.body_size:
            raise InputError(f"domain.{key} = {value:g} m leaves no room around the body (its "
                             f"centre at z = {where.z_c:+.4g} m where it is meshed) and the "
                             f"free-surface band (±{tank.band:.4g} m: a quarter of the body's "
                             f"smallest width and the [release] offsets); valid is > "
                             f"{need + spec.body_size:.4g} m, or a smaller release")
    return c, v_lo, v_hi


def planar_domain(case, spec: MeshSpec, tank: Tank, where: Pose, kind: str,
                  path: Path) -> dict:
    """Mesh the 2D (``kind`` "2d") or wedge (``kind`` "wedge") domain of ``case`` at a pose and
    write it to ``path`` (MSH 2.2); returns a summary (see :func:`summary`)."""
    body = case.body
    if kind == "2d":
        polygon = body_surface.place_section(body_surface.section_polygon(body, spec), where)
        polygon = even_polygon(polygon)
    else:
        wedge_ready(case, where)
        polygon = body_surface.meridian_polyline(body, spec) + [0.0, where.z_c]
    radius = float(np.max(np.hypot(*(polygon - [where.y_c, where.z_c]).T)))
    with gmshio.session(f"{case.name}-{kind}") as gmsh:
        groups = _build(gmsh, polygon, radius, spec, tank, where, kind)
        gmshio.write_msh22(path)
        return summary(gmsh, groups, path)


def even_polygon(polygon: np.ndarray) -> np.ndarray:
    """The polygon with an even number of edges: a quadrangle mesh of the core needs an even
    number of boundary edges (its outer rectangle has an even number). When odd, a node is added
    in the middle of the longest edge: the polygon, hence the discrete body, is unchanged."""
    if len(polygon) % 2 == 0:
        return polygon
    lengths = np.linalg.norm(np.roll(polygon, -1, axis=0) - polygon, axis=1)
    k = int(np.argmax(lengths))
    middle = 0.5 * (polygon[k] + polygon[(k + 1) % len(polygon)])
    return np.insert(polygon, k + 1, middle, axis=0)


def summary(gmsh, groups: dict, path: Path) -> dict:
    """Cells by type, their total, the patches with their face counts, and the file."""
    cells = gmshio.element_counts(3)
    patches = {}
    for name, (dim, tags) in groups.items():
        if dim == 2:
            patches[name] = sum(len(elements) for tag in tags
                                for elements in gmsh.model.mesh.getElements(2, tag)[1])
    return {"path": str(path), "cells": sum(cells.values()), "cell_types": cells,
            "patches": patches}


class Sketch:
    """Points, lines and blocks in the mesh plane, with their transfinite constraints, applied
    after the OpenCASCADE model is synchronised. ``place(u, v)`` gives a point's (x, y, z)."""

    def __init__(self, occ, place):
        self.occ, self.place = occ, place
        self.curves: dict[int, tuple[int, float]] = {}
        self.blocks: list[int] = []

    def point(self, u: float, v: float) -> int:
        return self.occ.addPoint(*self.place(u, v))

    def line(self, start: int, end: int, cells: int | None = None, coef: float = 1.0) -> int:
        """A straight line; ``cells`` (with a Progression ``coef``) fixes its 1D mesh."""
        tag = self.occ.addLine(start, end)
        if cells is not None:
            self.curves[tag] = (cells, coef)
        return tag

    def block(self, edges: list[int]) -> int:
        """A structured block bounded by four lines (in loop order)."""
        tag = self.occ.addPlaneSurface([self.occ.addCurveLoop(edges)])
        self.blocks.append(tag)
        return tag

    def apply(self, gmsh) -> None:
        for tag, (cells, coef) in self.curves.items():
            gmsh.model.mesh.setTransfiniteCurve(tag, cells + 1, "Progression", coef)
        for tag in self.blocks:
            gmsh.model.mesh.setTransfiniteSurface(tag)
            gmsh.model.mesh.setRecombine(2, tag)
            gmsh.model.mesh.setSmoothing(2, tag, 0)  # an elliptic smoother skews the grading


def _build(gmsh, polygon, radius, spec, tank, where, kind) -> dict:
    """Blocks, core, mesh and physical groups in the open session."""
    c, v_lo, v_hi = core_bounds(radius, where, spec, tank)
    rows = divisions([-tank.depth, v_lo, v_hi, tank.air_height], 1, spec)
    occ = gmsh.model.occ
    if kind == "2d":
        x0 = -tank.thickness / 2
        sketch = Sketch(occ, lambda u, v: (x0, u, v))
        core = _layout_2d(sketch, polygon, c, rows, spec, tank)
    else:
        half = math.radians(WEDGE_ANGLE) / 2  # the plane of the wedge's first side, at −θ/2
        sketch = Sketch(occ, lambda u, v: (u * math.cos(half), -u * math.sin(half), v))
        core = _layout_wedge(sketch, polygon, c, rows, spec, tank)
    occ.synchronize()
    sketch.apply(gmsh)
    gmsh.model.mesh.setRecombine(2, core)
    _quad_options(gmsh, spec)
    gmsh.model.mesh.generate(2)
    surfaces = [(2, tag) for tag in [*sketch.blocks, core]]
    if kind == "2d":
        out = occ.extrude(surfaces, tank.thickness, 0.0, 0.0, numElements=[1], recombine=True)
    else:
        out = occ.revolve(surfaces, 0, 0, 0, 0, 0, 1, math.radians(WEDGE_ANGLE),
                          numElements=[1], recombine=True)
    occ.synchronize()
    gmsh.model.mesh.generate(3)
    return _physical_groups(gmsh, surfaces, out, tank, kind)


def _layout_2d(sketch: Sketch, polygon, c, rows, spec, tank) -> int:
    """3 × 3 blocks in (y, z); the middle one is the core with the body's polygon as a hole.
    Returns the core surface."""
    cols = divisions([-tank.half_length, -c, c, tank.half_length], 1, spec)
    us = [cols[0].lo] + [col.hi for col in cols]
    vs = [rows[0].lo] + [row.hi for row in rows]
    grid = [[sketch.point(u, v) for v in vs] for u in us]
    horizontal = [[sketch.line(grid[i][j], grid[i + 1][j], col.cells, col.gmsh_coef())
                   for j in range(4)] for i, col in enumerate(cols)]
    vertical = [[sketch.line(grid[i][j], grid[i][j + 1], row.cells, row.gmsh_coef())
                 for j, row in enumerate(rows)] for i in range(4)]
    for i in range(3):
        for j in range(3):
            if (i, j) != (1, 1):
                sketch.block([horizontal[i][j], vertical[i + 1][j], horizontal[i][j + 1],
                              vertical[i][j]])
    nodes = [sketch.point(u, v) for u, v in polygon]
    hole = [sketch.line(nodes[k], nodes[(k + 1) % len(nodes)], 1) for k in range(len(nodes))]
    outer = sketch.occ.addCurveLoop([horizontal[1][1], vertical[2][1], horizontal[1][2],
                                     vertical[1][1]])
    return sketch.occ.addPlaneSurface([outer, sketch.occ.addCurveLoop(hole)])


def _layout_wedge(sketch: Sketch, polyline, c, rows, spec, tank) -> int:
    """Blocks in (r, z) for a wedge: a strip one cell wide along the axis (below the keel and
    above the top of the body it is bounded by the body's first and last edges, so that every
    cell touching the axis does so by an edge and revolves into a prism), the core column and
    the far column. Returns the core surface (which does not touch the axis)."""
    keel, top = polyline[0][1], polyline[-1][1]
    w_lo, w_hi = polyline[1][0], polyline[-2][0]  # strip widths below and above the body
    v = [rows[0].lo] + [row.hi for row in rows]
    far = divisions([c, tank.half_length], -1, spec)[0]
    core_lo = divisions([w_lo, c], 0, spec)[0]
    core_hi = divisions([w_hi, c], 0, spec)[0]
    n_keel = max(1, round((keel - v[1]) / spec.body_size))
    n_top = max(1, round((v[2] - top) / spec.body_size))
    segments = len(polyline) - 1
    if (core_lo.cells + rows[1].cells + core_hi.cells + n_top + segments - 2 + n_keel) % 2:
        n_keel += 1  # the core's boundary needs an even number of edges for quadrangles
    p, line, block = sketch.point, sketch.line, sketch.block
    axis = [p(0.0, v[0]), p(0.0, v[1]), p(0.0, keel), p(0.0, top), p(0.0, v[2]), p(0.0, v[3])]
    strip = [p(w_lo, v[0]), p(w_lo, v[1]), p(*polyline[1]), p(*polyline[-2]), p(w_hi, v[2]),
             p(w_hi, v[3])]
    inner = [p(c, vj) for vj in v]
    outer = [p(tank.half_length, vj) for vj in v]
    body = [strip[2]] + [p(*q) for q in polyline[2:-2]] + [strip[3]]
    seg = [line(axis[2], strip[2], 1)]
    seg += [line(body[k], body[k + 1], 1) for k in range(len(body) - 1)]
    seg += [line(strip[3], axis[3], 1)]
    r0, r2 = rows[0], rows[2]
    a_low = line(axis[0], axis[1], r0.cells, r0.gmsh_coef())
    a_keel = line(axis[1], axis[2], n_keel)
    a_top = line(axis[3], axis[4], n_top)
    a_high = line(axis[4], axis[5], r2.cells, r2.gmsh_coef())
    s_low = line(strip[0], strip[1], r0.cells, r0.gmsh_coef())
    s_keel = line(strip[1], strip[2], n_keel)
    s_top = line(strip[3], strip[4], n_top)
    s_high = line(strip[4], strip[5], r2.cells, r2.gmsh_coef())
    inner_v = [line(inner[j], inner[j + 1], row.cells, row.gmsh_coef())
               for j, row in enumerate(rows)]
    outer_v = [line(outer[j], outer[j + 1], row.cells, row.gmsh_coef())
               for j, row in enumerate(rows)]
    across = [line(axis[k], strip[k], 1) for k in (0, 1, 4, 5)]
    core_h = [line(strip[k], inner[j], col.cells)
              for k, j, col in ((0, 0, core_lo), (1, 1, core_lo), (4, 2, core_hi),
                                (5, 3, core_hi))]
    far_h = [line(inner[j], outer[j], far.cells, far.gmsh_coef()) for j in range(4)]
    block([across[0], s_low, across[1], a_low])
    block([across[1], s_keel, seg[0], a_keel])
    block([seg[-1], s_top, across[2], a_top])
    block([across[2], s_high, across[3], a_high])
    block([core_h[0], inner_v[0], core_h[1], s_low])
    block([core_h[2], inner_v[2], core_h[3], s_high])
    for j in range(3):
        block([far_h[j], outer_v[j], far_h[j + 1], inner_v[j]])
    loop = [core_h[1], inner_v[1], core_h[2], s_top, *seg[1:-1][::-1], s_keel]
    return sketch.occ.addPlaneSurface([sketch.occ.addCurveLoop(loop)])


def _quad_options(gmsh, spec: MeshSpec) -> None:
    gmsh.option.setNumber("Mesh.MeshSizeMax", spec.body_size)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 8)  # Frontal-Delaunay for quadrangles
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)  # Blossom
    gmsh.option.setNumber("Mesh.Smoothing", 10)  # Laplace on the unstructured core


def _physical_groups(gmsh, sources, out, tank: Tank, kind: str) -> dict:
    """Name every boundary of the extruded (revolved) blocks, and the fluid volume."""
    tops = [out[k - 1] for k in range(1, len(out)) if out[k][0] == 3]
    volumes = [tag for dim, tag in out if dim == 3]
    planes = {tag for _, tag in sources + tops}
    boundary = {abs(tag) for _, tag in gmsh.model.getBoundary([(3, v) for v in volumes],
                                                              combined=True, oriented=False)}
    groups = {"bottom": [], "atmosphere": [], "sides": [], "body": []}
    tol = 1e-6 * tank.half_length  # OpenCASCADE pads bounding boxes by its tolerances
    for tag in sorted(boundary - planes):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, tag)
        u_min = x0 if kind == "wedge" else min(abs(y0), abs(y1))
        if z1 - z0 < tol and abs(z0 + tank.depth) < tol:
            groups["bottom"].append(tag)
        elif z1 - z0 < tol and abs(z0 - tank.air_height) < tol:
            groups["atmosphere"].append(tag)
        elif u_min > tank.half_length * math.cos(math.radians(WEDGE_ANGLE)) - tol:
            groups["sides"].append(tag)
        else:
            groups["body"].append(tag)
    if kind == "2d":
        groups["frontAndBack"] = sorted(planes)
    else:
        groups["wedge0"] = [tag for _, tag in sources]
        groups["wedge1"] = [tag for _, tag in tops]
    named = {name: (2, tags) for name, tags in groups.items()}
    named["fluid"] = (3, volumes)
    for name, (dim, tags) in named.items():
        if not tags:
            raise RuntimeError(f"meshing: the {name!r} patch came out empty")
        gmsh.model.addPhysicalGroup(dim, tags, name=name)
    return named


def wedge_ready(case, where: Pose) -> None:
    """A wedge models a body of revolution about z, upright: raise otherwise."""
    if not case.body.is_axisymmetric:
        raise InputError(f"--kind wedge: the body of {case.name} is not a body of revolution "
                         "about z; valid kinds for it are 2d (2D sections) or 3d")
    if where.heel != 0.0 or where.trim != 0.0:
        raise InputError(f"--kind wedge: {case.name} is heeled or trimmed at this pose "
                         f"({math.degrees(where.heel):g}°, {math.degrees(where.trim):g}°); "
                         "a wedge is upright: valid is --set release.heel=0 --set "
                         "release.trim=0 (heave only), or --kind 3d")
