"""Panel meshes of the wetted surface for the potential-flow (BEM) solvers.

3D bodies: the body's own closed surface mesh (``Body.surface_mesh()``, fine: an icosphere, a
marching-cubes surface or a user's STL) is placed at its equilibrium attitude in the earth frame,
clipped at the free surface z = 0, and the wetted part is remeshed by gmsh (discrete surface:
``classifySurfaces`` + ``createGeometry``, then Frontal-Delaunay triangles of a uniform size) to
about ``panels`` triangles. The waterline is kept exactly on z = 0 (it is a boundary curve of
the discrete surface) and the orientation of the input (normals out of the body) is kept. A
wetted surface symmetric about y = 0 and/or x = 0 is cut there first and only its half or
quarter meshed (the solver mirrors it). The lid for irregular-frequency removal is the interior
waterplane bounded by the hull's own waterline nodes, meshed by gmsh.

2D sections: the section polygon's wetted contour
(:func:`floatfoam.potential.sections.wetted_contour`) divided into straight panels of equal arc
length between its corners.
"""

from __future__ import annotations

import numpy as np

from floatfoam import gmshio
from floatfoam.bodies.geometry import to_earth
from floatfoam.hydrostatics.immersion import clip_triangles
from floatfoam.potential.sections import panel_nodes, wetted_contour

DEFAULT_PANELS_3D = 800  # hemisphere: ≤ 1.6 % from Hulme (1982) at ka ≤ 2 (see tests/)
SYMMETRY_TOL = 1e-4  # odd moments of the wetted surface, relative (see symmetry_planes)
SNAP = 0.05  # × the mean edge of the body's surface mesh: waterline snapping (wetted_triangles)
FEATURE_ANGLE = 30.0  # degrees: facets meeting at a sharper angle keep their edge (box corners)


def wetted_triangles(body, z_c: float, heel: float, trim: float) -> np.ndarray:
    """Wetted part (T, 3, 3) of the body's surface mesh at an attitude, earth frame.

    Vertices within :data:`SNAP` of a mean edge of the free surface are moved onto it first:
    a waterline a hair from a ring of vertices (a sphere floating at its equator) would
    otherwise cut slivers thinner than round-off, on which gmsh's surface classification never
    returns. The move is far below the panel size the hull is remeshed to; facets then lying
    in the free surface itself (a flat bottom at the waterline) are not wetted and dropped.
    """
    vertices, faces = body.surface_mesh()
    earth = to_earth(vertices, z_c, heel, trim)
    edge = float(np.linalg.norm(earth[faces[:, 1]] - earth[faces[:, 0]], axis=1).mean())
    earth[np.abs(earth[:, 2]) < SNAP * edge, 2] = 0.0
    triangles = earth[faces]
    in_surface = np.all(triangles[:, :, 2] == 0.0, axis=1)
    return clip_triangles(triangles[~in_surface])


