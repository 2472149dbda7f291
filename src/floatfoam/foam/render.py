"""Render an OpenFOAM run directory ``build/<case>/<level>/`` from a case.

The shared dictionaries of ``cases/_common/`` are copied, then every case-specific value is
set with foamlib from the case file ([fluid], [domain], [mesh], [run]) and the theory
(equilibrium, mass properties). Templates are never run in place.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
from foamlib import FoamFile

from floatfoam.bodies.geometry import rotation
from floatfoam.bodies.shapes import EllipticCylinder
from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.foam.dictionaries import write_dict, write_field
from floatfoam.foam.ogrid import OGrid, block_mesh_dict
from floatfoam.hydrostatics.theory import Equilibrium
from floatfoam.layout import COMMON_DIR
from floatfoam.meshing.levels import level_index, refinement_ratio
from floatfoam.settings import max_cells, memory_text


def required(value, name: str):
    """A setting the CFD case cannot do without: an InputError naming it when absent."""
    if value is None:
        raise InputError(f"{name} is missing; the CFD case needs it")
    return value


def level_factor(case: Case, level: str) -> float:
    """Cell-count multiplier of a mesh level: r⁰, r¹, r² for coarse, medium, fine."""
    return refinement_ratio(case) ** level_index(level)


def release_state(case: Case, eq: Equilibrium) -> dict:
    """Body centre and centre of mass (earth frame) at release, and the equilibrium z of G,
    from the case's equilibrium ``eq``."""
    heel = math.radians(case.release["heel"])
    trim = math.radians(case.release["trim"])
    centre_z = eq.z_c + case.release["heave"]
    cog = rotation(heel, trim) @ case.cog + np.array([0.0, 0.0, centre_z])
    g_eq = rotation(eq.heel, eq.trim) @ case.cog + np.array([0.0, 0.0, eq.z_c])
    return {"centre_z": centre_z, "cog": cog, "z_G_equilibrium": float(g_eq[2]),
            "heel": heel, "trim": trim}


def ogrid_for(case: Case, level: str, state: dict, *, local: bool = True) -> OGrid:
    """The O-grid of a circular section at ``level``, the body at its release ``state``;
    ``local``: the run is on this machine, whose memory bounds the cells."""
    body = case.body
    if not (isinstance(body, EllipticCylinder) and body.b == body.c):
        raise InputError(f"body.shape of case {case.name!r}: the CFD mesh is available for "
                         "circular_cylinder only so far")
    mesh, domain = case.settings.mesh, case.settings.domain
    depth = case.depth if math.isfinite(case.depth) else required(domain.depth, "domain.depth")
    grid = OGrid(
        radius=body.b, centre_z=state["centre_z"],
        half_length=required(domain.half_length, "domain.half_length"), depth=depth,
        air_height=required(domain.air_height, "domain.air_height"),
        thickness=required(domain.thickness, "domain.thickness"),
        square=required(mesh.square_half_size, "mesh.square_half_size"),
        cells_side=mesh.cells_side, cells_radial=mesh.cells_radial,
        radial_grading=mesh.radial_grading, cells_horizontal=mesh.cells_horizontal,
        cells_below=mesh.cells_below, cells_above=mesh.cells_above,
        factor=level_factor(case, level),
    )
    b, zc = grid.square, grid.centre_z
    if not body.b < b < min(grid.half_length, grid.depth + zc, grid.air_height - zc):
        raise InputError(f"mesh.square_half_size = {b:g}: valid is between the radius "
                         f"{body.b:g} and the distance from the body to the tank's ends, bottom "
                         "and top")
    if local and grid.cell_count() > max_cells():
        raise InputError(f"[mesh] cell counts at the {level} level give "
                         f"{memory_text(grid.cell_count())}: valid is at most "
                         f"{max_cells():,} cells on this machine (lower mesh.cells_* or "
                         "mesh.refinement_ratio, or run on others with --hostfile)")
    inner, outer = motion_distances(case, grid)
    if not inner < outer:
        raise InputError(f"run.inner_distance = {inner:g} ≥ run.outer_distance = {outer:g} "
                         "(one of them defaulted from mesh.square_half_size): valid is "
                         "inner_distance < outer_distance")
    required(case.settings.run.end_time, "run.end_time")
    return grid


