"""Join a 3D mesh's prisms to the tetrahedra beside them across a side split in two.

The free-surface band of a 3D tank is made of prisms whose sides towards the column about the
body are quadrangles, which the column's tetrahedra meet as two triangles each
(:func:`floatfoam.meshing.domain3d.split_walls`). gmshToFoam matches the cells' faces by their
points, finds neither the quadrangle nor its triangles twice and leaves them all in a patch
``defaultFaces``. :func:`join_split_faces` makes the two triangles the faces the prism shares
with the tetrahedra (the prism then has six faces, two of them in one plane: a polyhedron to
OpenFOAM) and drops the quadrangle, so that the patch goes.
"""

from __future__ import annotations

from itertools import combinations
from pathlib import Path

import numpy as np

#: gmshToFoam's patch for the faces it found once and no physical group names
UNMATCHED = "defaultFaces"


def join_split_faces(case_dir: Path) -> int:
    """Join the quadrangles of the patch ``defaultFaces`` of ``case_dir``'s constant/polyMesh
    to the two triangles each that share its points, rewrite the mesh without that patch, and
    return how many quadrangles were joined (0, and nothing written, without the patch).
    Raises RuntimeError, writing nothing, if any face of the patch finds no partner."""
    from foamlib import FoamFile

    poly = Path(case_dir) / "constant" / "polyMesh"
    with FoamFile(poly / "boundary") as boundary:
        patches = [(name, dict(entry)) for name, entry in boundary[None]]
    unmatched = [entry for name, entry in patches if name == UNMATCHED]
    if not unmatched:
        return 0
    start, count = int(unmatched[0]["startFace"]), int(unmatched[0]["nFaces"])
    faces = _faces(poly / "faces")
    owner = np.asarray(FoamFile(poly / "owner")[None], dtype=np.int64)
    neighbour = np.asarray(FoamFile(poly / "neighbour")[None], dtype=np.int64)
    quads, triangles = {}, []
    for index in range(start, start + count):
        if len(faces[index]) == 4:
            for three in combinations(faces[index], 3):
                quads[frozenset(three)] = index
        elif len(faces[index]) == 3:
            triangles.append(index)
    joined: dict[int, list[int]] = {}
    for index in triangles:
        quad = quads.get(frozenset(faces[index]))
        if quad is None:
            raise RuntimeError(f"{poly}: a triangle of {UNMATCHED} (face {index}) lies on no "
                               "quadrangle of it")
        joined.setdefault(quad, []).append(index)
    quads_found = set(quads.values())
    if len(triangles) + len(quads_found) != count or len(joined) != len(quads_found) or \
            any(len(pair) != 2 for pair in joined.values()):
        raise RuntimeError(f"{poly}: the faces of {UNMATCHED} do not pair as a quadrangle and "
                           "two triangles each")
    internal = [(int(owner[i]), int(neighbour[i]), faces[i]) for i in range(len(neighbour))]
    for quad, pair in joined.items():
        prism = int(owner[quad])
        for index in pair:
            tetrahedron = int(owner[index])  # the triangle points out of it
            face = faces[index]
            if prism < tetrahedron:
                internal.append((prism, tetrahedron, face[::-1]))
            else:
                internal.append((tetrahedron, prism, face))
    internal.sort(key=lambda item: (item[0], item[1]))  # upper-triangular order
    new_faces = [face for _, _, face in internal]
    new_owner = [own for own, _, _ in internal]
    new_neighbour = [nbr for _, nbr, _ in internal]
    kept = []
    for name, entry in patches:
        if name == UNMATCHED:
            continue
        first, size = int(entry["startFace"]), int(entry["nFaces"])
        entry["startFace"] = len(new_faces)
        new_faces.extend(faces[first:first + size])
        new_owner.extend(int(o) for o in owner[first:first + size])
        kept.append((name, entry))
    cells = int(max(owner.max(), neighbour.max() if len(neighbour) else 0)) + 1
    points = len(FoamFile(poly / "points")[None])
    note = (f"nPoints:{points}  nCells:{cells}  nFaces:{len(new_faces)}  "
            f"nInternalFaces:{len(new_neighbour)}")
    _write_list(poly / "faces", "faceList", None,
                [f"{len(face)}({' '.join(map(str, face))})" for face in new_faces])
    _write_list(poly / "owner", "labelList", note, [str(o) for o in new_owner])
    _write_list(poly / "neighbour", "labelList", note, [str(n) for n in new_neighbour])
    with FoamFile(poly / "boundary") as boundary:
        boundary[None] = kept
    return len(joined)


def _faces(path: Path) -> list[list[int]]:
    """The faces of a faces file: a faceList (ASCII), or a faceCompactList (binary), which
    foamlib gives as (offsets, points)."""
    from foamlib import FoamFile

    read = FoamFile(path)[None]
    if isinstance(read, tuple) and len(read) == 2 and np.ndim(read[1]) == 1:
        offsets, flat = (np.asarray(a, dtype=np.int64) for a in read)
        return [flat[a:b].tolist() for a, b in zip(offsets[:-1], offsets[1:], strict=True)]
    return [[int(p) for p in face] for face in read]


def _write_list(path: Path, cls: str, note: str | None, lines: list[str]) -> None:
    """An ASCII OpenFOAM list file (whatever format the one it replaces was in)."""
    header = ["FoamFile", "{", "    version     2.0;", "    format      ascii;",
              f"    class       {cls};"]
    if note:
        header.append(f'    note        "{note}";')
    header += ['    location    "constant/polyMesh";', f"    object      {path.name};", "}",
               "", str(len(lines)), "("]
    path.write_text("\n".join(header + lines + [")", ""]))
