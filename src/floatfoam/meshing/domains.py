"""One entry point for the fluid domains: pick the kind, mesh, write, check the body patch.

Kinds: ``2d`` (2D sections, one cell thick), ``wedge`` (bodies of revolution about z, upright),
``3d`` (any body), ``3d-half`` (x ≥ 0 and a symmetry plane x = 0 for a heel or a heave, y ≥ 0
and y = 0 for a trim: a body symmetric about that plane, an STL's found so from its
triangles, and a motion that keeps it). ``auto`` takes 2d for a
section, wedge for an upright body of revolution, 3d-half where it can, 3d otherwise
(:func:`floatfoam.plan.kind.default_kind`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from floatfoam.bodies.geometry import mesh_volume
from floatfoam.errors import InputError
from floatfoam.hydrostatics.immersion import immersed, mesh_immersed, section_immersed
from floatfoam.meshing import body_surface
from floatfoam.meshing.domain3d import domain_3d
from floatfoam.meshing.levels import mesh_spec
from floatfoam.meshing.planar import even_polygon, planar_domain
from floatfoam.plan.kind import check_layers, default_kind, half_plane
from floatfoam.tank import Pose, pose, tank

KINDS = ("auto", "2d", "wedge", "3d", "3d-half")


def build_domain(case, level: str, kind: str = "auto", pose_name: str = "release",
                 path: Path | None = None, equilibrium=None, where=None) -> dict:
    """Mesh the fluid domain of ``case`` at ``level`` with the body at a pose and write it
    (default ``build/<case>/mesh/<level>/domain_<kind>.msh``).

    Returns the summary of the mesher (``path``, ``cells``, ``cell_types``, ``patches``) with
    ``kind``, ``level``, ``sizes`` (m) and ``body_patch``: the immersed volume of the body
    patch at this pose against the exact body's there. ``equilibrium``: the case's, when it is
    already solved; ``where``: a pose of its own (a :class:`floatfoam.tank.Pose`, the body met
    on its way by a run's remeshing) instead of the named one.
    """
    if kind not in KINDS:
        raise InputError(f"--kind {kind!r}: valid kinds are {', '.join(KINDS)}")
    spec, box = mesh_spec(case, level), tank(case)
    if where is None:
        if equilibrium is None and pose_name != "body":
            from floatfoam.hydrostatics.theory import equilibrium as solve

            equilibrium = solve(case)
        where = pose(case, pose_name, equilibrium)
    kind = default_kind(case, where) if kind == "auto" else kind
    if kind == "2d" and not case.body.is_section:
        raise InputError(f"--kind 2d: the body of {case.name} is not a 2D section; valid kinds "
                         "for it are wedge (bodies of revolution about z) or 3d")
    if kind == "2d" and where.trim != 0.0:
        raise InputError(f"--kind 2d: {case.name} is trimmed at this pose; a 2D section cannot "
                         "trim: valid is release.trim = 0 or --kind 3d")
    from floatfoam.layout import case_build_dir

    path = Path(path) if path else case_build_dir(case.name) / "mesh" / level / \
        f"domain_{kind}.msh"
    check_layers(case, kind)
    half = half_plane(case, where) if kind == "3d-half" else None
    if kind == "3d-half" and half is None:
        raise InputError(f"--kind 3d-half: {case.name} keeps no symmetry plane at this pose (a "
                         "body symmetric about x = 0 with G on it and no trim, or about y = 0 "
                         "with G on it and no heel; mesh.gmsh.half_3d = true); valid kinds for "
                         "it: 3d")
    if kind in ("3d", "3d-half"):
        result = domain_3d(case, spec, box, where, path, half=half)
        vertices, faces = result.pop("body_triangles")
        if half:  # close the half body by its mirror image for the volume
            mirrored = vertices * ([-1.0, 1.0, 1.0] if half == "x" else [1.0, -1.0, 1.0])
            vertices = np.concatenate([vertices, mirrored])
            faces = np.concatenate([faces, faces[:, ::-1] + len(mirrored)])
        if mesh_volume(vertices, faces) < 0:
            faces = faces[:, ::-1]
        discrete = mesh_immersed(vertices, faces, 0.0, 0.0, 0.0).volume
    else:
        result = planar_domain(case, spec, box, where, kind, path)
        discrete = _planar_immersed(case, spec, where, kind)
    exact = immersed(case.body, where.z_c, where.heel, where.trim).volume
    result.update(kind=kind, level=level, pose=pose_name, sizes=_sizes(spec, box, kind),
                  body_patch={"immersed_discrete": discrete, "immersed_exact": exact,
                              "immersed_error": (discrete - exact) / exact if exact else 0.0})
    return result


def _planar_immersed(case, spec, where: Pose, kind: str) -> float:
    """Immersed volume of the body patch of a 2D or wedge mesh, from the same polygon."""
    if kind == "2d":
        polygon = even_polygon(body_surface.section_polygon(case.body, spec))
        return section_immersed(polygon, case.body.length, where.z_c, where.heel).volume
    polyline = body_surface.meridian_polyline(case.body, spec)
    imm = section_immersed(polyline, 1.0, where.z_c, 0.0)
    return 2.0 * math.pi * imm.volume * imm.centroid[1]


def _sizes(spec, box, kind: str) -> dict:
    """The size parameters of the level, for the tables."""
    body = spec.body_size_3d if kind.startswith("3d") else spec.body_size
    return {"body_cell": body, "band_half_height": box.band, "half_length": box.half_length,
            "depth": box.depth, "air_height": box.air_height,
            "half_width": box.half_width if kind.startswith("3d") else None,
            "thickness": box.thickness if kind == "2d" else None}


def format_domain(result: dict) -> str:
    """Readable lines of a :func:`build_domain` result."""
    types = ", ".join(f"{n} {k.lower()}" for k, n in result["cell_types"].items())
    patches = ", ".join(f"{k} {n}" for k, n in result["patches"].items())
    bp = result["body_patch"]
    sizes = result["sizes"]
    return "\n".join([
        f"{result['kind']} domain, {result['level']}, body at its {result['pose']} pose: "
        f"{result['cells']} cells ({types})",
        f"  body cell {sizes['body_cell'] * 1e3:.3g} mm, free-surface band ±"
        f"{sizes['band_half_height'] * 1e3:.3g} mm, tank half-length {sizes['half_length']:g} "
        f"m, depth {sizes['depth']:g} m, air {sizes['air_height']:g} m",
        f"  patches (faces): {patches}",
        f"  body patch immersed volume {bp['immersed_discrete']:.6g} m³ (exact body "
        f"{bp['immersed_exact']:.6g}, {bp['immersed_error']:+.2e})",
        f"  written {result['path']}",
        *([f"  note: {result['surface_note']}"] if result.get("surface_note") else []),
    ])
