"""gmsh plumbing: one session at a time, mesh data out as NumPy arrays, files out.

gmsh keeps one global model; :func:`session` opens it, sets quiet single-threaded defaults (the
cores belong to the solver), keeps the process's signal handlers (which gmsh's first initialize
resets) and always finalises it, even when meshing fails. Sessions do not
nest: compute what needs its own session (e.g. the body's polygon) before opening another.
"""

from __future__ import annotations

import struct
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from floatfoam.bodies.geometry import outward_pieces
from floatfoam.interrupts import handlers_kept

TRIANGLE, QUAD = 2, 3  # gmsh element types


@contextmanager
def session(name: str = "floatfoam", verbosity: int = 1):
    """Open a gmsh model ``name``; yield the ``gmsh`` module; finalise on exit."""
    import gmsh

    if gmsh.isInitialized():
        raise RuntimeError("a gmsh session is already open: gmsh has one global model")
    with handlers_kept():  # gmsh's first initialize resets SIGTERM, SIGHUP and SIGPIPE
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Verbosity", verbosity)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add(name)
        yield gmsh
    finally:
        gmsh.finalize()


def node_table() -> tuple[np.ndarray, np.ndarray]:
    """All mesh nodes: (tags, coordinates (N, 3)), tags sorted."""
    import gmsh

    tags, coords, _ = gmsh.model.mesh.getNodes(returnParametricCoord=False)
    order = np.argsort(tags)
    return tags[order].astype(np.int64), coords.reshape(-1, 3)[order]


def surface_triangles(surface_tags) -> tuple[np.ndarray, np.ndarray]:
    """Triangles of the surfaces ``surface_tags`` as one compact (vertices, faces) mesh, nodes
    shared where the surfaces meet, every surface oriented like its neighbours (gmsh orients
    each surface's elements by its own parametrisation, not by the volume it bounds)."""
    _, vertices, faces = surface_mesh(surface_tags)
    return vertices, faces


