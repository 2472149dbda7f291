"""The discrete body of a mesh level: the triangles of its surface and, for a 2D section, the
polygon of its section (and for a body of revolution, the polyline of its meridian).

The exact OpenCASCADE geometry (:mod:`floatfoam.meshing.sections`) is meshed by gmsh at the
level's surface cell size h = D / (body_cells r^level), refined where the surface turns fast
(``curvature_points`` cells per 2π of turning). Every mesh node lies on the exact surface, so the
discrete body is inscribed in the exact one and slightly smaller (by ~ h²/(8 R) per unit area
where the radius of curvature is R). Bodies given as triangles (``stl``, ``implicit``) are their
triangles: the theory uses the same ones, so they are exported as they are.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from floatfoam import gmshio
from floatfoam.bodies.geometry import to_earth
from floatfoam.meshing import sections
from floatfoam.meshing.levels import MeshSpec
from floatfoam.tank import Pose

SECTION_ASPECT = 4.0  # axial spacing of a section's prism ≤ 4 h: a closed, light STL


def size_options(gmsh, size: float, curvature_points: float, smallest: float = 0.0) -> None:
    """Surface cell size ``size`` everywhere, smaller where the curvature asks for it, down to
    ``smallest``."""
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", smallest)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", round(curvature_points))
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)  # Frontal-Delaunay: regular triangles


def section_polygon(body, spec: MeshSpec) -> np.ndarray:
    """The (y, z) polygon of a 2D section's mesh at this level, counter-clockwise (N, 2), body
    frame: the nodes gmsh puts on the exact section curve."""
    with gmshio.session("section") as gmsh:
        curves = sections.add_section(body, 0.0)
        gmsh.model.occ.synchronize()
        size_options(gmsh, spec.body_size, spec.curvature_points, spec.curvature_size)
        gmsh.model.mesh.generate(1)
        polygon = gmshio.curve_chain(curves)[:, 1:]
    return _counter_clockwise(polygon)


def meridian_polyline(body, spec: MeshSpec) -> np.ndarray:
    """The (r, z) polyline of a body of revolution's meridian at this level, from the keel
    (r = 0) to the top (r = 0), (N, 2)."""
    with gmshio.session("meridian") as gmsh:
        curves = sections.add_meridian(body)
        gmsh.model.occ.synchronize()
        size_options(gmsh, spec.body_size, spec.curvature_points, spec.curvature_size)
        gmsh.model.mesh.generate(1)
        chain = gmshio.curve_chain(curves)[:, [0, 2]]
    chain[np.abs(chain[:, 0]) < 1e-12 * spec.span, 0] = 0.0  # ends exactly on the axis
    return chain if chain[0, 1] < chain[-1, 1] else chain[::-1].copy()


def body_triangles(body, spec: MeshSpec) -> tuple[np.ndarray, np.ndarray]:
    """Closed, outward-oriented triangle mesh (vertices (N, 3), faces (T, 3)) of ``body`` at
    this level, in the body frame."""
    if body.given_by_triangles:
        return body.vertices, body.faces
    with gmshio.session("body") as gmsh:
        if body.is_section:
            layers = max(1, math.ceil(body.length / (SECTION_ASPECT * spec.body_size)))
            loop = gmsh.model.occ.addCurveLoop(sections.add_section(body, -body.length / 2))
            face = gmsh.model.occ.addPlaneSurface([loop])
            out = gmsh.model.occ.extrude([(2, face)], body.length, 0.0, 0.0,
                                         numElements=[layers])
            volume = next(tag for dim, tag in out if dim == 3)
        else:
            volume = sections.add_solid(body)
        gmsh.model.occ.synchronize()
        size_options(gmsh, spec.body_size, spec.curvature_points,
                     spec.curvature_size if body.is_section else 0.0)
        gmsh.model.mesh.generate(2)
        boundary = gmsh.model.getBoundary([(3, volume)], oriented=False)
        vertices, faces = gmshio.surface_triangles([tag for _, tag in boundary])
    return vertices, faces  # outward (gmshio.surface_mesh)


def place(vertices: np.ndarray, where: Pose) -> np.ndarray:
    """Body-frame points (N, 3) placed in the earth frame at a pose."""
    return to_earth(vertices, where.z_c, where.heel, where.trim) + [where.x_c, where.y_c, 0.0]


def place_section(polygon: np.ndarray, where: Pose) -> np.ndarray:
    """A (y, z) section polygon heeled, raised and swayed to a pose (a 2D section has no
    trim)."""
    c, s = math.cos(where.heel), math.sin(where.heel)
    y, z = polygon[:, 0], polygon[:, 1]
    return np.column_stack([c * y - s * z + where.y_c, s * y + c * z + where.z_c])


def write_body(case, spec: MeshSpec, where: Pose, folder: Path, stem: str = "body") -> dict:
    """Write ``<stem>.stl`` (and ``<stem>_section.csv``, columns y,z, for a 2D section) into
    ``folder`` at a pose; return the paths written."""
    vertices, faces = body_triangles(case.body, spec)
    written = {"stl": gmshio.write_stl(folder / f"{stem}.stl", place(vertices, where), faces)}
    if case.body.is_section:
        polygon = place_section(section_polygon(case.body, spec), where)
        written["section"] = folder / f"{stem}_section.csv"
        np.savetxt(written["section"], polygon, delimiter=",", header="y,z", comments="",
                   fmt="%.12g")
    return written


def _counter_clockwise(polygon: np.ndarray) -> np.ndarray:
    y, z = polygon[:, 0], polygon[:, 1]
    area = 0.5 * float(np.sum(y * np.roll(z, -1) - np.roll(y, -1) * z))
    return polygon if area > 0 else polygon[::-1].copy()
