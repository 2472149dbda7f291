"""3D fluid domains: the tank minus the body, in tetrahedra graded away from the body and the
free surface.

Why tetrahedra: gmsh has no robust hexahedral-dominant mesher for a body-fitted 3D domain, and
a tensor-product block layout (as in 2D) would carry the body's cell size across the whole
tank in all three directions. Sizes (one function, divided by r at each level):

    h = min( h₀ + α d,                                  (near the body)
             h₀ + α/2 d + α max(|z| − b, 0) )           (free-surface band |z| ≤ b)

with d the distance to the body, h₀ = D / body_cells_3d and α = growth_3d − 1; capped at a
quarter of the tank's height. In the band the cells grow half as fast with the distance from
the body, so the radiated waves keep more of their resolution.

Bodies with an exact geometry are OpenCASCADE solids cut out of the tank. Bodies given as
triangles (``stl``, ``implicit``) are classified into smooth patches (feature angle
:data:`~floatfoam.meshing.surface3d.FEATURE_ANGLE`; the wider ones of ``FEATURE_ANGLES`` where
gmsh fails so), reparametrised and remeshed at the same
sizes, and the tank is built around them with gmsh's built-in kernel; an implicit body's
marching-cubes triangles are first relaxed onto F = 0
(:func:`~floatfoam.meshing.surface3d.relax_on_surface`), their slivers defeat the
reparametrisation. In a half domain their half is cut along the plane
(:func:`~floatfoam.meshing.surface3d.half_surface`).

Prism layers (``mesh.gmsh.layers_3d``, 3 by default at a body given by triangles, none at an
exact solid: settings.TRIANGLE_LAYERS): the body's surface mesh extruded outwards along its
normals (gmsh's built-in ``extrudeBoundaryLayer``), each layer :data:`LAYER_GROWTH` times the
one below, together ``layers_height_3d`` × h₀; the tetrahedra start on the outer layer. Their
cost is small (3 layers: +2 % cells on the 3D sphere), and they stand in for the first
tetrahedra at the body, where the free surface meets it. An ellipsoid takes them too when the
case asks (``layers_3d`` > 0): OpenCASCADE meshes its surface (its half x ≥ 0 or y ≥ 0 in a
half domain) at the same sizes, and that mesh takes the discrete route with the ellipsoid's
exact normals (:func:`~floatfoam.meshing.surface3d.solid_surface`), which at the symmetry
plane lie in it, so the layers' side faces do too and join the plane's symmetry patch; gmsh's
own normals there, from the triangles on one side only, leaned 0.4 mm out of it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from floatfoam import gmshio
from floatfoam.bodies.expression import compile_expression
from floatfoam.errors import ComputationError, InputError
from floatfoam.interrupts import RECEIVED
from floatfoam.meshing import sections
from floatfoam.meshing.body_surface import place
from floatfoam.meshing.levels import MeshSpec
from floatfoam.meshing.surface3d import (
    FEATURE_ANGLE,
    FEATURE_ANGLES,
    PLANE_EPS,
    VERBOSITY,
    ellipsoid_normals,
    half_surface,
    keep_volume,
    onto_ellipsoid,
    relax_on_surface,
    solid_surface,
)
from floatfoam.tank import Pose, Tank

LAYER_GROWTH = 1.2  # each prism layer this much thicker than the one below it


def domain_3d(case, spec: MeshSpec, tank: Tank, where: Pose, path: Path,
              half: str | None = None) -> dict:
    """Mesh the 3D domain of ``case`` with the body at a pose; write ``path`` (MSH 2.2).
    ``half`` "x" (or "y"): only x ≥ 0 (y ≥ 0), that plane a ``symmetry`` patch — for a body
    symmetric about it whose motion keeps it (roll about x keeps x = 0, pitch about y keeps
    y = 0).

    Returns a summary: ``path``, ``cells``, ``cell_types``, ``patches`` (faces per patch) and
    ``body_triangles`` ((vertices, faces) of the body patch, earth frame, for volume checks),
    and ``surface_note`` when a body given by triangles was meshed otherwise than asked: its
    edges at a wider angle (:data:`~floatfoam.meshing.surface3d.FEATURE_ANGLES`) or without
    prism layers, where gmsh could not make it so.
    """
    if not case.body.given_by_triangles:  # an OpenCASCADE solid: meshed as it is asked
        return _domain_3d(case, spec, tank, where, path, half, FEATURE_ANGLE)
    attempts = [(angle, spec) for angle in FEATURE_ANGLES]
    if spec.layers_3d:  # then without the prism layers
        attempts += [(angle, replace(spec, layers_3d=0)) for angle, _ in attempts]
    failures = []
    for angle, tried in attempts:
        try:  # quiet: what gmsh says of a failure comes back in what it raises
            result = _domain_3d(case, tried, tank, where, path, half, angle, verbosity=0)
        except Exception as err:  # noqa: BLE001 - gmsh raises Exception itself, saying why
            # what gmsh raises, and an empty patch; an interrupt wrapped by gmsh's ctypes
            # call stops, it is not retried
            if type(err) not in (Exception, RuntimeError) or RECEIVED:
                raise
            failures.append(f"{err}")
            continue
        if failures:
            wider = (f"gmsh meshed the body's surface with turns sharper than {angle:g}° as edges"
                     + ("" if tried.layers_3d == spec.layers_3d else " and without prism layers")
                     + f" (as asked, it failed: {failures[0]})")
            result["surface_note"] = "; ".join(filter(None, [wider, result.get("surface_note")]))
        return result
    angles = ", ".join(f"{a:g}" for a in FEATURE_ANGLES)
    raise ComputationError(f"gmsh could not mesh the body's surface ({failures[0]}), with its "
                           f"edges at turns sharper than {angles}°"
                           + (", with and without prism layers" if spec.layers_3d else "")
                           + ": a finer [body] resolution, or a cleaner STL")


def _domain_3d(case, spec: MeshSpec, tank: Tank, where: Pose, path: Path, half: str | None,
               angle: float, verbosity: int = VERBOSITY) -> dict:
    """:func:`domain_3d` with the body's surface edged at turns sharper than ``angle``
    (degrees), gmsh's messages at ``verbosity``."""
    from floatfoam.meshing.planar import summary

    body = case.body
    surface = None
    if spec.layers_3d and not body.given_by_triangles:  # its own gmsh session first
        surface = solid_surface(body, spec, half)
    with gmshio.session(f"{case.name}-3d", verbosity=verbosity) as gmsh:
        if body.given_by_triangles:
            vertices, faces = body.vertices, body.faces
            if body.expression is not None:  # an implicit surface: nodes back onto F = 0
                func = compile_expression(body.expression)
                vertices = relax_on_surface(vertices, faces, func, spec.span)
            normals = None
            if half:
                vertices, faces, normals = half_surface(vertices, faces, half, spec, angle)
            body_surfaces, volumes, layers, column = _discrete_body(
                gmsh, vertices, faces, where, tank, spec, half, normals=normals, angle=angle)
        elif spec.layers_3d:  # an ellipsoid's surface meshed by OpenCASCADE, then as triangles
            vertices, faces = surface
            body_surfaces, volumes, layers, column = _discrete_body(
                gmsh, vertices, faces, where, tank, spec, half,
                normals=ellipsoid_normals(body, vertices))
        else:
            body_surfaces, volume = _solid_body(gmsh, body, where, tank, spec, half)
            volumes, layers, column = (volume,), Layers(), []
        # curvature sizing on reparametrised triangles costs minutes (the pontoon's, the
        # superellipsoid's): exact solids only, the layered ellipsoid's remeshed surface too
        # (2 s for ellipsoid_roll's coarse mesh)
        _size_field(gmsh, body_surfaces, spec, tank,
                    curvature=not body.given_by_triangles)
        if column:  # the band's walls towards the column: triangles for the tetrahedra
            gmsh.model.mesh.generate(2)
            split_walls(gmsh, column)
        gmsh.model.mesh.generate(3)
        if surface is not None:  # remeshed on OpenCASCADE's triangles: back onto the solid
            onto_ellipsoid(gmsh, body, body_surfaces, where, layer_heights(spec)[0])
        note = None  # the facets, chords of the surface, out to the body's volume
        room = layer_heights(spec)[0] if spec.layers_3d else spec.body_size_3d
        moved = keep_volume(gmsh, body_surfaces, _volume_of(body, half), half, room, angle)
        if moved < 0.0:
            note = (f"the body's facets are left as chords: moving them to its volume "
                    f"would move a node {-moved * 1e3:.3g} mm")
        groups = _physical_groups(gmsh, volumes, body_surfaces, tank, half, layers)
        inside_out = gmshio.inside_out_prisms(groups["fluid"][1])
        if inside_out:  # gmshToFoam's turning them over leaves faces in no patch
            raise RuntimeError(f"meshing: {inside_out} prisms of the layers come out inside "
                               "out (folded over at a thin edge)")
        gmshio.write_msh22(path)
        result = summary(gmsh, groups, path)
        result["body_triangles"] = gmshio.surface_triangles(body_surfaces)
    if note:
        result["surface_note"] = note
    return result


