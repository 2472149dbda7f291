"""How a run's mesh follows the body: the motion solver, "auto" resolved (:func:`mesh_motion`),
and the six-DoF solver's distances — rigid with the body within the inner one, fixed beyond
the outer one —, by default from the body and the tank (:func:`distances`,
:func:`clearance`). The measurements behind the rules: docs/morphing.md."""

from __future__ import annotations

import math
from dataclasses import dataclass

from floatfoam.case import Case
from floatfoam.errors import InputError, required
from floatfoam.tank import Pose, body_extents, tank


@dataclass(frozen=True)
class MeshMotion:
    """How a run's mesh follows the body: ``motion`` "layered", "laplacian" or "distances"
    (:func:`mesh_motion`), and the six-DoF solver's ``inner`` and ``outer`` distances (m,
    :func:`distances`; used by "distances" only)."""

    motion: str
    inner: float
    outer: float


def of_case(case: Case, release: Pose) -> MeshMotion:
    """The mesh motion of ``case`` with the body at ``release`` in the domain it is meshed in
    (:func:`floatfoam.plan.kind.kind_of`)."""
    from floatfoam.plan.kind import kind_of

    return resolve(case, release, kind_of(case, release))


def motion_in(case: Case, kind: str) -> str | None:
    """How the mesh of a run of ``case`` in a domain of ``kind`` follows the body, "layered",
    "laplacian" or "distances" (:func:`resolve` at the case's release); None when the release
    or the tank is refused."""
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.plan.release import release_state

    try:
        return resolve(case, release_state(case, equilibrium(case))["pose"], kind).motion
    except InputError:
        return None


def resolve(case: Case, release: Pose, kind: str) -> MeshMotion:
    """The mesh motion of ``case`` in a domain of ``kind`` ("ogrid", "2d", "wedge", "3d",
    "3d-half": :mod:`floatfoam.plan.kind`) with the body at ``release``: the O-grid's zone
    reaches from its square (``mesh.square_half_size``) to the [domain]'s walls, a gmsh
    mesh's from the body's smallest dimension across to the tank's (:func:`floatfoam.tank.tank`;
    its sides are held in 3D only). Raises InputError for a setting missing or a tank without
    room."""
    smallest = float(body_extents(case.body).min())  # the body's smallest dimension across
    if kind == "ogrid":
        mesh, domain = case.settings.mesh, case.settings.domain
        depth = case.depth if math.isfinite(case.depth) else required(domain.depth,
                                                                       "domain.depth")
        walls = [required(domain.air_height, "domain.air_height"), depth,
                 required(domain.half_length, "domain.half_length")]
        length = required(mesh.square_half_size, "mesh.square_half_size")
    else:
        box = tank(case)
        walls = [box.air_height, box.depth, box.half_length] + (
            [box.half_width] if kind.startswith("3d") else [])
        length = smallest
    inner, outer = distances(case, length, clearance(case, release, walls, kind))
    return MeshMotion(mesh_motion(case, kind), inner, outer)


def mesh_motion(case: Case, kind: str) -> str:
    """How the mesh follows the body in a domain of ``kind`` (``run.mesh_motion``; "auto"
    resolved here).

    "layered": floatfoam's six-DoF motion solver whose scale depends on the height alone
    (``layeredSixDoFRigidBodyMotion``, src/solver/): the rows of points across the body's height
    move with it, those below and above it less, linearly to nothing at the tank's bottom and
    top; every row stays horizontal and the cells beside the body are not deformed. For a body
    free in heave alone, and no setting but ``run.layer_band``.
    "laplacian": ``displacementLaplacian`` with the diffusivity ``quadratic inverseDistance
    (body)`` and the body's point displacement from the six-DoF equations
    (``sixDoFRigidBodyDisplacement``): the whole tank deforms, the cells near the body move
    nearly with it, and no distance is set.
    "distances": the six-DoF motion solver, rigid within ``run.inner_distance`` and fixed
    beyond ``run.outer_distance``: the route of rotations and of a mesh made at rest.
    "auto" is the distances where the case sets ``run.inner_distance`` or
    ``run.outer_distance`` (a distance set is a distance used), for a release that turns the
    body over (a heel or trim in a DoF of non-positive stiffness, :func:`turns_over`: a
    displacement field cannot follow a turn of tens of degrees) and for a mesh made at
    equilibrium (moved to the release by the six-DoF solver's scale); else the layered motion
    for a body free in heave alone (:func:`heave_only`: a heave release) on a 2D section's,
    an O-grid's or a wedge's mesh (in a 3D tank, whose free surface its rows would carry up
    and down through the tetrahedra, the heaved 3D sphere's middle cycles ran about 1 % short on
    it); else the Laplacian, in 2D, a wedge and a 3D tank alike. In 3D the Laplacian's coarse
    level is the nearer to the finer levels: the ellipsoid's roll within 0.01 % of its medium
    level's period and 2.4 % of its damping ratio, where the distances' coarse level is 0.37 %
    and 15 % off theirs (the two agree within 0.1 % at the medium level); the heaved 3D sphere
    on it comes within 0.02 % of the wedge's period at the medium level; and in a zone thinner
    than about twice the body's smallest dimension the distances squeeze the cells until the
    step collapses. The measurements behind this rule: docs/morphing.md."""
    run = case.settings.run
    if run.mesh_motion == "layered" and not heave_only(case, kind):
        raise InputError("run.mesh_motion = \"layered\" for a body free in "
                         f"{', '.join(free_names(case, kind))}: its rows would turn with the "
                         "body; valid is a body free in heave alone (a heave release, or "
                         "motion.free = [\"heave\"]), or mesh_motion \"laplacian\", "
                         "\"distances\" or \"auto\"")
    if run.mesh_motion != "auto":
        return run.mesh_motion
    if run.inner_distance is not None or run.outer_distance is not None \
            or run.mesh_pose != "release" or turns_over(case):
        return "distances"
    if kind in ("2d", "wedge", "ogrid") and heave_only(case, kind):
        return "layered"
    return "laplacian"


