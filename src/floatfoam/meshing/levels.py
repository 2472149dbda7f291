"""Mesh levels (the tank and the poses: :mod:`floatfoam.tank`).

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

from dataclasses import dataclass

from floatfoam.case import Case
from floatfoam.plan.level import level_index, refinement_ratio
from floatfoam.tank import body_extents


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
    curvature_size : the smallest surface cell the curvature makes (2D, wedge),
        body_size / curvature_refinement
    growth, growth_3d : grading away from the body (coarse values; see the module docstring)
    layers_3d, layers_height_3d : prism layers at the body in 3D (a body given by triangles,
        or an ellipsoid): their count (0: none) and total height (m)
    band_prisms_3d : the 3D free-surface band in horizontal layers of prisms outside a column
        about the body (:mod:`floatfoam.meshing.domain3d`)
    optimize_netgen_3d : the 3D tetrahedra optimised by Netgen's optimiser after gmsh's own
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
    curvature_size: float
    growth: float
    growth_3d: float
    margin: float
    layers_3d: int = 0
    layers_height_3d: float = 0.0
    band_prisms_3d: bool = False
    optimize_netgen_3d: bool = True

    def refine(self, count: float) -> int:
        """A coarse-level cell count at this level: round(count r^index), at least 1."""
        return max(1, round(count * self.ratio**self.index))


def mesh_spec(case: Case, level: str) -> MeshSpec:
    """Sizes of ``level`` for ``case``: ``[mesh.gmsh]`` (defaults and ranges in
    :class:`floatfoam.settings.GmshSettings`), the ratio ``mesh.refinement_ratio``."""
    index = level_index(level)
    cfg = case.settings.mesh.gmsh
    ratio = refinement_ratio(case)
    extents = body_extents(case.body)
    length, span = float(extents.min()), float(extents.max())
    scale = ratio**index
    body_size = length / (cfg.body_cells * scale)
    return MeshSpec(
        level=level, index=index, ratio=ratio, length=length, span=span,
        body_size=body_size,
        body_size_3d=length / (cfg.body_cells_3d * scale),
        curvature_points=cfg.curvature_cells * scale,
        curvature_size=body_size / cfg.curvature_refinement,
        growth=cfg.growth, growth_3d=cfg.growth_3d, margin=cfg.margin * length,
        layers_3d=cfg.layers_3d,
        layers_height_3d=cfg.layers_height_3d * length / (cfg.body_cells_3d * scale),
        band_prisms_3d=cfg.band_prisms_3d, optimize_netgen_3d=cfg.optimize_netgen_3d)