def _volume_of(body, half: str | None) -> float:
    """The volume the body's meshed surface must enclose: the body's own (an ellipsoid's or a
    vertical cylinder's exact one, a section's from its fine polygon; that of a body's
    triangles, which the theory takes, an implicit body's as marching cubes give them); half
    of it with ``half``."""
    volume = abs(body.volume())
    return volume / 2.0 if half else volume


def _solid_body(gmsh, body, where: Pose, tank: Tank, spec: MeshSpec,
                half: str | None = None) -> tuple[list[int], int]:
    """The tank (its half on the positive side of the plane ``half`` = 0) minus the placed
    solid."""
    occ = gmsh.model.occ
    solid = sections.add_solid(body)
    occ.rotate([(3, solid)], 0, 0, 0, 1, 0, 0, where.heel)
    occ.rotate([(3, solid)], 0, 0, 0, 0, 1, 0, where.trim)
    occ.translate([(3, solid)], where.x_c, where.y_c, where.z_c)
    box = occ.getBoundingBox(3, solid)
    _check_room(np.array(box[:3]), np.array(box[3:]), tank, spec)
    x0 = 0.0 if half == "x" else -tank.half_length
    y0 = 0.0 if half == "y" else -tank.half_width
    box = occ.addBox(x0, y0, -tank.depth, tank.half_length - x0, tank.half_width - y0,
                     tank.depth + tank.air_height)
    out, _ = occ.cut([(3, box)], [(3, solid)])
    occ.synchronize()
    volume = out[0][1]
    walls = _tank_faces(gmsh, tank) | (_plane_faces(gmsh, half, tank) if half else set())
    faces = [abs(tag) for _, tag in gmsh.model.getBoundary([(3, volume)], oriented=False)]
    return [tag for tag in faces if tag not in walls], volume