def merge_vertices(triangles: np.ndarray, rel_tol: float = 1e-7):
    """Indexed mesh (vertices, faces) of a triangle soup; vertices within ``rel_tol`` × the
    largest coordinate of each other merged and triangles that collapse to a segment dropped.
    A marching-cubes surface cut at the free surface and a symmetry plane can hold edges of
    1e-10 m (the implicit sphere of radius 0.1 m at a resolution of 80), on which gmsh's
    reparametrisation of the surface does not return."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    points = triangles.reshape(-1, 3)
    scale = float(np.abs(points).max()) or 1.0
    pairs = cKDTree(points).query_pairs(scale * rel_tol, output_type="ndarray")
    n = len(points)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    _, first, inverse = np.unique(label, return_index=True, return_inverse=True)
    faces = inverse.reshape(-1, 3)
    degenerate = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) \
        | (faces[:, 2] == faces[:, 0])
    return points[first], faces[~degenerate]


def triangle_areas(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    a, b, c = (vertices[faces[:, i]] for i in range(3))
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def remesh(vertices: np.ndarray, faces: np.ndarray, panels: int = DEFAULT_PANELS_3D):
    """Remesh an open or closed triangle surface with about ``panels`` near-equilateral
    triangles (gmsh). Returns (vertices (N, 3), faces (M, 3)) with the input's orientation.

    Patch boundaries add triangles, so when the first mesh misses ``panels`` by more than 25 %
    the size is corrected by √(count/panels) and the surface meshed once more.
    """
    area = float(triangle_areas(vertices, faces).sum())
    size = np.sqrt(4.0 * area / (np.sqrt(3.0) * panels))  # equilateral triangles of side `size`
    new_vertices, new_faces = _gmsh_mesh(vertices, faces, size)
    if abs(len(new_faces) / panels - 1.0) > 0.25:
        size *= np.sqrt(len(new_faces) / panels)
        new_vertices, new_faces = _gmsh_mesh(vertices, faces, size)
    return new_vertices, new_faces


def _gmsh_mesh(vertices: np.ndarray, faces: np.ndarray, size: float):
    """One gmsh pass: discrete surface → classified patches → triangles of side ``size``."""
    with gmshio.session("wetted", verbosity=0) as gmsh:
        surface = gmsh.model.addDiscreteEntity(2)
        gmsh.model.mesh.addNodes(2, surface, np.arange(1, len(vertices) + 1), vertices.ravel())
        gmsh.model.mesh.addElementsByType(surface, 2, [], (faces + 1).ravel())
        gmsh.model.mesh.classifySurfaces(np.radians(FEATURE_ANGLE), True, True, np.pi)
        gmsh.model.mesh.createGeometry()
        for name, value in (("MeshSizeFromCurvature", 0), ("MeshSizeExtendFromBoundary", 0),
                            ("MeshSizeFromPoints", 0), ("MeshSizeMin", size),
                            ("MeshSizeMax", size)):
            gmsh.option.setNumber(f"Mesh.{name}", value)
        gmsh.model.mesh.generate(2)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        node_tags = gmsh.model.mesh.getElementsByType(2)[1]
    new_vertices, new_faces = _triangles(tags, coords, node_tags)
    used = np.unique(new_faces)
    renumber = np.zeros(len(new_vertices), dtype=np.int64)
    renumber[used] = np.arange(len(used))
    return new_vertices[used], renumber[new_faces]


def symmetry_planes(triangles: np.ndarray, rel_tol: float = SYMMETRY_TOL) -> tuple[str, ...]:
    """Planes of reflection symmetry of a wetted surface: "xOz" (y → −y) and/or "yOz"
    (x → −x).

    A surface symmetric about y = 0 has every moment odd in y equal to zero; the test asks it of
    ∫ y dS, ∫ y³ dS, ∫ y x dS, ∫ y z dS, ∫ y x² dS and ∫ y z² dS (lengths scaled by the size),
    to ``rel_tol`` of the area: a marching-cubes or STL surface of a symmetric body passes at
    the level of its own discretisation, a heeled or bow-stern asymmetric one does not.
    """
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    size = float(np.ptp(triangles.reshape(-1, 3), axis=0).max())
    shift = np.array([0.0, 0.0, float(triangles[..., 2].mean())])
    # Strang & Fix 4-point rule, exact for cubic integrands on a triangle
    rule = [(-27.0 / 48.0, (a + b + c) / 3.0)] + [
        (25.0 / 48.0, 0.6 * p + 0.2 * q + 0.2 * r) for p, q, r in ((a, b, c), (b, c, a),
                                                                      (c, a, b))]
    planes = []
    for plane, axis in (("xOz", 1), ("yOz", 0)):
        total = np.zeros(6)
        for weight, point in rule:
            scaled = (point - shift) / size
            s = scaled[:, axis]
            u, v = (scaled[:, k] for k in range(3) if k != axis)
            odd = np.stack([s, s**3, s * u, s * v, s * u * u, s * v * v])
            total += weight * (odd @ area)
        if np.abs(total).max() <= rel_tol * area.sum():
            planes.append(plane)
    return tuple(planes)


# Rotations taking the half-space {coordinate ≥ 0} to {z ≤ 0}, so that the free-surface
# clipping of the hydrostatics cuts along the symmetry planes too.
_TO_BELOW = {"xOz": np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]),
             "yOz": np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])}


def keep_side(triangles: np.ndarray, plane: str) -> np.ndarray:
    """Parts of the triangles on the positive side of a symmetry plane (y ≥ 0 for "xOz",
    x ≥ 0 for "yOz"), orientation kept."""
    rot = _TO_BELOW[plane]
    return clip_triangles(triangles @ rot.T) @ rot


def wetted_hull(body, z_c: float, heel: float, trim: float, panels: int = DEFAULT_PANELS_3D,
                *, symmetry: bool = True):
    """BEM hull mesh of a 3D body's wetted surface at an attitude, earth frame, z ≤ 0, normals
    out of the body, about ``panels`` triangles in all.

    When the wetted surface is symmetric about y = 0 and/or x = 0, only the half (y ≥ 0) or the
    quarter (x ≥ 0, y ≥ 0) is meshed; Capytaine rebuilds the whole by reflection and solves
    2 or 4 times smaller blocks.

    Returns (vertices, faces, planes): the meshed piece and its symmetry planes.
    """
    triangles = wetted_triangles(body, z_c, heel, trim)
    if len(triangles) == 0:
        raise ValueError("the body is out of the water: no wetted surface to mesh")
    planes = symmetry_planes(triangles) if symmetry else ()
    for plane in planes:
        triangles = keep_side(triangles, plane)
    vertices, faces = merge_vertices(triangles)
    vertices, faces = remesh(vertices, faces, max(panels // 2 ** len(planes), 16))
    vertices[:, 2] = np.minimum(vertices[:, 2], 0.0)  # round-off above the free surface
    for plane in planes:  # round-off across the symmetry planes
        axis = 1 if plane == "xOz" else 0
        vertices[:, axis] = np.maximum(vertices[:, axis], 0.0)
    return vertices, faces, planes


def panel_size(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Side of the equilateral triangle of the mean panel area."""
    return float(np.sqrt(4.0 * triangle_areas(vertices, faces).mean() / np.sqrt(3.0)))


