"""The body's surface as the 3D mesher takes it (:mod:`floatfoam.meshing.domain3d`): an
implicit body's triangles relaxed onto F = 0 (:func:`relax_on_surface`), a symmetric body's
half cut along its plane with the normals of its prism layers (:func:`half_surface`), and an
ellipsoid's surface meshed by OpenCASCADE for its layers (:func:`solid_surface`), with its exact
normals (:func:`ellipsoid_normals`) and its remeshed nodes put back onto it
(:func:`onto_ellipsoid`); the remeshed facets moved out to the body's volume
(:func:`keep_volume`)."""

from __future__ import annotations

import functools
import math

import numpy as np

from floatfoam import gmshio
from floatfoam.bodies import shapes as bodies
from floatfoam.bodies.geometry import enclosed_volume, rotation
from floatfoam.errors import InputError
from floatfoam.meshing import sections
from floatfoam.meshing.levels import MeshSpec
from floatfoam.tank import Pose

FEATURE_ANGLE = 20.0  # degrees: sharper turns between triangles stay edges (pontoon: 25.6°)
# where gmsh cannot parametrise or layer the surface so edged, the angles tried after it (an
# implicit spar's layers are made at 45°: meshing.domain3d.domain_3d)
FEATURE_ANGLES = (FEATURE_ANGLE, 30.0, 45.0)


VERBOSITY = 1  # gmsh messages: 1 errors only; 4 to see where the time goes


@functools.singledispatch
def solid_surface(body, spec: MeshSpec, half: str | None) -> tuple[np.ndarray, np.ndarray]:
    """An ellipsoid's surface as OpenCASCADE meshes it at the 3D sizes (h₀, finer where it
    turns fast, as in :func:`_solid_body`), with ``half`` only its half ``half`` ≥ 0 (the
    cut's nodes exactly on the plane): (vertices, outward faces), body frame. Only the
    ellipsoid registers one."""
    raise TypeError(f"prism layers at a {type(body).__name__}: only at an ellipsoid or "
                    "a body given by triangles")


@solid_surface.register(bodies.Ellipsoid)
def _ellipsoid_surface(body: bodies.Ellipsoid, spec: MeshSpec, half: str | None
                       ) -> tuple[np.ndarray, np.ndarray]:
    from floatfoam.meshing.body_surface import size_options

    with gmshio.session("surface", verbosity=VERBOSITY) as gmsh:
        occ = gmsh.model.occ
        solid = sections.add_solid(body)
        if half:
            k = "xy".index(half)
            big = 2.0 * float(np.max(body.axes))
            corner = [-big, -big, -big]
            corner[k] = 0.0
            extent = [2 * big] * 3
            extent[k] = big
            out, _ = occ.intersect([(3, solid)], [(3, occ.addBox(*corner, *extent))])
            solid = out[0][1]
        occ.synchronize()
        size_options(gmsh, spec.body_size_3d, spec.curvature_points)
        gmsh.model.mesh.generate(2)
        faces = [abs(tag) for _, tag in gmsh.model.getBoundary([(3, solid)], oriented=False)]
        if half:  # the cut face is the symmetry plane's, not the body's
            cut = set()
            for tag in faces:
                box = gmsh.model.getBoundingBox(2, tag)
                if max(abs(box[k]), abs(box[k + 3])) < PLANE_EPS:
                    cut.add(tag)
            faces = [tag for tag in faces if tag not in cut]
        vertices, triangles = gmshio.surface_triangles(faces)
    if half:
        vertices[np.abs(vertices[:, k]) < PLANE_EPS, k] = 0.0
    return vertices, triangles  # outward (gmshio.surface_mesh)