@dataclass(frozen=True)
class Layers:
    """The prism layers' volumes, their outer surfaces and, in a half domain, their side
    faces in the symmetry plane (none without layers)."""

    volumes: tuple[int, ...] = ()
    tops: frozenset[int] = frozenset()
    sides: frozenset[int] = frozenset()


def layer_heights(spec: MeshSpec) -> list[float]:
    """Cumulative heights of ``spec.layers_3d`` prism layers, each LAYER_GROWTH times the one
    below it, together ``spec.layers_height_3d``."""
    steps = [LAYER_GROWTH**k for k in range(spec.layers_3d)]
    scale = spec.layers_height_3d / sum(steps)
    return [scale * sum(steps[:k + 1]) for k in range(len(steps))]


def _discrete_body(gmsh, vertices, faces, where: Pose, tank: Tank, spec: MeshSpec,
                   half: str | None = None, normals: np.ndarray | None = None,
                   angle: float = FEATURE_ANGLE) -> tuple[list[int], int, Layers]:
    """A triangulated body as reparametrised discrete surfaces, its prism layers if
    ``spec.layers_3d``, and the tank around them (its half ``half`` ≥ 0, the body's half
    surface cut out of that plane). ``normals`` (body frame, one per vertex (N, 3) or per
    triangle corner (T, 3, 3)): the direction of the layers, else gmsh's from the triangles."""
    if normals is not None:  # turned to the pose (directions: no shift)
        flat = normals.reshape(-1, 3)
        normals = (place(flat, where) - place(np.zeros_like(flat), where)).reshape(normals.shape)
    vertices = place(vertices, where)
    _check_room(vertices.min(axis=0), vertices.max(axis=0), tank, spec)
    surface = gmsh.model.addDiscreteEntity(2)
    n = len(vertices)
    gmsh.model.mesh.addNodes(2, surface, list(range(1, n + 1)), vertices.ravel().tolist())
    gmsh.model.mesh.addElementsByType(surface, gmshio.TRIANGLE, [],
                                      (faces + 1).ravel().tolist())
    gmsh.model.mesh.classifySurfaces(math.radians(angle), True, True, math.pi)
    gmsh.model.mesh.createGeometry()
    body_surfaces = [tag for _, tag in gmsh.model.getEntities(2)]
    geo = gmsh.model.geo
    layers, inner = Layers(), body_surfaces
    if spec.layers_3d:  # extruded along the body mesh's normals, outwards (outward triangles)
        view = -1
        if normals is not None:  # given normals, as a view gmsh finds by position
            view = _normals_view(gmsh, vertices, faces, normals)
        made = geo.extrudeBoundaryLayer([(2, tag) for tag in body_surfaces],
                                        [1] * spec.layers_3d, layer_heights(spec), True,
                                        False, view)
        tops = [made[k - 1][1] for k in range(1, len(made)) if made[k][0] == 3]
        sides = {tag for dim, tag in made if dim == 2} - set(tops)
        layers = Layers(tuple(tag for dim, tag in made if dim == 3), frozenset(tops),
                        frozenset(sides))
        inner = tops
        geo.synchronize()  # the tops' edges known to the model: the rim below
    core = _core_half_width(vertices, spec, tank) if spec.band_prisms_3d else None
    volumes, column = _tank_around(gmsh, inner, tank, spec, half, core)
    return body_surfaces, volumes, layers, column


