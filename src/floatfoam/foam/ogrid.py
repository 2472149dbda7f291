"""blockMesh O-grid for a 2D tank around a circular section (the (y, z) plane, one cell in x).

Four O-grid blocks join the cylinder to a square of half-size b centred on the body; eight
graded Cartesian blocks reach the tank walls, the bottom and the top of the air. Every cell
count scales with the level's refinement factor; the cells along the square's sides set the
size h = 2b/N that the outer blocks grow from geometrically.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class OGrid:
    """Dimensions (m) and cell counts of the O-grid tank; ``factor`` multiplies the counts."""

    radius: float
    centre_z: float  # height of the cylinder's axis at release
    half_length: float
    depth: float
    air_height: float
    thickness: float
    square: float  # half-size b of the square around the body
    cells_side: int
    cells_radial: int
    radial_grading: float
    cells_horizontal: int
    cells_below: int
    cells_above: int
    factor: float = 1.0

    def n(self, base: int) -> int:
        return max(1, int(round(base * self.factor)))

    @property
    def side_cell(self) -> float:
        return 2.0 * self.square / self.n(self.cells_side)

    def cell_count(self) -> int:
        nt, nr = self.n(self.cells_side), self.n(self.cells_radial)
        ny, nb, na = (self.n(c) for c in (self.cells_horizontal, self.cells_below,
                                          self.cells_above))
        return 4 * nr * nt + 2 * ny * nt + nt * (nb + na) + 2 * ny * (nb + na)


def expansion_ratio(length: float, first: float, cells: int) -> float:
    """Last-to-first cell ratio of ``cells`` geometric cells over ``length`` whose first cell
    is ``first`` (bisection on the common ratio)."""
    if abs(first * cells - length) < 1e-12 * length:
        return 1.0
    lo, hi = 1e-6, 10.0
    for _ in range(200):
        r = 0.5 * (lo + hi)
        total = first * (r**cells - 1.0) / (r - 1.0) if abs(r - 1.0) > 1e-12 else first * cells
        lo, hi = (r, hi) if total < length else (lo, r)
    return r ** (cells - 1)


def block_mesh_dict(g: OGrid) -> dict:
    """The blockMeshDict entries (vertices, blocks, edges, boundary) of the O-grid tank.

    Patches (:mod:`floatfoam.foam.patches`): ``body``, ``bottom``, ``sides`` (the tank's
    ends), ``atmosphere`` (top), ``frontAndBack`` (empty).
    """
    a, zc, b, t = g.radius, g.centre_z, g.square, g.thickness
    if not a < b < min(g.half_length, g.depth + zc, g.air_height - zc):
        raise ValueError("the O-grid square must hold the body and fit in the tank")
    ys = [-g.half_length, -b, b, g.half_length]
    zs = [-g.depth, zc - b, zc + b, g.air_height]
    pts: list[tuple[float, float]] = []
    corner = [[_add(pts, y, z) for z in zs] for y in ys]
    c = a / math.sqrt(2.0)
    ring = [_add(pts, c, zc - c), _add(pts, c, zc + c), _add(pts, -c, zc + c),
            _add(pts, -c, zc - c)]
    square = [corner[2][1], corner[2][2], corner[1][2], corner[1][1]]
    k = len(pts)

    def hex_(quad):
        return [*quad, *(q + k for q in quad)]

    nt, nr = g.n(g.cells_side), g.n(g.cells_radial)
    ny, nb, na = g.n(g.cells_horizontal), g.n(g.cells_below), g.n(g.cells_above)
    h = g.side_cell
    ry = expansion_ratio(g.half_length - b, h, ny)
    rb = expansion_ratio(g.depth + zc - b, h, nb)
    ra = expansion_ratio(g.air_height - zc - b, h, na)
    blocks: list = []
    for i in range(4):  # O-grid: radial first, then along the ring (counter-clockwise)
        quad = (ring[i], square[i], square[(i + 1) % 4], ring[(i + 1) % 4])
        blocks += ["hex", hex_(quad), [nr, nt, 1], "simpleGrading", [g.radial_grading, 1, 1]]
    counts_y, counts_z = [ny, nt, ny], [nb, nt, na]
    grade_y, grade_z = [1 / ry, 1.0, ry], [1 / rb, 1.0, ra]
    for i in range(3):
        for j in range(3):
            if i == j == 1:
                continue
            quad = (corner[i][j], corner[i + 1][j], corner[i + 1][j + 1], corner[i][j + 1])
            blocks += ["hex", hex_(quad), [counts_y[i], counts_z[j], 1], "simpleGrading",
                       [round(grade_y[i], 8), round(grade_z[j], 8), 1]]
    edges: list = []
    mids = [(a, zc), (0.0, zc + a), (-a, zc), (0.0, zc - a)]
    for i, (my, mz) in enumerate(mids):
        p, q = ring[i], ring[(i + 1) % 4]
        edges += ["arc", p, q, [0.0, my, mz], "arc", p + k, q + k, [t, my, mz]]

    def face(p, q):
        return [p, q, q + k, p + k]

    body = [face(ring[(i + 1) % 4], ring[i]) for i in range(4)]
    left = [face(corner[0][j + 1], corner[0][j]) for j in range(3)]
    right = [face(corner[3][j], corner[3][j + 1]) for j in range(3)]
    bottom = [face(corner[i][0], corner[i + 1][0]) for i in range(3)]
    top = [face(corner[i + 1][3], corner[i][3]) for i in range(3)]
    vertices = [[0.0, y, z] for y, z in pts] + [[t, y, z] for y, z in pts]
    return {
        "convertToMeters": 1,
        "vertices": [[round(v, 10) for v in p] for p in vertices],
        "blocks": blocks,
        "edges": edges,
        "boundary": [
            ("body", {"type": "wall", "faces": body}),
            ("bottom", {"type": "wall", "faces": bottom}),
            ("sides", {"type": "wall", "faces": left + right}),
            ("atmosphere", {"type": "patch", "faces": top}),
        ],
        "defaultPatch": {"name": "frontAndBack", "type": "empty"},
    }


def _add(pts: list, y: float, z: float) -> int:
    pts.append((y, z))
    return len(pts) - 1
