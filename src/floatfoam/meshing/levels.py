"""Mesh levels, the tank around the body and the body's poses.

Three levels, coarse → medium → fine, refine **every** size parameter by one constant ratio r
(default √2): cell sizes are divided by r, cell counts of structured blocks multiplied by r
(with their geometric progressions q → q^(1/r), so that every level samples the same spacing
function), the curvature resolution multiplied by r. A 2D mesh then gains r² = 2 cells per
level and a 3D mesh r³ ≈ 2.8, as Celik et al. (2008, J. Fluids Eng. 130, 078001) ask of a
grid-convergence study (r > 1.3, same mesh topology).

Why √2 rather than 2: on two cores the fine 3D mesh would be 64× the coarse one with r = 2 but
only 8× with √2, and the three levels then stay closer to one another (and to the asymptotic
range) for the same budget; Celik's r > 1.3 is still met.

Sizes scale with two lengths of the body: D, its smallest dimension across (y, z for a 2D
section, x, y, z otherwise), which sets the cell size; and the span S, its largest, which sets
the tank. The case's tables override the defaults: ``[domain]`` (the tank, shared by every
mesher), ``mesh.refinement_ratio`` (shared by every mesher) and ``[mesh.gmsh]`` (the sizes of
these gmsh meshes; other keys of ``[mesh]`` belong to other meshers, e.g. a blockMesh O-grid,
and are left alone).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.layout import LEVELS

DOMAIN_DEFAULTS = {  # × the body's span S (its largest dimension), unless a physical value
    "half_length": 20.0,  # tank half-length (y for a 2D section, x in 3D, radius of a wedge)
    "air_height": 3.0,  # air above the free surface
    "deep_depth": 10.0,  # water depth when fluid.depth is infinite
}


@dataclass(frozen=True)
class MeshSpec:
    """Sizes of one mesh level (lengths in m).

    Attributes
    ----------
    level, index : name and position (0 coarse, 1 medium, 2 fine)
    ratio : refinement ratio r between levels
    length : D, the body's smallest dimension across
    span : S, the body's largest dimension
    body_size : surface cell size on the body, D / (body_cells r^index)
    body_size_3d : same for 3D volume meshes
    curvature_points : cells per 2π of turning, curvature_cells r^index
    growth, growth_3d : grading away from the body (coarse values; see the module docstring)
    layers_3d, layers_height_3d : prism layers at the body in 3D (a body given by triangles,
        or an ellipsoid): their count (0: none) and total height (m)
    margin : half-thickness of the core block around the body, m
    """

    level: str
    index: int
    ratio: float
    length: float
    span: float
    body_size: float
    body_size_3d: float
    curvature_points: float
    growth: float
    growth_3d: float
    margin: float
    layers_3d: int = 0
    layers_height_3d: float = 0.0

    def refine(self, count: float) -> int:
        """A coarse-level cell count at this level: round(count r^index), at least 1."""
        return max(1, round(count * self.ratio**self.index))


@dataclass(frozen=True)
class Tank:
    """Fluid domain around the body, earth frame, free surface z = 0 (m).

    ``half_length`` is along y for a 2D section (its plane of motion is y-z), along x in 3D and
    the radius of a wedge; ``half_width`` is along y in 3D; ``band`` is the half-height of the
    free-surface band of fine cells; ``thickness`` the x-extent of a 2D mesh (default: the
    section's length L, so that forces and the case's mass are for the same length)."""

    half_length: float
    half_width: float
    depth: float
    air_height: float
    band: float
    thickness: float


@dataclass(frozen=True)
class Pose:
    """Placement of the body frame in the earth frame: z_c (m), heel and trim (radians)."""

    z_c: float = 0.0
    heel: float = 0.0
    trim: float = 0.0


POSES = ("body", "equilibrium", "release")


def body_extents(body) -> np.ndarray:
    """Extents of the body that set the mesh: (y, z) for a 2D section, (x, y, z) otherwise."""
    extents = np.asarray(body.hi, dtype=float) - np.asarray(body.lo, dtype=float)
    return extents[1:] if body.is_section else extents


def level_index(level: str) -> int:
    if level not in LEVELS:
        raise InputError(f"--level {level!r}: valid levels are {', '.join(LEVELS)}")
    return LEVELS.index(level)


def refinement_ratio(case: Case) -> float:
    """The ratio r between consecutive levels: ``mesh.refinement_ratio`` (default √2), > 1."""
    return case.settings.mesh.refinement_ratio


def mesh_spec(case: Case, level: str) -> MeshSpec:
    """Sizes of ``level`` for ``case``: ``[mesh.gmsh]`` (defaults and ranges in
    :class:`floatfoam.settings.GmshSettings`), the ratio ``mesh.refinement_ratio``."""
    index = level_index(level)
    cfg = case.settings.mesh.gmsh
    ratio = refinement_ratio(case)
    extents = body_extents(case.body)
    length, span = float(extents.min()), float(extents.max())
    scale = ratio**index
    return MeshSpec(
        level=level, index=index, ratio=ratio, length=length, span=span,
        body_size=length / (cfg.body_cells * scale),
        body_size_3d=length / (cfg.body_cells_3d * scale),
        curvature_points=cfg.curvature_cells * scale,
        growth=cfg.growth, growth_3d=cfg.growth_3d, margin=cfg.margin * length,
        layers_3d=cfg.layers_3d,
        layers_height_3d=cfg.layers_height_3d * length / (cfg.body_cells_3d * scale))


def tank(case: Case) -> Tank:
    """The tank of ``case``: its ``[domain]`` table, defaults scaled by the body's span."""
    values = {k: v for k, v in vars(case.settings.domain).items() if v is not None}
    extents = body_extents(case.body)
    span, length = float(extents.max()), float(extents.min())
    if math.isfinite(case.depth):
        values["depth"] = case.depth  # the case checked that domain.depth agrees
    half_length = values.get("half_length", DOMAIN_DEFAULTS["half_length"] * span)
    heave = abs(case.release["heave"])
    tilt = math.sin(math.radians(max(abs(case.release["heel"]), abs(case.release["trim"]))))
    return Tank(
        half_length=half_length,
        half_width=values.get("half_width", half_length),
        depth=values.get("depth", DOMAIN_DEFAULTS["deep_depth"] * span),
        air_height=values.get("air_height", DOMAIN_DEFAULTS["air_height"] * span),
        # the band holds the waterline over the first oscillation: release offset, the
        # waterline's shift at the body's side for the release angle, and D/4 of waves
        band=values.get("band", 0.25 * length + heave + 0.5 * span * tilt),
        thickness=values.get("thickness", case.body.length or length),
    )


def pose(case: Case, which: str = "release", equilibrium=None) -> Pose:
    """The body frame's placement: ``body`` (identity), ``equilibrium`` (the theory's) or
    ``release`` (equilibrium + the case's [release] offsets: the initial state of a decay
    test). ``equilibrium`` may be passed to avoid solving for it again."""
    if which not in POSES:
        raise InputError(f"--pose {which!r}: valid poses are {', '.join(POSES)}")
    if which == "body":
        return Pose()
    if equilibrium is None:
        from floatfoam.hydrostatics.theory import equilibrium as solve

        equilibrium = solve(case)
    base = Pose(equilibrium.z_c, equilibrium.heel, equilibrium.trim)
    if which == "equilibrium":
        return base
    rel = case.release
    return Pose(base.z_c + rel["heave"], base.heel + math.radians(rel["heel"]),
                base.trim + math.radians(rel["trim"]))