def _core_half_width(vertices: np.ndarray, spec: MeshSpec, tank: Tank) -> float | None:
    """Half-width of the column about the body that the free-surface band's prisms leave to
    tetrahedra: the placed body's horizontal reach, its prism layers and the core's margin;
    None (no prisms) where that column would not leave a cell between it and the tank's
    walls."""
    reach = float(np.abs(vertices[:, :2]).max()) + spec.layers_height_3d + spec.margin
    if reach + spec.body_size_3d >= min(tank.half_length, tank.half_width):
        return None
    return reach


def _tank_around(gmsh, inner: list[int], tank: Tank, spec: MeshSpec, half: str | None,
                 core: float | None) -> tuple[tuple[int, ...], list[int]]:
    """The tank (its half ``half`` ≥ 0) around the closed (in a half tank: open at the plane)
    surfaces ``inner``. With ``core``: its free-surface band |z| ≤ b outside the column
    |x|, |y| ≤ core is extruded upwards from z = −b in horizontal layers of prisms (one body
    cell high: gmsh's structured extrusion), so that a flat free surface there lies in a layer
    of cells whose centres are level; the rest is one volume of tetrahedra. Returns the
    volumes (tetrahedra first) and the band's faces towards the column (its walls, meshed in
    quadrangles that :func:`split_walls` halves for the tetrahedra)."""
    geo = gmsh.model.geo
    x0 = 0.0 if half == "x" else -tank.half_length
    y0 = 0.0 if half == "y" else -tank.half_width
    x1, y1, z0, z1 = tank.half_length, tank.half_width, -tank.depth, tank.air_height
    rim = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]  # side k runs from corner k to k + 1
    plane = {"x": 3, "y": 0}.get(half)  # x = x0 is the 4th side
    walls = _Walls(gmsh)
    faces = [walls.face([(x, y, z) for x, y in rim]) for z in (z0, z1)]
    if core is None:
        for k in range(4):
            (xa, ya), (xb, yb) = rim[k], rim[(k + 1) % 4]
            outline = [(xa, ya, z0), (xb, yb, z0), (xb, yb, z1), (xa, ya, z1)]
            faces.append(walls.face(outline, [_rim(gmsh, inner)] if k == plane else []))
        return (_volume(geo, faces, inner, half),), []
    b = tank.band
    band, shared, column = _band(gmsh, walls, rim, half, core, b, spec)
    for k in range(4):
        (xa, ya), (xb, yb) = rim[k], rim[(k + 1) % 4]
        if k == plane:  # the plane's face: the band's strips and the body's rim cut out of it
            u0, u1 = (y0, y1) if half == "x" else (x0, x1)

            def at(u, z):
                return (0.0, u, z) if half == "x" else (u, 0.0, z)

            outline = [at(u0, z0), at(u1, z0), at(u1, -b), at(core, -b), at(core, b),
                       at(u1, b), at(u1, z1), at(u0, z1), at(u0, b), at(-core, b),
                       at(-core, -b), at(u0, -b)]
            faces.append(walls.face(outline, [_rim(gmsh, inner)]))
            continue
        faces.append(walls.face([(xa, ya, z0), (xb, yb, z0), (xb, yb, -b), (xa, ya, -b)]))
        faces.append(walls.face([(xa, ya, b), (xb, yb, b), (xb, yb, z1), (xa, ya, z1)]))
    return (_volume(geo, faces + shared + column, inner, half), band), column