def surface_mesh(surface_tags) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`surface_triangles` with the gmsh tags of its vertices: (tags, vertices, faces)."""
    import gmsh

    patches = [gmsh.model.mesh.getElementsByType(TRIANGLE, abs(tag))[1].reshape(-1, 3)
               .astype(np.int64) for tag in surface_tags]
    elements = np.concatenate(consistent_orientation(patches))
    tags, coords = node_table()
    used, inverse = np.unique(elements, return_inverse=True)
    vertices = coords[np.searchsorted(tags, used)]
    return used, vertices, outward_pieces(vertices, inverse.reshape(-1, 3))[0]


def consistent_orientation(patches: list[np.ndarray]) -> list[np.ndarray]:
    """Flip whole patches (each consistently oriented in itself) so that every edge shared by
    two patches is run in opposite directions by them (breadth-first over the patches, from
    the first of each separate piece)."""
    directed = [{e for tri in p.tolist() for e in ((tri[0], tri[1]), (tri[1], tri[2]),
                                                   (tri[2], tri[0]))} for p in patches]
    flipped = [None] * len(patches)
    queue = []
    while queue or None in flipped:
        if not queue:  # the first patch of a piece not reached yet
            start = flipped.index(None)
            flipped[start] = False
            queue = [start]
        i = queue.pop()
        edges_i = directed[i] if not flipped[i] else {(b, a) for a, b in directed[i]}
        for j in range(len(patches)):
            if flipped[j] is not None:
                continue
            if edges_i & directed[j]:
                flipped[j] = True
            elif edges_i & {(b, a) for a, b in directed[j]}:
                flipped[j] = False
            else:
                continue
            queue.append(j)
    return [p[:, ::-1] if f else p for p, f in zip(patches, flipped, strict=True)]


def curve_chain(curve_tags) -> np.ndarray:
    """Nodes of the 1D mesh of ``curve_tags`` chained into one path (closed loops are returned
    without repeating the first node), coordinates (N, 3)."""
    import gmsh

    segments = np.concatenate([
        gmsh.model.mesh.getElementsByType(1, abs(tag))[1].reshape(-1, 2) for tag in curve_tags
    ]).astype(np.int64)
    neighbours: dict[int, list[int]] = {}
    for a, b in segments.tolist():
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)
    ends = [n for n, adj in neighbours.items() if len(adj) == 1]
    start = ends[0] if ends else segments[0, 0]
    path, previous = [int(start)], None
    while True:
        options = [n for n in neighbours[path[-1]] if n != previous]
        if not options or (not ends and options[0] == path[0]):
            break
        previous = path[-1]
        path.append(options[0])
        if len(path) > len(neighbours):
            raise RuntimeError("the body's curves do not form one chain")
    tags, coords = node_table()
    return coords[np.searchsorted(tags, np.array(path))]


def element_counts(dim: int) -> dict[str, int]:
    """Number of mesh elements of dimension ``dim`` by type name (e.g. Hexahedron 8)."""
    import gmsh

    counts: dict[str, int] = {}
    types, tags, _ = gmsh.model.mesh.getElements(dim)
    for etype, etags in zip(types, tags, strict=True):
        name = gmsh.model.mesh.getElementProperties(etype)[0].split()[0]
        counts[name] = counts.get(name, 0) + len(etags)
    return counts


def write_msh22(path: Path) -> Path:
    """Write the mesh as MSH 2.2 ASCII (what gmshToFoam reads): physical entities only."""
    import gmsh

    path.parent.mkdir(parents=True, exist_ok=True)
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.option.setNumber("Mesh.SaveAll", 0)
    gmsh.write(str(path))
    return path


def write_stl(path: Path, vertices: np.ndarray, faces: np.ndarray, name: str = "body") -> Path:
    """Binary STL of a triangle mesh (float32 coordinates; the header names the solid but does
    not start with "solid", which readers take for an ASCII file)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tri = vertices[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    normals /= np.where(lengths > 0, lengths, 1.0)[:, None]
    record = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    data = np.zeros(len(faces), dtype=record)
    data["n"], data["v"] = normals, tri
    header = f"{name}: floatfoam binary STL, metres".encode()[:80].ljust(80, b" ")
    with open(path, "wb") as fh:
        fh.write(header + struct.pack("<I", len(faces)))
        fh.write(data.tobytes())
    return path


#: OpenFOAM's prism (cellModels): its faces, outwards, by its points' places — gmsh's order
_PRISM_FACES = ((0, 2, 1), (3, 4, 5), (0, 3, 5, 2), (1, 2, 5, 4), (0, 1, 4, 3))


def inside_out_prisms(volumes: list[int]) -> int:
    """How many prisms of the ``volumes`` gmshToFoam takes for inside out: a face at least
    whose area normal points towards the cell's centre (OpenFOAM's: of the pyramids its faces
    make with its points' mean) from the face's first point — gmshToFoam's test. gmshToFoam
    "corrects" such a prism by swapping two points of one triangle only, which crosses two of
    its quadrangles: the cells beside them then find no face to share, and gmshToFoam leaves
    those faces in a patch of their own. A prism layer folded over at a thin edge (a hull's
    knife-edge keel) makes them."""
    import gmsh

    tags, coords = node_table()
    count = 0
    for tag in volumes:
        types, _, nodes = gmsh.model.mesh.getElements(3, tag)
        for etype, flat in zip(types, nodes, strict=True):
            if etype != 6:  # prisms
                continue
            points = coords[np.searchsorted(tags, np.asarray(flat).reshape(-1, 6))]
            guess = points.mean(axis=1)
            faces = [_face_centre_normal(points[:, face]) for face in _PRISM_FACES]
            volume, moment = 0.0, 0.0
            for centre, normal in faces:  # the pyramids from the points' mean
                pyramid = np.sum(normal * (centre - guess), axis=1) / 3.0
                volume = volume + pyramid
                moment = moment + pyramid[:, None] * (0.75 * centre + 0.25 * guess)
            cell = moment / (volume[:, None] + 1e-300)
            wrong = np.zeros(len(points), dtype=bool)
            for face, (_, normal) in zip(_PRISM_FACES, faces, strict=True):
                wrong |= np.sum(normal * (points[:, face[0]] - cell), axis=1) < 0.0
            count += int(np.sum(wrong))
    return count


def _face_centre_normal(p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """OpenFOAM's face centre and area normal of faces ``p`` (n, 3 or 4 points, 3): a
    triangle's points' mean and half its cross product; else the area-weighted centres of the
    triangles each edge makes with the points' mean, and the sum of their area normals."""
    if p.shape[1] == 3:
        return p.mean(axis=1), 0.5 * np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    mean = p.mean(axis=1)
    normal, weighted, total = 0.0, 0.0, 0.0
    for j in range(p.shape[1]):
        a, b = p[:, j], p[:, (j + 1) % p.shape[1]]
        cross = np.cross(a - mean, b - mean)
        area = np.linalg.norm(cross, axis=1)
        normal = normal + 0.5 * cross
        weighted = weighted + area[:, None] * (a + b + mean) / 3.0
        total = total + area
    centre = np.where(total[:, None] > 1e-300, weighted / np.maximum(total, 1e-300)[:, None],
                      mean)
    return centre, normal