#: the type name of floatfoam's layered motion solver (src/solver/), linked into floatfoam's
#: interFoam by scripts/build_solver.sh
LAYERED_SOLVER = "layeredSixDoFRigidBodyMotion"


def free_names(case: Case, kind: str) -> list[str]:
    """The DoFs the body is free in, in a domain of ``kind`` (:func:`floatfoam.dofs.free_dofs`:
    a wedge holds a body of revolution to heave)."""
    from floatfoam.dofs import free_dofs

    return [d.name for d in free_dofs(case.release, axisymmetric=kind == "wedge",
                                      chosen=case.settings.motion.free)]


def heave_only(case: Case, kind: str) -> bool:
    """Whether the body is free in heave alone: the layered motion's domain."""
    return free_names(case, kind) == ["heave"]


#: the inner distance's default, × the body's smallest dimension across
INNER_SHARE = 0.5


#: the outer distance's default, × the clearance between the body at its release and the
#: nearest held wall (:func:`clearance`): the rest is left to the walls' first cells
OUTER_SHARE = 0.9


def distances(case: Case, length: float, clearance: float) -> tuple[float, float]:
    """[run] inner and outer distances, else their defaults from the body and the tank: the
    mesh turns rigidly with the body within half of ``length`` (the O-grid's half square, or
    the body's smallest dimension across for a gmsh mesh) and the zone between the distances,
    where the cells are sheared and squeezed, is as wide as the tank allows: out to 0.9 ×
    ``clearance``, the room between the body and the nearest held wall (:func:`clearance`).
    A wider zone shears each cell less for the same motion; one that reaches a held wall
    squeezes the wall's first cells (:func:`clamped_bottom`). The inner distance is at most
    half the outer one. docs/morphing.md has the measurements
    behind the rule."""
    run = case.settings.run
    if run.outer_distance is None and clearance <= 0:
        turning = " turning over" if turns_over(case) else ""
        raise InputError(f"the tank leaves the body no room to move: the body{turning} "
                         f"reaches {-clearance:.3g} m past its nearest held wall; valid is a "
                         "larger tank ([domain] half_length, half_width, depth, air_height) or "
                         "run.inner_distance and run.outer_distance set")
    outer = run.outer_distance if run.outer_distance is not None else OUTER_SHARE * clearance
    inner = run.inner_distance if run.inner_distance is not None \
        else min(INNER_SHARE * length, 0.5 * outer)
    if not 0 < inner < outer:
        raise InputError(f"run.inner_distance = {inner:g} m, run.outer_distance = {outer:g} m "
                         "(defaulted from the body's size and its clearance to the tank's "
                         "walls when not set): valid is 0 < inner_distance < outer_distance, "
                         "with the walls beyond the outer distance")
    return inner, outer


def clearance(case: Case, release: Pose, walls: list[float], kind: str) -> float:
    """The room between the body and the tank's nearest held wall: the smallest distance from
    the body at ``release`` to the top, the bottom and the ends (and the sides in 3D),
    ``walls`` = [air height, depth, half-length, (half-width)] from the still water and the
    tank's middle; a symmetry plane is not a held wall. A body released to turn over (a heel
    or trim in a DoF whose hydrostatic stiffness is not positive: :func:`turns_over`) must
    have room for the circle it sweeps about its G: when it has not, the (negative) room left
    to that circle is returned instead."""
    import numpy as np

    from floatfoam.bodies.geometry import rotation, to_earth

    vertices, _ = case.body.surface_mesh()
    earth = to_earth(vertices, release.z_c, release.heel, release.trim)
    room = _room(earth.min(axis=0), earth.max(axis=0), walls, kind)
    if not turns_over(case):
        return room
    cog = np.asarray(case.cog, dtype=float)
    reach = vertices - cog
    if kind in ("2d", "ogrid"):
        reach = reach[:, 1:]
    radius = float(np.sqrt((reach ** 2).sum(axis=1)).max())
    g = rotation(release.heel, release.trim) @ cog + np.array([0.0, 0.0, release.z_c])
    swept = _room(g - radius, g + radius, walls, kind)
    return room if swept > 0 else swept


def _room(lo, hi, walls: list[float], kind: str) -> float:
    """The smallest distance from the box ``lo``–``hi`` (earth frame) to the held walls."""
    along = 1 if kind in ("2d", "ogrid") else 0
    room = [walls[0] - hi[2], walls[1] + lo[2], walls[2] - max(hi[along], -lo[along])]
    if len(walls) > 3:
        room.append(walls[3] - max(hi[1], -lo[1]))
    return float(min(room))


def turns_over(case: Case) -> bool:
    """Whether the release heels or trims the body in a DoF whose hydrostatic stiffness about
    G is not positive (Le Barbier's verdict: it capsizes or stays)."""
    heel, trim = case.release["heel"], case.release["trim"]
    if not (heel or trim):
        return False
    from floatfoam.hydrostatics.theory import stiffness_matrix

    stiffness = stiffness_matrix(case)
    return bool((heel and stiffness[1, 1] <= 0) or (trim and stiffness[2, 2] <= 0))
