"""A mesh made with the body at its equilibrium, moved to the release before the first step
(``[run] mesh_pose = "equilibrium"``, heave releases).

The six-DoF morphing solver moves every point from the mesh it read first (``points0``) by the
body's motion since then, scaled by the point's distance from the body (1 within the inner
distance, a cosine ramp to 0 at the outer one, walls held). A mesh made at the release stays
deformed by the whole release for as long as the body rests at equilibrium; one made at the
equilibrium is undeformed there. The second needs the body at its release at t = 0: the
dynamicMeshDict's ``initialCentreOfMass`` (and the constraints' centre of rotation) is G at
equilibrium, its ``centreOfMass`` G at release, and the points are moved here as the solver
would move them, from its own scale field (``motionScale``, written when the solver starts),
so its first step does not jump. OpenFOAM v1912,
src/sixDoFRigidBodyMotion/sixDoFRigidBodyMotion/sixDoFRigidBodyMotion.C, ``transform``: a
point of scale s moves by s × the translation (s > 1 − SMALL: by all of it; s ≤ SMALL: not)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

SMALL = 1e-15  # OpenFOAM's (double precision)


def mesh_dirs(run_dir: Path) -> list[Path]:
    """The folders holding a mesh the solver reads: ``processor*`` when decomposed, else the
    run directory."""
    return sorted(run_dir.glob("processor[0-9]*")) or [run_dir]


def held_patches(run_dir: Path) -> list[str]:
    """The patches whose points the motion holds still (fixedValue in 0.orig's
    pointDisplacement: the tank's walls and top)."""
    from foamlib import FoamFile

    boundary = FoamFile(run_dir / "0.orig" / "pointDisplacement")["boundaryField"]
    return [name for name, entry in boundary.items() if entry.get("type") == "fixedValue"]


def _patch_points(mesh: Path, names: list[str]) -> np.ndarray:
    """The indices of the points on the named patches of the polyMesh folder ``mesh``."""
    from foamlib import FoamFile

    faces = FoamFile(mesh / "faces")[None]
    if isinstance(faces, tuple):  # a compact list: offsets and the flat point list
        offsets, flat = (np.asarray(part) for part in faces)

        def face_points(first, count):
            return flat[offsets[first]:offsets[first + count]]
    else:
        def face_points(first, count):
            return np.concatenate([np.asarray(f) for f in faces[first:first + count]])
    found = [np.zeros(0, dtype=int)]
    for name, patch in FoamFile(mesh / "boundary")[None]:
        if name in names and int(patch["nFaces"]) > 0:
            found.append(face_points(int(patch["startFace"]), int(patch["nFaces"])))
    return np.unique(np.concatenate(found)).astype(int)


def _made(mesh: Path) -> np.ndarray:
    """The points of the polyMesh folder ``mesh`` as made: ``points0`` once written."""
    from foamlib import FoamFieldFile

    source = mesh / "points0" if (mesh / "points0").is_file() else mesh / "points"
    return np.asarray(FoamFieldFile(source)[None], dtype=float).reshape(-1, 3)


def _share(folder: Path, held: list[str]) -> np.ndarray:
    """The share of the offset each point of the mesh in ``folder`` moves by: its scale
    (0 at or below SMALL, 1 above 1 − SMALL), 0 on the held patches."""
    from foamlib import FoamFieldFile

    mesh = folder / "constant" / "polyMesh"
    count = len(_made(mesh))
    scale = np.asarray(FoamFieldFile(folder / "0" / "motionScale").internal_field, dtype=float)
    scale = np.broadcast_to(scale, (count,))
    share = np.where(scale > 1.0 - SMALL, 1.0, np.where(scale > SMALL, scale, 0.0))
    share[_patch_points(mesh, held)] = 0.0
    return share


def move_to_release(run_dir: Path, offset) -> int:
    """Move each mesh of ``run_dir`` by ``offset`` (m, earth frame) scaled by the solver's
    ``0/motionScale`` there, its held patches still; the mesh as made becomes ``points0``.

    Decomposed, a point the ranks share takes the largest share any of them gives it, as the
    solver's ``pointConstraints::constrainDisplacement`` does (``maxMagSqrEqOp``: a wall point
    of one rank that is no wall point of another moves); the whole case's mesh is moved too,
    from the ranks' points (``pointProcAddressing``), for a reconstruction. Idempotent: the
    mesh as made is read from ``points0`` when that is already written. Returns the number of
    the whole mesh's points that move."""
    from foamlib import FoamFile

    held = held_patches(run_dir)
    offset = np.asarray(offset, dtype=float)
    folders = mesh_dirs(run_dir)
    if folders == [run_dir]:
        share = _share(run_dir, held)
    else:
        share = np.zeros(len(_made(run_dir / "constant" / "polyMesh")))
        addressing = {}
        for folder in folders:
            address = np.asarray(FoamFile(folder / "constant" / "polyMesh" /
                                          "pointProcAddressing")[None], dtype=int)
            addressing[folder] = address
            np.maximum.at(share, address, _share(folder, held))
        for folder in folders:
            _write(folder / "constant" / "polyMesh", share[addressing[folder]], offset)
    _write(run_dir / "constant" / "polyMesh", share, offset)
    return int(np.count_nonzero(share))


def _write(mesh: Path, share: np.ndarray, offset: np.ndarray) -> None:
    """``points0`` (the mesh as made), then ``points`` moved by ``share`` × ``offset``; a
    points0 whose class is not vectorField the solver ignores, and falls back to points."""
    from floatfoam.foam.dictionaries import write_list

    made = _made(mesh)
    for name, points in (("points0", made), ("points", made + share[:, None] * offset[None, :])):
        write_list(mesh / name, points, "vectorField")
        (mesh / f"{name}.gz").unlink(missing_ok=True)
