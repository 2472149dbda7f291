"""Convert a gmsh mesh for OpenFOAM and check it: gmshToFoam (the prisms of a 3D band joined
to the tetrahedra beside them: :mod:`floatfoam.foam.splitfaces`), the patch types, checkMesh.

Light applications only (no solver): they run in a scratch case with the minimal system/
files they read, rendered with foamlib. gmshToFoam names the patches after the physical groups
and makes them all ``patch``; :func:`set_patch_types` gives them their OpenFOAM types
(:data:`floatfoam.foam.patches.PATCH_TYPES`), which checkMesh needs to see a 2D or wedge mesh
as such.
"""

from __future__ import annotations

import re
from pathlib import Path

from floatfoam.foam.dictionaries import write_dict
from floatfoam.foam.patches import PATCH_TYPES
from floatfoam.foam.runner import check_path, run_app
from floatfoam.foam.splitfaces import join_split_faces

_SYSTEM = {
    "controlDict": {"application": "checkMesh", "startFrom": "startTime", "startTime": 0,
                    "stopAt": "endTime", "endTime": 1, "deltaT": 1,
                    "writeControl": "timeStep", "writeInterval": 1},
    "fvSchemes": {key: {} for key in ("ddtSchemes", "gradSchemes", "divSchemes",
                                      "laplacianSchemes", "interpolationSchemes",
                                      "snGradSchemes")},
    "fvSolution": {},
}


def write_system(case_dir: Path) -> None:
    """The system/ dictionaries gmshToFoam and checkMesh read, nothing more."""
    for name, entries in _SYSTEM.items():
        write_dict(case_dir / "system" / name, entries)


def set_patch_types(case_dir: Path, types: dict | None = None) -> dict:
    """Give the patches of constant/polyMesh/boundary their types (walls join group ``wall``);
    returns {patch: type}."""
    from foamlib import FoamFile

    types = {**PATCH_TYPES, **(types or {})}
    done = {}
    with FoamFile(case_dir / "constant" / "polyMesh" / "boundary") as boundary:
        patches = []
        for name, entry in boundary[None]:
            entry = {k: v for k, v in dict(entry).items() if k not in ("physicalType",
                                                                       "inGroups")}
            entry["type"] = types.get(name, entry["type"])
            if entry["type"] == "wall":
                entry["inGroups"] = ["wall"]
            patches.append((name, entry))
            done[name] = entry["type"]
        boundary[None] = patches
    return done


def convert_and_check(msh: Path, case_dir: Path, types: dict | None = None) -> dict:
    """gmshToFoam ``msh`` into ``case_dir`` (created), set the patch types, run checkMesh.

    Returns
    -------
    dict: ``cells``, ``cell_types`` (hexahedra, prisms, … as checkMesh counts them),
    ``max_non_orthogonality`` and ``average_non_orthogonality`` (degrees), ``max_skewness``,
    ``max_aspect_ratio``, ``mesh_ok`` (checkMesh's verdict), ``patches`` ({name: type}) and
    ``log`` (checkMesh's log).
    """
    check_path(case_dir)
    case_dir.mkdir(parents=True, exist_ok=True)
    write_system(case_dir)
    run_app(case_dir, "gmshToFoam", ["gmshToFoam", str(Path(msh).resolve())], quiet=True,
            marker=False)
    join_split_faces(case_dir)  # a 3D band's prisms to the tetrahedra beside them
    patches = set_patch_types(case_dir, types)
    log = run_app(case_dir, "checkMesh", ["checkMesh"], quiet=True, marker=False, check=False)
    result = parse_check_mesh(log.read_text())
    result.update(patches=patches, log=str(log))
    return result


def parse_check_mesh(text: str) -> dict:
    """The numbers of a checkMesh log that tell a mesh's quality."""
    def number(pattern):
        match = re.search(pattern, text, flags=re.M)
        return float(match.group(1)) if match else None

    types = dict(re.findall(r"^\s+(hexahedra|prisms|wedges|pyramids|tet wedges|tetrahedra|"
                            r"polyhedra):\s+(\d+)", text, flags=re.M))
    return {
        "cells": int(number(r"^\s+cells:\s+(\d+)") or 0),
        "cell_types": {k: int(v) for k, v in types.items() if int(v)},
        "max_non_orthogonality": number(r"non-orthogonality Max:\s*([-\d.e+]+)"),
        "average_non_orthogonality": number(r"non-orthogonality Max:.*average:\s*([-\d.e+]+)"),
        "max_skewness": number(r"Max skewness = ([-\d.e+]+)"),
        "max_aspect_ratio": number(r"Max aspect ratio = ([-\d.e+]+)"),
        "mesh_ok": "\nMesh OK." in text,
        "negative_volume_cells": int(number(r"Number of negative volume cells:\s*(\d+)") or 0),
        "inverted_pyramid_faces": int(number(r"Error in face pyramids:\s*(\d+)") or 0),
    }