def waterline_chain(vertices: np.ndarray, faces: np.ndarray, rel_tol: float = 1e-9):
    """Vertex indices of the hull's waterline, in order: the boundary edges lying on z = 0,
    chained head to tail (an open chain for a half or quarter hull, closed for a whole one).
    Returns None when the waterline is not a single chain (several waterplanes)."""
    tol = rel_tol * float(np.ptp(vertices, axis=0).max())
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    edges = {tuple(e) for e in directed.tolist()}
    on_surface = np.abs(vertices[:, 2]) <= tol
    nxt = {a: b for a, b in edges if (b, a) not in edges and on_surface[a] and on_surface[b]}
    if not nxt:
        return None
    starts = set(nxt) - set(nxt.values())
    if len(starts) > 1:
        return None
    chain = [starts.pop() if starts else next(iter(nxt))]
    while chain[-1] in nxt and len(chain) <= len(nxt):
        chain.append(nxt[chain[-1]])
    if len(chain) - 1 != len(nxt):
        return None
    return chain


def waterplane_lid(vertices: np.ndarray, faces: np.ndarray, planes: tuple[str, ...],
                   size: float):
    """Triangle mesh (vertices, faces) of the interior waterplane, for irregular-frequency
    removal: the region bounded by the waterline and, for a half or quarter hull, the symmetry
    planes, meshed by gmsh with triangles of side ``size``. None if the waterline is not one
    chain (then Capytaine's own lid is used)."""
    chain = waterline_chain(vertices, faces)
    if chain is None:
        return None
    points = [vertices[i, :2] for i in chain]
    closed = chain[0] == chain[-1]
    if closed:
        points = points[:-1]
    elif planes == ("xOz",) or planes == ("yOz",):
        pass  # the closing segment runs along the plane
    elif len(planes) == 2:
        points.append(np.zeros(2))  # the corner where the two planes meet
    else:
        return None
    with gmshio.session("lid", verbosity=0) as gmsh:
        tags = [gmsh.model.geo.addPoint(x, y, 0.0, size) for x, y in points]
        lines = []
        for k, (a, b) in enumerate(zip(tags, tags[1:] + tags[:1], strict=True)):
            lines.append(gmsh.model.geo.addLine(a, b))
            # waterline segments keep the hull's nodes (one element each); the closing
            # segments along the symmetry planes get elements of about `size`
            length = float(np.linalg.norm(points[(k + 1) % len(points)] - points[k]))
            count = 2 if k < len(chain) - 1 else max(2, int(np.ceil(length / size)) + 1)
            gmsh.model.geo.mesh.setTransfiniteCurve(lines[-1], count)
        loop = gmsh.model.geo.addCurveLoop(lines)
        gmsh.model.geo.addPlaneSurface([loop])
        gmsh.model.geo.synchronize()
        for name, value in (("MeshSizeExtendFromBoundary", 0), ("MeshSizeMin", size),
                            ("MeshSizeMax", size)):
            gmsh.option.setNumber(f"Mesh.{name}", value)
        gmsh.model.mesh.generate(2)
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        element_tags = gmsh.model.mesh.getElementsByType(2)[1]
    lid_vertices, lid_faces = _triangles(node_tags, coords, element_tags)
    lid_vertices[:, 2] = 0.0
    return lid_vertices, lid_faces


def _triangles(node_tags, coords, element_nodes):
    """Vertices (N, 3) and 0-based triangles (M, 3) from gmsh's node tags and the node tags of
    its 3-node triangles."""
    index = np.zeros(int(node_tags.max()) + 1, dtype=np.int64)
    index[node_tags.astype(np.int64)] = np.arange(len(node_tags))
    return coords.reshape(-1, 3), index[element_nodes.astype(np.int64)].reshape(-1, 3)


def section_panels(body, z_c: float, heel: float, panels: int) -> np.ndarray:
    """Panel nodes (N+1, 2) of a 2D section's wetted contour, earth frame (y, z)."""
    return panel_nodes(wetted_contour(body.section_polygon(), z_c, heel), panels)