def _volume(geo, faces: list[int], inner: list[int], half: str | None) -> int:
    """The volume bounded by ``faces`` and ``inner`` (one shell in a half tank, two else)."""
    if half:
        volume = geo.addVolume([geo.addSurfaceLoop(faces + inner)])
    else:
        volume = geo.addVolume([geo.addSurfaceLoop(faces), geo.addSurfaceLoop(inner)])
    geo.synchronize()
    return volume


def _band(gmsh, walls: _Walls, rim, half: str | None, core: float, b: float,
          spec: MeshSpec) -> tuple[int, list[int], list[int]]:
    """The free-surface band outside the column |x|, |y| ≤ ``core``: its floor at z = −b
    extruded to z = b in layers one body cell high. Returns its volume, its floor and roof,
    and its walls towards the column (the faces it shares with the tetrahedra)."""
    geo = gmsh.model.geo
    (x0, y0), (x1, _), (_, y1) = rim[0], rim[1], rim[2]
    c = core
    if half == "x":  # a U about the column's half, open at x = 0
        loops = [[(0.0, y0), (x1, y0), (x1, y1), (0.0, y1), (0.0, c), (c, c), (c, -c),
                  (0.0, -c)]]
    elif half == "y":
        loops = [[(x0, 0.0), (-c, 0.0), (-c, c), (c, c), (c, 0.0), (x1, 0.0), (x1, y1),
                  (x0, y1)]]
    else:
        loops = [rim, [(-c, -c), (c, -c), (c, c), (-c, c)]]
    floor = walls.face([[(x, y, -b) for x, y in loop] for loop in loops], nested=True)
    layers = max(2, round(2 * b / spec.body_size_3d))
    made = geo.extrude([(2, floor)], 0, 0, 2 * b, numElements=[layers], recombine=True)
    geo.synchronize()
    walls.index()
    column = []  # the sides within the column's reach; the others are the tank's
    for dim, tag in made[2:]:
        if dim == 2:
            box = gmsh.model.getBoundingBox(2, tag)
            if max(abs(v) for v in (*box[:2], *box[3:5])) <= c * (1 + 1e-4):
                column.append(tag)
    return made[1][1], [floor, made[0][1]], column


def split_walls(gmsh, walls: list[int]) -> None:
    """Halve each quadrangle of the meshed surfaces ``walls`` into two triangles, so that the
    tetrahedra beside them conform to triangles (gmsh's pyramids on quadrangles overlapped
    tetrahedra here); the prisms keep their quadrangular side, which
    :func:`floatfoam.foam.splitfaces.join_split_faces` joins to the two triangles."""
    for tag in walls:
        types, _, nodes = gmsh.model.mesh.getElements(2, tag)
        quads = [np.asarray(n, dtype=np.int64).reshape(-1, 4)
                 for t, n in zip(types, nodes, strict=True) if t == gmshio.QUAD]
        if not quads:
            continue
        q = np.concatenate(quads)
        halves = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]], axis=1).reshape(-1)
        gmsh.model.mesh.removeElements(2, tag)
        gmsh.model.mesh.addElementsByType(tag, gmshio.TRIANGLE, [], halves.tolist())


