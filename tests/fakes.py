"""Run folders written by hand for the fast tests: a one-cell case the OpenFOAM reader accepts
(no OpenFOAM utility runs), with a heave record, as a finished or an unfinished run."""

import json

import numpy as np

from floatfoam.motion import write_motion

HEADER = 'FoamFile {{ version 2.0; format ascii; class {cls}; object {obj}; }}\n'
# a unit cube, one cell: the patch body its bottom face, the patch walls the five others
POINTS = "(0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1)"
FACES = "4(0 3 2 1) 4(4 5 6 7) 4(0 1 5 4) 4(3 7 6 2) 4(0 4 7 3) 4(1 2 6 5)"
BOUNDARY = "2(body { type wall; nFaces 1; startFace 0; } walls { type wall; nFaces 5; " \
           "startFace 1; })"
FIELDS = {"alpha.water": ("volScalarField", "0", "1"),
          "p_rgh": ("volScalarField", "-2 1 -2 0 0 0 0", "0"),
          "U": ("volVectorField", "0 1 -1 0 0 0 0", "(0 0 0)")}


def _write(path, cls, body):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(HEADER.format(cls=cls, obj=path.name) + body + "\n")


def fake_run(build, times=(0.0, 0.1, 0.2, 0.3), *, finished=True, fields=tuple(FIELDS)):
    """A run directory ``<build>/sphere/coarse`` the OpenFOAM reader accepts: one cell, the
    written ``times`` holding ``fields``, a heave record with its first trough at 0.2 s."""
    run = build / "sphere" / "coarse"
    mesh = run / "constant" / "polyMesh"
    _write(run / "system" / "controlDict", "dictionary",
           "application interFoam; startFrom startTime; startTime 0; stopAt endTime; "
           f"endTime {times[-1]}; deltaT 0.01; writeControl runTime; writeInterval 0.1;")
    _write(mesh / "points", "vectorField", f"8({POINTS})")
    _write(mesh / "faces", "faceList", f"6({FACES})")
    _write(mesh / "owner", "labelList", "6(0 0 0 0 0 0)")
    _write(mesh / "neighbour", "labelList", "0()")
    _write(mesh / "boundary", "polyBoundaryMesh", BOUNDARY)
    for t in times:
        for name in fields:
            cls, dims, value = FIELDS[name]
            _write(run / f"{t:g}" / name, cls, f"dimensions [{dims}]; internalField uniform "
                   f"{value}; boundaryField {{ body {{ type zeroGradient; }} walls {{ type "
                   "zeroGradient; }} }}")
    markers = run / ".floatfoam"
    markers.mkdir(parents=True)
    (markers / "info.json").write_text(json.dumps({"mesh": "2d", "cells": 1, "heel": 0.0,
                                                   "trim": 0.0, "end_time": times[-1]}))
    if finished:
        (markers / "finished.done").write_text("done\n")
    t = np.linspace(0.0, times[-1], 31)
    write_motion(run / "motion.csv", t, z=0.01 * np.cos(np.pi * t / 0.2))
    return run