def half_surface(vertices: np.ndarray, faces: np.ndarray, half: str, spec: MeshSpec,
                 angle: float = FEATURE_ANGLE
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """A symmetric body's triangles on the side ``half`` ≥ 0 (:func:`floatfoam.bodies.mirror
    .clip_half`), and the normals its prism layers take: None (gmsh's own, as in the whole
    tank) where the surface stays square to the plane within a body cell of it, as a
    prism-shaped hull does; else
    per triangle corner (:func:`floatfoam.bodies.mirror.corner_normals`, lying in the plane
    at its edge there, where gmsh's, from one side only, would lean out of it)."""
    from floatfoam.bodies.mirror import clip_half, corner_normals, into_plane

    k = "xy".index(half)
    vertices, faces = clip_half(vertices, faces, k)
    if not spec.layers_3d:
        return vertices, faces, None
    normals = corner_normals(vertices, faces, math.radians(angle))
    corners = vertices[faces]
    # square to the plane as far as a body cell from it (a prism-shaped hull), not only on it:
    # a surface that bends away from the plane there (a superellipsoid, flat in x at x = 0
    # to 4e-15 and curved a cell away) gets remeshed triangles whose own normals lean out
    near = np.abs(corners[..., k]) <= spec.body_size_3d
    if float(np.abs(normals[..., k][near]).max(initial=0.0)) < 1e-9:
        return vertices, faces, None
    return vertices, faces, into_plane(normals, corners, k)


def ellipsoid_normals(body, vertices: np.ndarray) -> np.ndarray:
    """The exact outward unit normals of an ellipsoid at body-frame points on it: ∇ of
    (x/a)² + (y/b)² + (z/c)², normalised."""
    gradient = vertices / body.axes**2
    return gradient / np.linalg.norm(gradient, axis=1)[:, None]


def onto_ellipsoid(gmsh, body, surfaces: list[int], where: Pose, first: float) -> None:
    """Move the nodes of the body's surfaces, remeshed on OpenCASCADE's triangles, onto the
    exact ellipsoid along the rays from its centre (by ~h²/(8R), a fraction of a millimetre;
    nodes in a symmetry plane stay in it). On `ellipsoid`'s coarse mesh the immersed volume's
    error goes from −0.72 % to −0.39 %, the route without layers' −0.38 %."""
    turn = rotation(where.heel, where.trim)
    shift = np.array([where.x_c, where.y_c, where.z_c])
    moved: dict[int, np.ndarray] = {}
    for tag in surfaces:
        tags, coords, _ = gmsh.model.mesh.getNodes(2, tag, includeBoundary=True)
        for node, point in zip(tags, coords.reshape(-1, 3), strict=True):
            moved[int(node)] = point
    nodes = np.array(list(moved))
    local = (np.array(list(moved.values())) - shift) @ turn  # body frame
    onto = local / np.sqrt(np.sum((local / body.axes) ** 2, axis=1))[:, None]
    move = float(np.max(np.linalg.norm(onto - local, axis=1)))
    if move > 0.5 * first:  # towards the layers, whose tops stay: the first would fold
        raise InputError(f"mesh.gmsh.layers_height_3d: the first prism layer, {first * 1e3:.3g} "
                         f"mm, is too thin for the body's nodes, which move {move * 1e3:.3g} mm "
                         "onto the ellipsoid; valid: a first layer over twice that (fewer "
                         "mesh.gmsh.layers_3d or a larger layers_height_3d)")
    local = onto
    for node, point in zip(nodes, local @ turn.T + shift, strict=True):
        gmsh.model.mesh.setNode(int(node), point.tolist(), [])


def relax_on_surface(vertices: np.ndarray, faces: np.ndarray, func, size: float,
                     iterations: int = 20) -> np.ndarray:
    """Marching-cubes triangles made fit for remeshing: each sweep moves every vertex half-way
    to the mean of its neighbours (uniform Laplacian), then back onto F = 0 by Newton steps
    along the gradient (central differences). Slivers (triangle quality ~1e-3) become regular
    (~0.3 at worst) and the vertices end on the exact surface, not on its trilinear
    interpolation."""
    import scipy.sparse as sp

    n = len(vertices)
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    adjacency = sp.coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    adjacency = ((adjacency + adjacency.T) > 0).astype(float).tocsr()
    degree = np.asarray(adjacency.sum(axis=1)).ravel()[:, None]
    step = 1e-6 * size
    v = np.array(vertices, dtype=float)
    for _ in range(iterations):
        v += 0.5 * (adjacency @ v / degree - v)
        for _ in range(4):
            value = func(*v.T)
            grad = np.column_stack([(func(*(v + step * e).T) - func(*(v - step * e).T))
                                    / (2 * step) for e in np.eye(3)])
            v -= (value / np.maximum((grad * grad).sum(axis=1), 1e-300))[:, None] * grad
    return v


PLANE_EPS = 2e-5  # m: OpenCASCADE pads bounding boxes by up to ~1e-5 m (a 2 m tank's 2e-6


def keep_volume(gmsh, surfaces: list[int], volume: float, half: str | None, room: float,
                angle: float = FEATURE_ANGLE) -> float:
    """Move the nodes of the body's remeshed surfaces along their normals until the surface
    encloses ``volume`` (m³: the body's, half of it with ``half``, whose plane closes the half
    surface). Facets on a curved surface are its chords and cut it short: a sphere meshed at
    12 cells across loses 1 % of its volume, and its waterplane, the heave's stiffness, 0.7 %.
    Each node moves by c·w, w its bulge (its height above its neighbours' mean along its
    normal: ~h²κ/2, nil where the surface is flat, negative where it is hollow), a node on a
    turn sharper than ``angle`` (degrees) not at all (a crease, which the facets keep), c
    the one factor that gives the volume. Nodes in the symmetry plane stay in it. ``room``:
    the first prism layer's height, or the body's cell size: a node that would move beyond half
    of it (the correction gathered on a few nodes, a layer folded) leaves every node where it
    is. Returns the largest move (m), negative when the nodes were left."""
    tags, v, faces = gmshio.surface_mesh(surfaces)
    k = "xy".index(half) if half else None
    on_plane = np.abs(v[:, k]) < PLANE_EPS if half else np.zeros(len(v), dtype=bool)
    held = _crease_nodes(v, faces, math.radians(angle))
    if half:  # a crease the surface makes with its mirror image (a keel, a stem) is held too
        c = v[faces]
        normal = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        steep = np.abs(normal[:, k]) > math.sin(math.radians(angle) / 2.0)
        for j in range(3):
            held[faces[steep, j][on_plane[faces[steep, j]]]] = True
    n = len(v)
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    edges = np.unique(np.sort(edges, axis=1), axis=0)
    degree = np.bincount(edges.ravel(), minlength=n).astype(float)
    move = np.zeros(n)
    for _ in range(3):  # c by Newton's step on the enclosed volume, linear in it to O(move²)
        moved = v
        corners = moved[faces]
        area_normals = 0.5 * np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        normals = np.zeros_like(moved)
        for j in range(3):
            np.add.at(normals, faces[:, j], area_normals)
        area = np.linalg.norm(normals, axis=1) / 3.0  # a third of the ring's area, ~
        if half:
            normals[on_plane, k] = 0.0
        length = np.linalg.norm(normals, axis=1)
        normals = np.divide(normals, length[:, None], out=np.zeros_like(normals),
                            where=length[:, None] > 0.0)
        mean = np.zeros_like(moved)
        np.add.at(mean, edges[:, 0], moved[edges[:, 1]])
        np.add.at(mean, edges[:, 1], moved[edges[:, 0]])
        mean /= degree[:, None]
        if half:  # the mirrored neighbours too: their mean lies in the plane
            mean[on_plane, k] = 0.0
        bulge = np.sum((moved - mean) * normals, axis=1)
        bulge[held | (length == 0.0)] = 0.0
        gain = float(np.sum(area * bulge))
        missing = volume - enclosed_volume(moved, faces)
        # bulges that cancel (round-off on flat faces, or as much hollow as convex) give no
        # direction to move in: stop rather than divide by them
        if abs(gain) <= 0.1 * float(np.sum(area * np.abs(bulge))) \
                or abs(missing) <= 1e-9 * volume:
            break
        step = missing / gain * bulge
        v = moved + step[:, None] * normals
        move += step
    largest = float(np.max(np.abs(move)))
    if largest > 0.5 * room:  # the correction gathered on a few nodes: the chords are kept
        return -largest
    if half:
        v[on_plane, k] = 0.0
    for node, point in zip(tags, v, strict=True):
        gmsh.model.mesh.setNode(int(node), point.tolist(), [])
    return largest


def _crease_nodes(vertices: np.ndarray, faces: np.ndarray, angle: float) -> np.ndarray:
    """The nodes on an edge between two triangles turned by more than ``angle`` (rad)."""
    c = vertices[faces]
    normal = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    owner = np.tile(np.arange(len(faces)), 3)
    key = np.sort(edges, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, owner = key[order], owner[order]
    same = np.all(key[1:] == key[:-1], axis=1)
    held = np.zeros(len(vertices), dtype=bool)
    pairs = np.nonzero(same)[0]
    turned = np.sum(normal[owner[pairs]] * normal[owner[pairs + 1]], axis=1) < math.cos(angle)
    held[key[pairs[turned]].ravel()] = True
    return held