class _Walls:
    """Plane faces of the tank built from outlines of points, sharing the points and lines
    that exist already (the band's extruded ones among them) by their coordinates."""

    def __init__(self, gmsh):
        self.gmsh, self.geo = gmsh, gmsh.model.geo
        self.points: list[tuple[np.ndarray, int]] = []
        self.lines: dict[frozenset, int] = {}

    def index(self) -> None:
        """Learn the model's points and straight lines (after a synchronize)."""
        model = self.gmsh.model
        known = {tag for _, tag in self.points}
        for _, tag in model.getEntities(0):
            if tag not in known:
                self.points.append((np.asarray(model.getValue(0, tag, [])), tag))
        for _, tag in model.getEntities(1):
            ends = [abs(t) for _, t in model.getBoundary([(1, tag)], oriented=False)]
            if len(ends) == 2:
                self.lines.setdefault(frozenset(ends), tag)

    def point(self, xyz) -> int:
        """The point at ``xyz`` (within 1e-9 m: an extruded one lands within rounding of
        where it is asked for), made if there is none."""
        xyz = np.asarray(xyz, dtype=float)
        for where, tag in self.points:
            if np.abs(where - xyz).max() < 1e-9:
                return tag
        tag = self.geo.addPoint(*xyz)
        self.points.append((xyz, tag))
        return tag

    def loop(self, outline) -> int:
        tags = [self.point(q) for q in outline]
        curves = []
        for a, b in zip(tags, tags[1:] + tags[:1], strict=True):
            if frozenset((a, b)) not in self.lines:
                self.lines[frozenset((a, b))] = self.geo.addLine(a, b)
            curves.append(self.lines[frozenset((a, b))])
        return self.geo.addCurveLoop(curves, reorient=True)

    def face(self, outline, holes: list[list[int]] = (), nested: bool = False) -> int:
        """A plane face: ``outline`` (points), or with ``nested`` a list of outlines (the
        first the outer one); ``holes``: curve loops given as their curves."""
        loops = [self.loop(o) for o in (outline if nested else [outline])]
        loops += [self.geo.addCurveLoop(h, reorient=True) for h in holes]
        return self.geo.addPlaneSurface(loops)


def _rim(gmsh, surfaces: list[int]) -> list[int]:
    """The curves that bound ``surfaces`` once (those two of them share are inside): an open
    half body's, or its layers', edge in the symmetry plane."""
    count: dict[int, int] = {}
    for _, curve in gmsh.model.getBoundary([(2, tag) for tag in surfaces], combined=False,
                                           oriented=False):
        count[abs(curve)] = count.get(abs(curve), 0) + 1
    return sorted(curve for curve, n in count.items() if n == 1)


def _normals_view(gmsh, vertices: np.ndarray, faces: np.ndarray, normals: np.ndarray) -> int:
    """A list-data view of vectors (per vertex, or per triangle corner) on the triangles
    (gmsh's "VT": each triangle's corners, then a vector at each): where the boundary layer's
    extrusion looks its normals up, by position, on the surface as it will be remeshed.
    Returns the view's index."""
    corners = vertices[faces]  # (T, 3 corners, 3)
    vectors = normals[faces] if normals.ndim == 2 else normals
    data = np.concatenate([corners.transpose(0, 2, 1).reshape(len(faces), 9),
                           vectors.reshape(len(faces), 9)], axis=1)
    view = gmsh.view.add("layer normals")
    gmsh.view.addListData(view, "VT", len(faces), data.ravel().tolist())
    return gmsh.view.getIndex(view)


                  # missed the symmetry plane)


def _in_plane(gmsh, surface: int, axis: str, tank: Tank) -> bool:
    """Every node of a meshed ``surface`` lies in the plane ``axis`` = 0."""
    coords = gmsh.model.mesh.getNodes(2, surface, includeBoundary=True)[1].reshape(-1, 3)
    eps = max(1e-6 * tank.half_length, PLANE_EPS)
    return len(coords) > 0 and float(np.abs(coords[:, "xy".index(axis)]).max()) < eps


def _plane_faces(gmsh, axis: str, tank: Tank) -> set[int]:
    """The faces lying in the plane ``axis`` = 0 ("x" or "y")."""
    eps = max(1e-6 * tank.half_length, PLANE_EPS)
    lo = [-tank.half_length - eps, -tank.half_width - eps, -tank.depth - eps]
    hi = [tank.half_length + eps, tank.half_width + eps, tank.air_height + eps]
    k = "xy".index(axis)
    lo[k], hi[k] = -eps, eps
    return {tag for _, tag in gmsh.model.getEntitiesInBoundingBox(*lo, *hi, 2)}


def _tank_faces(gmsh, tank: Tank) -> set[int]:
    eps = 1e-6 * tank.half_length
    found = set()
    for lo, hi in (([-1, -1, -1], [1, 1, -1]), ([-1, -1, 1], [1, 1, 1]),
                   ([-1, -1, -1], [-1, 1, 1]), ([1, -1, -1], [1, 1, 1]),
                   ([-1, -1, -1], [1, -1, 1]), ([-1, 1, -1], [1, 1, 1])):
        box = np.array([tank.half_length, tank.half_width, 1.0])
        lo, hi = np.array(lo) * box, np.array(hi) * box
        lo[2] = -tank.depth if lo[2] < 0 else tank.air_height
        hi[2] = -tank.depth if hi[2] < 0 else tank.air_height
        found.update(tag for _, tag in gmsh.model.getEntitiesInBoundingBox(
            *(lo - eps), *(hi + eps), 2))
    return found