def motion_distances(case: Case, grid: OGrid) -> tuple[float, float]:
    """The six-DoF morphing distances: [run] inner and outer, else 0.3 and 1.6 × the O-grid's
    half-square (rigid inside the inner one, fixed beyond the outer one)."""
    run = case.settings.run
    inner = run.inner_distance if run.inner_distance is not None else 0.3 * grid.square
    outer = run.outer_distance if run.outer_distance is not None else 1.6 * grid.square
    return inner, outer


SCOTCH = Path("/usr/lib/libscotchDecomp.so")
SCOTCH_STUB = b"This message is from the dummy scotchDecomp stub library"


def scotch_available(library: Path = SCOTCH) -> bool:
    """Whether OpenFOAM's scotch decomposition is the real one (Debian's v1912 ships a stub
    that stops decomposePar with a fatal error)."""
    try:
        return SCOTCH_STUB not in library.read_bytes()
    except OSError:
        return False


def decomposition(np_: int, grid: OGrid) -> dict:
    """decomposeParDict entries for ``np_`` ranks: scotch where OpenFOAM has it, else a simple
    split of the (y, z) tank into a × b blocks, a·b = np_, as near square as the tank allows."""
    if scotch_available():
        return {"method": "scotch"}
    width, height = 2.0 * grid.half_length, grid.depth + grid.air_height
    splits = [(a, np_ // a) for a in range(1, np_ + 1) if np_ % a == 0]
    a, b = min(splits, key=lambda s: abs(math.log((width / s[0]) / (height / s[1]))))
    return {"method": "simple", "coeffs": {"n": [1, a, b], "delta": 0.001}}


def write_interval(end_time: float, requested: float) -> float:
    """The largest interval ≤ ``requested`` that divides ``end_time``, so that the run's last
    write falls on end_time exactly (interFoam's adjustable time step lands on write times)."""
    return end_time / math.ceil(end_time / requested - 1e-9)


def render(case: Case, level: str, run_dir: Path, state: dict, grid: OGrid, *,
           np_: int = 1) -> dict:
    """Write the run directory for the release ``state`` (:func:`release_state`) on ``grid``
    (:func:`ogrid_for`); returns what the driver needs (end time, cells, state)."""
    run_dir.mkdir(parents=True, exist_ok=True)
    for sub in ("system", "constant"):
        shutil.copytree(COMMON_DIR / sub, run_dir / sub, dirs_exist_ok=True)
    write_dict(run_dir / "system" / "blockMeshDict", block_mesh_dict(grid))
    end_time = required(case.settings.run.end_time, "run.end_time")
    _control(case, run_dir, grid, end_time)
    _fluid(case, run_dir)
    _motion(case, run_dir, grid, state)
    _fields(run_dir / "0.orig")
    write_dict(run_dir / "system" / "setAlphaFieldDict",
                {"field": "alpha.water", "type": "plane", "origin": [0.0, 0.0, 0.0],
                 "direction": [0.0, 0.0, 1.0]})
    decompose = FoamFile(run_dir / "system" / "decomposeParDict")
    decompose["numberOfSubdomains"] = np_
    for key, value in decomposition(np_, grid).items():
        decompose[key] = value
    return {"end_time": end_time, "cells": grid.cell_count(), **state}


def _control(case: Case, run_dir: Path, grid: OGrid, end_time: float) -> None:
    control = FoamFile(run_dir / "system" / "controlDict")
    run = case.settings.run
    control["endTime"] = end_time
    control["writeInterval"] = write_interval(end_time, run.write_interval)
    control["maxCo"] = run.max_courant
    control["maxAlphaCo"] = run.max_courant
    control["maxDeltaT"] = run.max_delta_t / grid.factor
    if run.static_body:
        pimple = FoamFile(run_dir / "system" / "fvSolution")
        pimple["PIMPLE"]["correctPhi"] = False
        pimple["PIMPLE"]["nOuterCorrectors"] = 1
        return
    control["functions"]["motion"] = {"type": "sixDoFRigidBodyState",
                                      "libs": ['"libsixDoFRigidBodyState.so"'],
                                      "angleFormat": "degrees"}


def _fluid(case: Case, run_dir: Path) -> None:
    transport = FoamFile(run_dir / "constant" / "transportProperties")
    transport["water"] = {"transportModel": "Newtonian", "nu": case.nu, "rho": case.rho}
    transport["air"] = {"transportModel": "Newtonian", "nu": case.nu_air, "rho": case.rho_air}
    write_dict(run_dir / "constant" / "g",
                {"dimensions": FoamFile.DimensionSet(length=1, time=-2),
                 "value": [0.0, 0.0, -case.g]}, cls="uniformDimensionedVectorField")


def _motion(case: Case, run_dir: Path, grid: OGrid, state: dict) -> None:
    """Six-DoF body: the slab of thickness t carries mass M·t/L and inertia M·t/L·k²."""
    share = grid.thickness / case.body.length
    mass = case.mass * share
    inertia = [mass * k * k for k in case.gyradius]
    x_mid = grid.thickness / 2.0
    cog = [x_mid, float(state["cog"][1]), float(state["cog"][2])]
    if case.release["heel"] == 0.0:  # heave only: slide along z, no rotation
        constraints = {
            "heaveOnly": {"sixDoFRigidBodyMotionConstraint": "line", "centreOfRotation": cog,
                          "direction": [0.0, 0.0, 1.0]},
            "noRotation": {"sixDoFRigidBodyMotionConstraint": "orientation"},
        }
    else:  # 2D section: heave, sway and roll in its plane
        constraints = {
            "inPlane": {"sixDoFRigidBodyMotionConstraint": "plane", "centreOfRotation": cog,
                        "normal": [1.0, 0.0, 0.0]},
            "rollOnly": {"sixDoFRigidBodyMotionConstraint": "axis", "axis": [1.0, 0.0, 0.0]},
        }
    if case.settings.run.static_body:  # body held at its release position (still-water test)
        write_dict(run_dir / "constant" / "dynamicMeshDict", {"dynamicFvMesh": "staticFvMesh"})
        return
    inner, outer = motion_distances(case, grid)
    coeffs = {
        "patches": ["body"],
        "innerDistance": inner,
        "outerDistance": outer,
        "centreOfMass": cog,
        "centreOfRotation": cog,
        "mass": mass,
        "momentOfInertia": inertia,
        "report": True,
        "accelerationRelaxation": case.settings.run.acceleration_relaxation,
        "solver": {"type": "Newmark"},
        "constraints": constraints,
    }
    write_dict(run_dir / "constant" / "dynamicMeshDict", {
        "dynamicFvMesh": "dynamicMotionSolverFvMesh",
        "motionSolverLibs": ['"libsixDoFRigidBodyMotion.so"'],
        "motionSolver": "sixDoFRigidBodyMotion",
        "sixDoFRigidBodyMotionCoeffs": coeffs,
    })


def _fields(folder: Path) -> None:
    """Initial fields: water and air at rest; the free surface is set by setAlphaField."""
    zero = [0.0, 0.0, 0.0]
    specs = {
        "U": ("volVectorField", FoamFile.DimensionSet(length=1, time=-1), zero, {
            "body": {"type": "movingWallVelocity", "value": zero},
            "walls": {"type": "noSlip"},
            "atmosphere": {"type": "pressureInletOutletVelocity", "value": zero}}),
        "p_rgh": ("volScalarField", FoamFile.DimensionSet(mass=1, length=-1, time=-2), 0.0, {
            "body": {"type": "fixedFluxPressure", "value": 0.0},
            "walls": {"type": "fixedFluxPressure", "value": 0.0},
            "atmosphere": {"type": "totalPressure", "p0": 0.0}}),
        "alpha.water": ("volScalarField", FoamFile.DimensionSet(), 0.0, {
            "body": {"type": "zeroGradient"}, "walls": {"type": "zeroGradient"},
            "atmosphere": {"type": "inletOutlet", "inletValue": 0.0, "value": 0.0}}),
        "pointDisplacement": ("pointVectorField", FoamFile.DimensionSet(length=1), zero, {
            "body": {"type": "calculated", "value": zero},
            "walls": {"type": "fixedValue", "value": zero},
            "atmosphere": {"type": "fixedValue", "value": zero}}),
    }
    for name, (cls, dims, internal, patches) in specs.items():
        write_field(folder / name, cls, dims, internal, {**patches, "frontBack": {"type": "empty"}})


