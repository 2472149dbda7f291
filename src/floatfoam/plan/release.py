"""Where a run starts and how long it goes, from the case and its equilibrium: the body at its
release (:func:`release_state`), the pose its mesh is made at (:func:`mesh_pose`), the
simulated time (:func:`end_time_of`) and a time-step study's smaller steps
(:func:`smaller_steps`). Each is checked before anything is written."""

from __future__ import annotations

import math

import numpy as np

from floatfoam.bodies.geometry import rotation
from floatfoam.case import Case
from floatfoam.dofs import released
from floatfoam.errors import InputError
from floatfoam.hydrostatics.fluid_domain import check_release
from floatfoam.hydrostatics.theory import Equilibrium


def release_state(case: Case, eq: Equilibrium) -> dict:
    """The body at release, from the case's equilibrium ``eq``: its pose (the equilibrium
    attitude plus the [release] offsets, :func:`floatfoam.tank.pose`), the centre of
    mass there (earth frame), its attitude as a rotation tensor, and the equilibrium's z of G
    and attitude (the reference of the motion series' angles). Raises InputError for a
    release outside the tank (:func:`floatfoam.hydrostatics.fluid_domain.check_release`),
    before the run plans its mesh or writes anything."""
    where = check_release(case, eq)
    attitude = rotation(where.heel, where.trim)
    cog = attitude @ case.cog + np.array([0.0, 0.0, where.z_c])
    reference = rotation(eq.heel, eq.trim)
    g_eq = reference @ case.cog + np.array([0.0, 0.0, eq.z_c])
    return {"pose": where, "centre_z": where.z_c, "cog": cog, "orientation": attitude,
            "z_G_equilibrium": float(g_eq[2]), "equilibrium_orientation": reference,
            "heel": math.radians(case.release["heel"]),
            "trim": math.radians(case.release["trim"])}


# Added mass lengthens the theory's periods (which have none): measured with Cummins' model
# (`floatfoam decay-model --model cummins`) up to +43 % in heave (the flat elliptic section,
# 0.80 s against 0.56 s) and +11 % in roll (the same section, 0.868 s against 0.785 s).
PERIOD_ALLOWANCE = {"heave": 1.5, "roll": 1.15, "pitch": 1.15}


DEFAULT_PERIODS = 5


def end_time_of(case: Case) -> float:
    """``run.end_time``, else :data:`DEFAULT_PERIODS` periods of the slowest released DoF:
    the theory's period × :data:`PERIOD_ALLOWANCE` for the added mass."""
    if case.settings.run.end_time is not None:
        return case.settings.run.end_time
    from floatfoam.hydrostatics.theory import theory_summary

    theory = theory_summary(case)
    periods = [(theory.period(d.name) or math.nan) * PERIOD_ALLOWANCE[d.name]
               for d in released(case.release) or released({"heave": 1.0})]
    finite = [p for p in periods if math.isfinite(p) and p > 0.0]
    if not finite:
        raise InputError("run.end_time is missing and the theory gives no period of the "
                         "released DoF to set it from (it capsizes); valid: run.end_time = "
                         "<simulated seconds>")
    return round(DEFAULT_PERIODS * max(finite), 2)


def mesh_pose(case: Case, state: dict, equilibrium: Equilibrium):
    """The pose the mesh is made at (``[run] mesh_pose``): the release's, or the
    equilibrium's for a heave release, whose offset to the release then goes in ``state``
    (``mesh_offset``, m) for the render and the move before the first step
    (:mod:`floatfoam.foam.meshpose`). Raises InputError for a heel or trim release or the
    O-grid, which that move does not serve."""
    if case.settings.run.mesh_pose == "release":
        return state["pose"]
    if case.release["heel"] or case.release["trim"]:
        raise InputError("run.mesh_pose = 'equilibrium' moves the mesh in heave only; valid "
                         "with a heel or trim release is run.mesh_pose = 'release'")
    if case.settings.run.static_body:
        raise InputError("run.mesh_pose = 'equilibrium' moves the mesh with the six-DoF "
                         "solver; valid with run.static_body = true is run.mesh_pose = "
                         "'release'")
    if case.settings.mesh.mesher == "ogrid":
        raise InputError("run.mesh_pose = 'equilibrium' needs a gmsh mesh; valid with "
                         "mesh.mesher = 'ogrid' is run.mesh_pose = 'release'")
    from floatfoam.tank import pose

    made = pose(case, "equilibrium", equilibrium)
    state["mesh_offset"] = [0.0, 0.0, float(state["pose"].z_c - made.z_c)]
    return made


# the bulk's Courant limit by the mesh's kind (:func:`floatfoam.plan.kind.kind_of`) where the
# case sets no run.max_courant: 3 on a 2D section's cells, gmsh's or an O-grid's
# (docs/studies/time-step-limits.md); 1 on a wedge, whose finer levels' steps the bulk's limit
# holds through the laboratory sphere's splash (not measured at 3), and in a 3D tank, where 3
# was measured on stl_pontoon alone
BULK_COURANT = {"2d": 3.0, "ogrid": 3.0, "wedge": 1.0, "3d": 1.0, "3d-half": 1.0}


def bulk_courant(case: Case, kind: str) -> float:
    """The largest Courant number in the bulk of a run of ``case`` in a domain of ``kind``:
    ``run.max_courant``, or :data:`BULK_COURANT`'s for the kind."""
    value = case.settings.run.max_courant
    return BULK_COURANT[kind] if value is None else value


# the coupling's tolerance by the mesh's kind where the case sets no run.coupling_tolerance:
# 0.01 in a 3D tank, where each iteration moves the tetrahedral mesh and costs a third of a step
# and 91 % of stl_pontoon's steps end after two, its first 2.5 cycles' period within 0.07 % of
# three iterations' (docs/studies/cases/stl_pontoon.md); 0 on a section's and a wedge's mesh,
# whose records are made at the three iterations of run.outer_correctors
COUPLING_TOLERANCE = {"2d": 0.0, "ogrid": 0.0, "wedge": 0.0, "3d": 0.01, "3d-half": 0.01}


def coupling_tolerance(case: Case, kind: str) -> float:
    """The coupling's tolerance of a run of ``case`` in a domain of ``kind`` (PIMPLE's
    ``couplingTolerance``, src/solver/couplingConvergence.H): ``run.coupling_tolerance``, or
    :data:`COUPLING_TOLERANCE`'s for the kind; 0 for a body held still (one iteration)."""
    run = case.settings.run
    if run.static_body:
        return 0.0
    return COUPLING_TOLERANCE[kind] if run.coupling_tolerance is None else run.coupling_tolerance


def check_divisor(divisor) -> None:
    """A time-step study's divisor (``--dt-divisor``) is a whole number ≥ 1."""
    if isinstance(divisor, bool) or not isinstance(divisor, int) or divisor < 1:
        raise InputError(f"--dt-divisor {divisor!r}: valid is a whole number ≥ 1")


def smaller_steps(case: Case, divisor: int, kind: str) -> Case:
    """The case with its time-step limits (run.max_delta_t, run.max_courant, as
    :func:`bulk_courant` resolves it in a domain of ``kind``, and run.max_alpha_courant)
    divided by ``divisor``, a whole number ≥ 1."""
    check_divisor(divisor)
    if divisor == 1:
        return case
    from floatfoam.case import with_overrides

    run = case.settings.run
    limits = {"max_delta_t": run.max_delta_t, "max_courant": bulk_courant(case, kind),
              "max_alpha_courant": run.max_alpha_courant}
    return with_overrides(case, [f"run.{key}={value / divisor!r}"
                                 for key, value in limits.items()])