def _check_room(lo: np.ndarray, hi: np.ndarray, tank: Tank, spec: MeshSpec) -> None:
    """The placed body's bounding box [lo, hi] inside the tank with a cell to spare, checked
    before the tank is cut: a body through a wall or the tank's top would be cut with it."""
    reach = {"half_length": (max(-lo[0], hi[0]), "|x|"), "half_width": (max(-lo[1], hi[1]), "|y|"),
             "depth": (-lo[2], "z = −"), "air_height": (hi[2], "z = +")}
    for key, (value, where) in reach.items():
        have = getattr(tank, key)
        if have <= value + spec.body_size_3d:
            at = f"{where} = {value:.4g}" if where.startswith("|") else f"{where}{value:.4g}"
            raise InputError(f"domain.{key} = {have:g} m does not hold the body, which reaches "
                             f"{at} m where it is meshed (the [release] offsets move it); "
                             f"valid is > {value + spec.body_size_3d:.4g} m, or a smaller "
                             "release")


def _size_field(gmsh, body_surfaces, spec: MeshSpec, tank: Tank, curvature: bool) -> None:
    field = gmsh.model.mesh.field
    h0 = spec.body_size_3d
    alpha = (spec.growth_3d - 1.0) / spec.ratio**spec.index  # same size function, ÷ r^level
    distance = field.add("Distance")
    field.setNumbers(distance, "SurfacesList", body_surfaces)
    field.setNumber(distance, "Sampling", 40)
    near = field.add("MathEval")
    field.setString(near, "F", f"{h0} + {alpha} * F{distance}")
    band = field.add("MathEval")
    field.setString(band, "F", f"{h0} + {alpha / 2} * F{distance} + "
                               f"{alpha} * Max(Abs(z) - {tank.band}, 0)")
    size = field.add("Min")
    field.setNumbers(size, "FieldsList", [near, band])
    field.setAsBackgroundMesh(size)
    height = tank.depth + tank.air_height
    gmsh.option.setNumber("Mesh.MeshSizeMax", height / 4 / spec.ratio**spec.index)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature",
                          round(spec.curvature_points) if curvature else 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
    gmsh.option.setNumber("Mesh.Optimize", 1)
    gmsh.option.setNumber("Mesh.OptimizeNetgen", 1 if spec.optimize_netgen_3d else 0)


def _physical_groups(gmsh, volumes: tuple[int, ...], body_surfaces: list[int], tank: Tank,
                     half: str | None = None, layers: Layers = Layers()) -> dict:
    groups = {"bottom": [], "atmosphere": [], "sides": [], "body": sorted(body_surfaces)}
    if half:
        groups["symmetry"] = []
    eps = 1e-6 * tank.half_length
    # the boundary of the tetrahedra and the band's prisms together (the faces they share
    # are inside)
    for _, tag in gmsh.model.getBoundary([(3, v) for v in volumes], combined=True,
                                         oriented=False):
        tag = abs(tag)
        if tag in body_surfaces or tag in layers.tops:
            continue
        box = gmsh.model.getBoundingBox(2, tag)
        z0, z1 = box[2], box[5]
        k = "xy".index(half) if half else 0
        if half and max(abs(box[k]), abs(box[k + 3])) < max(eps, PLANE_EPS):
            groups["symmetry"].append(tag)
        elif z1 - z0 < eps:
            groups["bottom" if z0 < 0 else "atmosphere"].append(tag)
        else:
            groups["sides"].append(tag)
    if half:  # the layers' side faces in the plane (not those between two patches' layers)
        groups["symmetry"].extend(tag for tag in sorted(layers.sides)
                                  if _in_plane(gmsh, tag, half, tank))
    named = {name: (2, tags) for name, tags in groups.items()}
    named["fluid"] = (3, [*volumes, *layers.volumes])
    for name, (dim, tags) in named.items():
        if not tags:
            raise RuntimeError(f"meshing: the {name!r} patch came out empty")
        gmsh.model.addPhysicalGroup(dim, tags, name=name)
    return named
