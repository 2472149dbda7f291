"""Render an OpenFOAM run directory ``build/<case>/<level>/`` from a case.

The shared dictionaries of ``cases/_common/`` are copied, then every case-specific value is
set with foamlib from the case file ([fluid], [run]), the run's mesh (:mod:`floatfoam.foam.
domain`: its source, patches, share of the body) and the theory (equilibrium, mass
properties). Templates are never run in place.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
from foamlib import FoamFile

from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.foam import domain
from floatfoam.foam.dictionaries import write_dict
from floatfoam.foam.domain import RunMesh
from floatfoam.foam.patches import write_initial_fields
from floatfoam.layout import COMMON_DIR
from floatfoam.plan.record import RunRecord
from floatfoam.plan.release import bulk_courant, coupling_tolerance
from floatfoam.plan.runplan import RunPlan
from floatfoam.plan.stamps import COMPENSATION, has_body_velocity, solver_has
from floatfoam.plan.zone import LAYERED_SOLVER, free_names, heave_only
from floatfoam.settings import time_scheme_coefficient

SCOTCH = Path("/usr/lib/libscotchDecomp.so")
SCOTCH_STUB = b"This message is from the dummy scotchDecomp stub library"


def scotch_available(library: Path = SCOTCH) -> bool:
    """Whether OpenFOAM's scotch decomposition is the real one (Debian's v1912 ships a stub
    that stops decomposePar with a fatal error)."""
    try:
        return SCOTCH_STUB not in library.read_bytes()
    except OSError:
        return False


def decomposition(np_: int, extents) -> dict:
    """decomposeParDict entries for ``np_`` ranks: scotch where OpenFOAM has it, else a simple
    split n = (a, b, c), a·b·c = np_, of the tank's ``extents`` (x, y, z; 0 along a direction
    one cell thick, never split), its blocks as near cubic as the tank allows."""
    if scotch_available():
        return {"method": "scotch"}
    sizes = [float(e) for e in extents]
    best, best_cost = [1, 1, 1], math.inf
    for a in range(1, np_ + 1):
        for b in range(1, np_ // a + 1):
            if np_ % (a * b):
                continue
            split = [a, b, np_ // (a * b)]
            if any(n > 1 and size <= 0.0 for n, size in zip(split, sizes, strict=True)):
                continue
            blocks = [size / n for n, size in zip(split, sizes, strict=True) if size > 0.0]
            cost = max(blocks) / min(blocks)
            if cost < best_cost - 1e-12:
                best, best_cost = split, cost
    return {"method": "simple", "coeffs": {"n": best, "delta": 0.001}}


def write_interval(end_time: float, requested: float) -> float:
    """The largest interval ≤ ``requested`` that divides ``end_time``, so that the run's last
    write falls on end_time exactly (interFoam's adjustable time step lands on write times)."""
    return end_time / math.ceil(end_time / requested - 1e-9)


def render(plan: RunPlan, mesh: RunMesh) -> RunRecord:
    """Write the plan's run directory (:mod:`floatfoam.plan.runplan`) on ``mesh``
    (:mod:`floatfoam.foam.domain`); returns the run's record (:mod:`floatfoam.plan.record`):
    its end time, cells, mesh kind and the body patch's immersed volume error, the release
    (:func:`floatfoam.plan.release.release_state`, and what [release] asked), the body's size
    (m, `floatfoam analyse`'s default DoFs), the case's file (for analyse's model) and the
    discrete body's equilibrium shift (:func:`equilibrium_shift`)."""
    case, run_dir, state, np_ = plan.case, plan.run_dir, plan.state, plan.np
    run_dir.mkdir(parents=True, exist_ok=True)
    for sub in ("system", "constant"):
        shutil.copytree(COMMON_DIR / sub, run_dir / sub, dirs_exist_ok=True)
    domain.write(mesh, run_dir)
    end_time = plan.end_time
    _control(case, run_dir, mesh, end_time)
    _solution(case, run_dir, mesh)
    _fluid(case, run_dir)
    own = has_body_velocity(case)  # floatfoam's interFoam, or another (run.solver)
    compensation = _compensation(case, plan.equilibrium, mesh) \
        if own and solver_has(case, COMPENSATION) else None
    body = _motion(case, run_dir, mesh, state, own, compensation)
    write_initial_fields(run_dir / "0.orig", mesh.patches, body_velocity=own)
    if body is not None:  # the Laplacian's body: its displacement from the six-DoF equations
        field = FoamFile(run_dir / "0.orig" / "pointDisplacement")
        field["boundaryField"]["body"] = body
    if mesh.motion == "layered" and "sides" in mesh.patches:  # rows slide along the ends
        FoamFile(run_dir / "0.orig" / "pointDisplacement")["boundaryField"]["sides"] = \
            {"type": "calculated", "value": [0.0, 0.0, 0.0]}
    write_dict(run_dir / "system" / "setAlphaFieldDict",
                {"field": "alpha.water", "type": "plane", "origin": [0.0, 0.0, 0.0],
                 "direction": [0.0, 0.0, 1.0]})
    decompose = FoamFile(run_dir / "system" / "decomposeParDict")
    decompose["numberOfSubdomains"] = np_
    for key, value in decomposition(np_, mesh.extents).items():
        decompose[key] = value
    return RunRecord.from_dict(
        {k: v for k, v in state.items() if k != "pose"}
        | {"end_time": end_time, "cells": mesh.cells, "mesh": mesh.kind,
           "immersed_error": mesh.immersed_error, "release": dict(case.release),
           "body_size": case.body.size, "case_path": str(case.path),
           "equilibrium_shift": equilibrium_shift(case, plan.level, mesh.kind,
                                                  plan.equilibrium)})


def equilibrium_shift(case: Case, level: str, kind: str, equilibrium) -> float | None:
    """How far the discrete body at ``level`` settles from the exact one's equilibrium, in z
    of G (m): it displaces a little less than the exact body
    (:func:`floatfoam.meshing.volume_report.discrete_volume_report`, the revolved meridian in a
    wedge). None where there is no discrete body to measure."""
    from floatfoam.meshing.volume_report import discrete_volume_report

    try:
        report = discrete_volume_report(case, level, equilibrium)
    except (InputError, ValueError, RuntimeError):
        return None
    if kind == "wedge":
        report = report["meridian"]
    return float(report["equilibrium_shift"])


# pcorr, the flux correction after each of a step's three mesh motions, by GAMG on every mesh but
# the wedge's; by the shared fvSolution's PCG (DIC) there. The shared fvSolution's tolerance
# either way (its reason there). Measured at 1e-3 on the coarse levels, 2 ranks, from release,
# the solver's wall (docs/studies/section-cost.md): stl_pontoon's half tank 0.06 s 21.3 → 19.9 s,
# cylinder_heave's O-grid 0.5 s 11.3 → 10.9 s, ellipsoid_roll's half tank 0.08 s 12.15 s both,
# the sphere's wedge 0.5 s 6.6 → 6.7 s; the motion the same within 1e-8 of its swing. At 1e-6 GAMG
# is the faster on gmsh's sections and whole tanks only (box_bilge 0.8 s 16 → 13 s).
PCORR_BY_GAMG = ("2d", "3d", "3d-half", "ogrid")
PCORR_GAMG = {"solver": "GAMG", "smoother": "DIC"}

# the meshes whose α takes one MULES corrector a step instead of the shared fvSolution's two:
# the 2D sections, where one costs 12 % less a step and moved flume_section_roll's T_d by
# 0.002 % and ζ by 0.6 %, cylinder_heave's O-grid T_d by 0.06 % and ζ by 0.2 %. Not the
# tetrahedral 3D tanks: with one, stl_pontoon's roll stops decaying below 2° (its extrema
# +1.78°, −1.43°, +1.29°, −1.48° from 2.4 s, against +1.54° at 2.37 s with two); nor the wedges,
# not measured (docs/studies/section-cost.md)
ALPHA_ONE_CORRECTOR = ("2d", "ogrid")


def _control(case: Case, run_dir: Path, mesh: RunMesh, end_time: float) -> None:
    control = FoamFile(run_dir / "system" / "controlDict")
    run = case.settings.run
    control["endTime"] = end_time
    control["writeInterval"] = write_interval(end_time, min(run.write_interval, end_time))
    bulk = bulk_courant(case, mesh.kind)
    control["maxCo"] = bulk
    control["maxAlphaCo"] = min(run.max_alpha_courant, bulk)
    control["maxDeltaT"] = run.max_delta_t / mesh.factor
    pimple = FoamFile(run_dir / "system" / "fvSolution")["PIMPLE"]
    pimple["nOuterCorrectors"] = 1 if run.static_body else run.outer_correctors
    pimple["couplingTolerance"] = coupling_tolerance(case, mesh.kind)
    pimple["interfaceGravity"] = run.interface_gravity
    pimple["interfaceGravitySmoothing"] = run.interface_gravity_smoothing
    if run.static_body:
        pimple["correctPhi"] = False


def _solution(case: Case, run_dir: Path, mesh: RunMesh) -> None:
    """pcorr's solver and α's correctors for the mesh's kind (:data:`PCORR_BY_GAMG`,
    :data:`ALPHA_ONE_CORRECTOR`); the time schemes: the momentum's (``run.time_scheme``: the
    shared fvSchemes' Euler unless the case names Crank–Nicolson) and the interface's
    (:func:`interface_scheme`, ``ddt(alpha)``)."""
    solvers = FoamFile(run_dir / "system" / "fvSolution")["solvers"]
    if mesh.kind in PCORR_BY_GAMG:
        shared = solvers['"pcorr.*"']
        solvers['"pcorr.*"'] = {**PCORR_GAMG, "tolerance": shared["tolerance"],
                                "relTol": shared["relTol"]}
    if mesh.kind in ALPHA_ONE_CORRECTOR:
        solvers['"alpha.water.*"']["nAlphaCorr"] = 1
    run = case.settings.run
    ddt = FoamFile(run_dir / "system" / "fvSchemes")["ddtSchemes"]
    psi = time_scheme_coefficient(run.time_scheme)
    if psi is not None:
        ddt["default"] = ("CrankNicolson", psi)
    psi = time_scheme_coefficient(interface_scheme(case, mesh.kind),
                                  "run.interface_time_scheme")
    ddt["ddt(alpha)"] = "Euler" if psi is None else ("CrankNicolson", psi)


#: the interface's time scheme that ``run.interface_time_scheme = "auto"`` takes for a body
#: free in heave alone: a quarter of Euler's step error in the period (docs/studies/time-step.md)
INTERFACE_CRANK_NICOLSON = "CrankNicolson 0.9"


def interface_scheme(case: Case, kind: str) -> str:
    """The interface's (α's) time scheme of a run of ``case`` in a domain of ``kind``:
    ``run.interface_time_scheme``, "auto" resolved to :data:`INTERFACE_CRANK_NICOLSON` for a
    body free in heave alone (:func:`floatfoam.plan.zone.heave_only`) and to Euler for a body
    free to turn, whose roll it measured the same as Euler (not measured on a capsize or in
    3D)."""
    scheme = case.settings.run.interface_time_scheme
    if scheme != "auto":
        return scheme
    return INTERFACE_CRANK_NICOLSON if heave_only(case, kind) else "Euler"


def _fluid(case: Case, run_dir: Path) -> None:
    transport = FoamFile(run_dir / "constant" / "transportProperties")
    transport["water"] = {"transportModel": "Newtonian", "nu": case.nu, "rho": case.rho}
    transport["air"] = {"transportModel": "Newtonian", "nu": case.nu_air, "rho": case.rho_air}
    write_dict(run_dir / "constant" / "g",
                {"dimensions": FoamFile.DimensionSet(length=1, time=-2),
                 "value": [0.0, 0.0, -case.g]}, cls="uniformDimensionedVectorField")


#: the axes of the translations and rotations v1912's six-DoF constraints hold
TRANSLATIONS = {"surge": [1.0, 0.0, 0.0], "sway": [0.0, 1.0, 0.0], "heave": [0.0, 0.0, 1.0]}
ROTATIONS = {"roll": [1.0, 0.0, 0.0], "pitch": [0.0, 1.0, 0.0]}


def constraints(case: Case, mesh: RunMesh, cog: list[float]) -> dict:
    """The six-DoF constraints that leave the body free in the DoFs of
    :func:`floatfoam.dofs.free_dofs` (``[motion] free``, else those the release excites; the
    potential-flow models take the same). v1912's constraints (src/sixDoFRigidBodyMotion/
    sixDoFRigidBodyMotion/constraints): G, the centre of rotation, is held at a ``point``
    (no translation free), on a ``line`` (one), in a ``plane`` (two) or not at all (three);
    the attitude by ``orientation`` (no rotation free), about an ``axis`` (roll or pitch), or
    not at all (both, and yaw with them: no v1912 constraint holds yaw alone)."""
    free = set(free_names(case, mesh.kind))
    moving = [name for name in TRANSLATIONS if name in free]
    held = [name for name in TRANSLATIONS if name not in free]
    out = {}
    if not moving:
        out["fixedPoint"] = {"sixDoFRigidBodyMotionConstraint": "point",
                             "centreOfRotation": cog}
    elif len(moving) == 1:
        out[f"{moving[0]}Only"] = {"sixDoFRigidBodyMotionConstraint": "line",
                                   "centreOfRotation": cog, "direction": TRANSLATIONS[moving[0]]}
    elif len(moving) == 2:
        out["inPlane"] = {"sixDoFRigidBodyMotionConstraint": "plane", "centreOfRotation": cog,
                          "normal": TRANSLATIONS[held[0]]}
    turning = [name for name in ROTATIONS if name in free]
    if not turning:
        out["noRotation"] = {"sixDoFRigidBodyMotionConstraint": "orientation"}
    elif len(turning) == 1:
        out["oneAxis"] = {"sixDoFRigidBodyMotionConstraint": "axis",
                          "axis": ROTATIONS[turning[0]]}
    return out


def _compensation(case: Case, equilibrium, mesh: RunMesh) -> dict | None:
    """The compensating mass of the six-DoF restraint ``addedMassCompensation``
    (:func:`floatfoam.potential.coupling.compensating_mass`: half the body's added mass at
    infinite frequency in the DoFs it is free in, × the domain's share); None for a body held
    still, or, with one line printed, where the potential flow cannot be had (the correctors
    then take the fluid's force as it comes). A body whose correctors would diverge without
    it (:func:`floatfoam.potential.coupling.coupling_gain` above 1) is named in one line."""
    if case.settings.run.static_body:
        return None
    from floatfoam.errors import ComputationError
    from floatfoam.potential.coupling import (
        compensating_mass,
        coupling_gain,
        infinite_frequency_added_mass,
    )

    free = free_names(case, mesh.kind)
    try:
        a_inf = infinite_frequency_added_mass(case, equilibrium, free)
    except (ComputationError, InputError, ValueError) as err:  # the panels refuse the body
        print(f"[{case.name}] no added-mass compensation of the coupling: {err}", flush=True)
        return None
    gain = coupling_gain(case, a_inf, free)
    if gain > 1.0:  # uncompensated, the correctors would diverge (docs/coupling.md)
        print(f"[{case.name}] a light body: its added mass at infinite frequency is "
              f"{2.0 * gain:.3g} × its own; the coupling's correctors are compensated",
              flush=True)
    return compensating_mass(a_inf, free, mesh.share)


def _motion(case: Case, run_dir: Path, mesh: RunMesh, state: dict,
            own: bool = True, compensation: dict | None = None) -> dict | None:
    """Six-DoF body: the domain holds the share s of the body (a slab t/L, a wedge θ/360°),
    mass s·M and inertia s·M·k² about the body's axes; its initial orientation is its attitude
    at release, so the reported orientation is the body's attitude. A mesh made at
    equilibrium (``state["mesh_offset"]``) gets G there as the initial centre of mass.

    The mesh follows the body as ``mesh.motion`` says
    (:func:`floatfoam.plan.zone.mesh_motion`): the six-DoF motion solver with its
    distances, or ``displacementLaplacian`` (its diffusivity :data:`LAPLACIAN_DIFFUSIVITY` of
    ``run.motion_diffusivity``) whose body
    patch carries the same six-DoF dictionary as its point displacement condition
    (``bodySixDoFRigidBodyDisplacement``: v1912's ``sixDoFRigidBodyDisplacement`` of
    src/sixDoFRigidBodyMotion/pointPatchFields, which floatfoam's interFoam has again with an
    accessor to the motion for the body's velocity condition; the original where ``own`` is
    False, on another interFoam): then the body's condition is returned, for the caller to
    write into pointDisplacement (the condition takes g from the solver, which registers
    it). ``compensation`` (:func:`_compensation`), where given, becomes the six-DoF restraint
    ``addedMassCompensation`` of floatfoam's interFoam."""
    if case.settings.run.static_body:  # body held at its release position (still-water test)
        write_dict(run_dir / "constant" / "dynamicMeshDict", {"dynamicFvMesh": "staticFvMesh"})
        return None
    mass = case.mass * mesh.share
    inertia = [mass * k * k for k in case.gyradius]
    # G's x: the slab's middle in a 2D mesh (where G lies along a section's length does not
    # enter), else its own: a trim moves it off x = 0 (2.6 mm for ellipsoid_pitch)
    x = float(state["cog"][0]) if mesh.x_mid is None else mesh.x_mid
    cog = [x, float(state["cog"][1]), float(state["cog"][2])]
    orientation = np.asarray(state["orientation"], dtype=float)
    coeffs = {
        "patches": ["body"],
        "innerDistance": mesh.inner,
        "outerDistance": mesh.outer,
        "centreOfMass": cog,
        "centreOfRotation": cog,
        "mass": mass,
        "momentOfInertia": inertia,
        "report": True,
        "accelerationRelaxation": case.settings.run.acceleration_relaxation,
        "solver": {"type": "Newmark"},
        "constraints": constraints(case, mesh, cog),
    }
    if compensation is not None:  # floatfoam's restraint (src/solver/): the coupling
        coeffs["restraints"] = {"addedMass": {
            "sixDoFRigidBodyMotionRestraint": "addedMassCompensation", **compensation}}
    offset = np.asarray(state.get("mesh_offset", (0.0, 0.0, 0.0)), dtype=float)
    if np.any(offset):  # the mesh holds the body at equilibrium (floatfoam.foam.meshpose):
        made = [c - o for c, o in zip(cog, offset.tolist(), strict=True)]  # G there
        coeffs["initialCentreOfMass"] = made
        # the constraints' centre of rotation is the solver's initial one
        coeffs["constraints"] = constraints(case, mesh, made)
    if not np.allclose(orientation, np.eye(3), atol=1e-15):
        coeffs["orientation"] = [round(float(v), 15) for v in orientation.ravel()]
    if mesh.motion == "layered":
        coeffs["layerBandExpansion"] = case.settings.run.layer_band
    if mesh.motion == "laplacian":
        write_dict(run_dir / "constant" / "dynamicMeshDict", {
            "dynamicFvMesh": "dynamicMotionSolverFvMesh",
            "motionSolverLibs": ['"libfvMotionSolvers.so"', '"libsixDoFRigidBodyMotion.so"'],
            "motionSolver": "displacementLaplacian",
            "displacementLaplacianCoeffs": {
                "diffusivity": LAPLACIAN_DIFFUSIVITY[case.settings.run.motion_diffusivity]},
        })
        body = {k: v for k, v in coeffs.items()
                if k not in ("patches", "innerDistance", "outerDistance")}
        condition = "bodySixDoFRigidBodyDisplacement" if own else "sixDoFRigidBodyDisplacement"
        return {"type": condition, **body, "value": [0.0, 0.0, 0.0]}
    write_dict(run_dir / "constant" / "dynamicMeshDict", {
        "dynamicFvMesh": "dynamicMotionSolverFvMesh",
        "motionSolverLibs": ['"libsixDoFRigidBodyMotion.so"'],
        "motionSolver": LAYERED_SOLVER if mesh.motion == "layered" else "sixDoFRigidBodyMotion",
        "sixDoFRigidBodyMotionCoeffs": coeffs,
    })
    return None


# the displacement's diffusivity by run.motion_diffusivity, d the distance from the body:
# 1/d² (the default) moves the cells near the body nearly with it and the far ones little; 1/d
# spreads the deformation further out (measured against each other: docs/morphing.md)
LAPLACIAN_DIFFUSIVITY = {"quadratic": ("quadratic", "inverseDistance", ["body"]),
                         "linear": ("inverseDistance", ["body"])}
