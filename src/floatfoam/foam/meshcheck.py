"""Convert a gmsh mesh for OpenFOAM and check it: gmshToFoam, the patch types, checkMesh.

Light applications only (no solver): they run in a scratch case with the minimal system/
files they read, rendered with foamlib. gmshToFoam names the patches after the physical groups
and makes them all ``patch``; :func:`set_patch_types` gives them their OpenFOAM types
(:data:`PATCH_TYPES`), which checkMesh needs to see a 2D or wedge mesh as such.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

from floatfoam.foam.runner import foam_env

PATCH_TYPES = {  # physical group → OpenFOAM patch type
    "body": "wall",
    "bottom": "wall",
    "sides": "wall",
    "atmosphere": "patch",
    "frontAndBack": "empty",
    "wedge0": "wedge",
    "wedge1": "wedge",
}

_SYSTEM = {
    "controlDict": {"application": "checkMesh", "startFrom": "startTime", "startTime": 0,
                    "stopAt": "endTime", "endTime": 1, "deltaT": 1,
                    "writeControl": "timeStep", "writeInterval": 1},
    "fvSchemes": {key: {} for key in ("ddtSchemes", "gradSchemes", "divSchemes",
                                      "laplacianSchemes", "interpolationSchemes",
                                      "snGradSchemes")},
    "fvSolution": {},
}




class MeshCheckError(RuntimeError):
    """gmshToFoam or checkMesh failed (message: one line and the log's path)."""


def write_system(case_dir: Path) -> None:
    """The system/ dictionaries gmshToFoam and checkMesh read, nothing more."""
    from foamlib import FoamFile

    for name, entries in _SYSTEM.items():
        path = case_dir / "system" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text("")
        with FoamFile(path) as dictionary:
            dictionary["FoamFile"] = {"version": 2.0, "format": "ascii", "class": "dictionary",
                                      "object": name}
            for key, value in entries.items():
                dictionary[key] = value


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
    case_dir.mkdir(parents=True, exist_ok=True)
    write_system(case_dir)
    _run(["gmshToFoam", "-case", str(case_dir), str(Path(msh).resolve())], case_dir,
         "gmshToFoam")
    patches = set_patch_types(case_dir, types)
    log = _run(["checkMesh", "-case", str(case_dir)], case_dir, "checkMesh", check=False)
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
    }


def _run(command: list[str], case_dir: Path, name: str, check: bool = True) -> Path:
    log = case_dir / f"log.{name}"
    with open(log, "w") as fh:
        done = subprocess.run(command, stdout=fh, stderr=subprocess.STDOUT,
                              env=foam_env(), check=False)
    if check and done.returncode != 0:
        raise MeshCheckError(f"{name} failed (exit {done.returncode}); see {log}")
    return log
