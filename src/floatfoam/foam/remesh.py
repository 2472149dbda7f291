"""A run's mesh made anew at the body's pose when the body has turned far from the attitude its
mesh was made at (``[run] remesh_angle``), the fields mapped onto it.

The six-DoF distances' morphing mesh shears the zone between the distances by the body's whole
turn since the mesh was made: a body that turns over cannot be followed by it (docs/morphing.md:
on the morphing mesh alone, the ellipsoid of ``ellipsoid_printed_verdict`` gives out at 58°).
Remeshing k (1, 2, …):

- **stop**: while the solver runs, a step whose attitude is ``remesh_angle`` from the mesh's
  (:class:`Trigger`) asks it to write its current time t_k and stop
  (:func:`floatfoam.foam.runner.stop_at_write_now`);
- **keep**: [reconstructPar of the times not yet gathered]; the mesh, the time folders and the
  ranks' folders move to ``remeshed/<k>/``, a case of its own (ParaView opens it by its
  ``.foam`` file);
- **mesh**: gmsh at the body's pose at t_k (G and attitude from its six-DoF state,
  ``uniform/sixDoFRigidBodyMotionState``), gmshToFoam, the patch types, checkMesh;
- **map**: t_k's fields onto the new mesh (``mapFieldsPar -consistent``, cell-volume
  weighted: the water is conserved; 0.orig's boundary conditions), its ``uniform/`` (the time
  and the body's state) copied, and the dynamicMeshDict's initial centre of mass and
  orientation set to t_k's: the new mesh is the motion's ``points0``, so the body carries on
  from its state with an undeformed mesh; the write interval shrunk to divide the time left,
  so the last write falls on the end time;
- [decomposePar], then the solver resumes from t_k.

Each stage is marked done in ``.floatfoam/`` (``remesh<k>.<stage>``, the whole remeshing
``remesh<k>``), so an interrupted remeshing resumes where it stopped. The mesh follows the body
by the six-DoF distances only (the Laplacian's body state lives in its point field), on a gmsh
mesh of a section, a half or a whole 3D tank (a wedge and the O-grid hold an upright body),
whose body has not turned about the vertical (a pose has heel and trim).
"""

from __future__ import annotations

import math
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from floatfoam import layout
from floatfoam.foam import domain, extension, runner
from floatfoam.tank import Pose

ARCHIVE = layout.REMESHED  # remeshed/<k>: the run on its k-th mesh, up to its remeshing
KINDS = ("2d", "3d", "3d-half")  # the gmsh meshes a pose can be remade in
YAW_LIMIT = math.radians(0.5)  # a turn about the vertical (which heel and trim cannot make)
# mapFieldsPar's cell-volume-weighted map conserves the water (measured on
# elliptic_cylinder_capsize's first remeshing: to 1e-14 of 35.98 m³); v1912's mapFields
# interpolates (mapNearest, interpolate, cellPointInterpolate) and lost 0.05 % of it there,
# 0.017 m³ per metre, 70 % of the section's displacement
MAP_METHOD = "cellVolumeWeight"


def applies(case, mesh) -> bool:
    """Whether the run can be remeshed: ``run.remesh_angle`` > 0, a moving body, the six-DoF
    distances' mesh motion on a gmsh mesh of :data:`KINDS`."""
    run = case.settings.run
    return (run.remesh_angle > 0.0 and not run.static_body and mesh.motion == "distances"
            and mesh.kind in KINDS)


def _coeffs(run_dir: Path):
    from foamlib import FoamFile

    return FoamFile(run_dir / "constant" / "dynamicMeshDict")["sixDoFRigidBodyMotionCoeffs"]


def mesh_attitude(run_dir: Path) -> np.ndarray:
    """The body's attitude when its current mesh was made: the dynamicMeshDict's initial
    orientation (the release's, or the last remeshing's)."""
    coeffs = _coeffs(run_dir)
    value = coeffs.get("initialOrientation", coeffs.get("orientation"))
    return np.eye(3) if value is None else np.asarray(value, dtype=float).reshape(3, 3)


def turn_angle(q: np.ndarray, q0: np.ndarray) -> float:
    """The angle (rad) of the rotation from attitude ``q0`` to ``q``."""
    cos = (np.trace(np.asarray(q) @ np.asarray(q0).T) - 1.0) / 2.0
    return math.acos(max(-1.0, min(1.0, cos)))


@dataclass
class Trigger:
    """Fires (a reason, in words) at the first step whose attitude is ``limit`` (rad) or more
    from the mesh's ``attitude``."""

    attitude: np.ndarray
    limit: float
    fired: str | None = None

    def check(self, steps) -> str | None:
        for step in steps:
            if step.orientation is not None:
                angle = turn_angle(step.orientation, self.attitude)
                if angle >= self.limit:
                    return (f"the body has turned {math.degrees(angle):.1f}° from its mesh's "
                            f"attitude (run.remesh_angle = {math.degrees(self.limit):g}°): "
                            "the domain is meshed anew at its pose")
        return None


def trigger(case, mesh, run_dir: Path) -> Trigger | None:
    """The run's :class:`Trigger`, or None when it is not remeshed (:func:`applies`)."""
    if not applies(case, mesh):
        return None
    return Trigger(mesh_attitude(run_dir), math.radians(case.settings.run.remesh_angle))


def done(run_dir: Path) -> int:
    """How many remeshings the run has finished."""
    count = 0
    while layout.step_done(run_dir, f"remesh{count + 1}"):
        count += 1
    return count


def pending(run_dir: Path) -> bool:
    """Whether a solver stopped for a remeshing that has not finished."""
    return layout.step_done(run_dir, f"remesh{done(run_dir) + 1}.stopped")


def stopped_at(run_dir: Path) -> float | None:
    """The time a pending remeshing resumes the run from, once its run is kept aside."""
    kept = run_dir / ARCHIVE / str(done(run_dir) + 1) / "remeshed-at"
    return float(kept.read_text()) if pending(run_dir) and kept.is_file() else None


def mark_stopped(run_dir: Path) -> None:
    """Record that the solver stopped for the next remeshing (written before it starts)."""
    layout.mark_done(run_dir, f"remesh{done(run_dir) + 1}.stopped")


def body_state(run_dir: Path, time_name: str) -> dict:
    """The body's six-DoF state written at ``time_name``: centre of rotation, attitude
    (rotation tensor), G (m, earth frame)."""
    from foamlib import FoamFile

    state = FoamFile(run_dir / time_name / "uniform" / "sixDoFRigidBodyMotionState")
    coeffs = _coeffs(run_dir)
    q = np.asarray(state["orientation"], dtype=float).reshape(3, 3)
    centre = np.asarray(state["centreOfRotation"], dtype=float)
    mass0 = np.asarray(coeffs.get("initialCentreOfMass", coeffs["centreOfMass"]), dtype=float)
    rotation0 = mass0
    for entry in dict(coeffs.get("constraints") or {}).values():
        if "centreOfRotation" in entry:
            rotation0 = np.asarray(entry["centreOfRotation"], dtype=float)
    q0 = mesh_attitude(run_dir)
    cog = centre + q @ q0.T @ (mass0 - rotation0)  # v1912's centreOfMass()
    return {"centre": centre, "orientation": q, "cog": cog}


def pose_of(case, mesh, state: dict) -> Pose:
    """The body frame's pose (:class:`floatfoam.tank.Pose`) from its six-DoF ``state``: the
    attitude Q = R_y(trim)·R_x(heel) (docs/conventions.md; any heel and trim, past 90° too),
    and the origin, G less Q applied to G's body-frame position (in a 2D slab, along the
    section's length G is the slab's middle, which no pose places). An attitude no heel and
    trim make (a turn about the vertical) is refused."""
    from floatfoam.bodies.geometry import rotation

    q = np.asarray(state["orientation"], dtype=float)
    heel = math.atan2(-q[1, 2], q[1, 1])
    trim = math.atan2(-q[2, 0], q[0, 0])
    off = float(np.max(np.abs(rotation(heel, trim) - q)))
    if off > math.sin(YAW_LIMIT):
        raise runner.RunError(f"the body has turned about the vertical ({off:.3g} of its "
                              "attitude no heel and trim give), which a remeshed pose cannot "
                              "hold; valid: run.remesh_angle = 0 (no remeshing) or a body held "
                              "in yaw")
    origin = np.asarray(state["cog"], dtype=float) - q @ np.asarray(case.cog, dtype=float)
    x_c = 0.0 if mesh.kind == "2d" else float(origin[0])
    return Pose(z_c=float(origin[2]), heel=heel, trim=trim, x_c=x_c, y_c=float(origin[1]))


def remesh(plan, mesh, run_dir: Path, hostfile: Path | None, label: str) -> None:
    """Remeshing k = :func:`done` + 1 of the run in ``run_dir`` at its latest written time (see
    the module docstring); each stage once."""
    from foamlib import FoamFile

    from floatfoam.foam.timedirs import latest_time

    case, np_ = plan.case, plan.np
    k = done(run_dir) + 1
    tag = f"remesh{k}"
    archive = run_dir / ARCHIVE / str(k)
    at = archive / "remeshed-at"  # the time remeshed at, written before anything moves
    if not layout.step_done(run_dir, f"{tag}.keep"):
        if not at.is_file():
            t = latest_time(run_dir)
            if t is None:
                raise runner.RunError(f"{label}: remeshing {k}: the solver wrote no time to "
                                      "remesh from")
            archive.mkdir(parents=True, exist_ok=True)
            at.write_text(_name(run_dir, t) + "\n")
        if np_ > 1:  # the mesh's times gathered, for the map and ParaView
            runner.run_app(run_dir, f"{tag}.reconstructPar", ["reconstructPar", "-newTimes"])
        _keep(run_dir, archive, case.name)
        layout.mark_done(run_dir, f"{tag}.keep")
    time_name = at.read_text().strip()
    state = body_state(archive, time_name)
    where = pose_of(case, mesh, state)
    if not layout.step_done(run_dir, f"{tag}.mesh"):
        print(f"[{label}] remeshing {k} at t = {time_name} s: gmsh meshes the "
              f"{mesh.kind} domain with the body at {math.degrees(where.heel):.1f}° heel, "
              f"{math.degrees(where.trim):.1f}° trim", file=sys.stderr)
        made = domain.generate(mesh, case, plan.level, plan.equilibrium, run_dir,
                               local=plan.local, where=where, name=f"{tag}.msh")
        domain.make_polymesh(made, run_dir, remade=tag)
        layout.mark_done(run_dir, f"{tag}.mesh")
    if not layout.step_done(run_dir, f"{tag}.map"):
        _map(run_dir, archive, time_name, tag)
        _restart_at(run_dir, state)
        extension.writes_from(FoamFile(run_dir / "system" / "controlDict"), float(time_name),
                              case.settings.run.write_interval)
        layout.mark_done(run_dir, f"{tag}.map")
    if np_ > 1:
        runner.run_app(run_dir, f"{tag}.decomposePar", ["decomposePar", "-force"])
    layout.mark_done(run_dir, tag)


def _name(run_dir: Path, t: float) -> str:
    """The name of the time folder of ``t`` (the whole case's, else the first rank's)."""
    for root in (run_dir, run_dir / "processor0"):
        for value, path in layout.time_folders(root):
            if abs(value - t) <= 1e-9 * max(abs(t), 1.0):
                return path.name
    raise runner.RunError(f"no time folder of t = {t:g} s in {run_dir}")


def _keep(run_dir: Path, archive: Path, case_name: str) -> None:
    """Move the run's mesh, time folders and ranks' folders to ``archive``, with a copy of its
    system/ and constant/ dictionaries: a case of its own. What is moved already stays where it
    went (an interrupted move resumes)."""
    (archive / "constant").mkdir(parents=True, exist_ok=True)
    for name in ("system",):
        if not (archive / name).exists():
            shutil.copytree(run_dir / name, archive / name)
    for item in (run_dir / "constant").iterdir():
        if item.is_file() and not (archive / "constant" / item.name).exists():
            shutil.copy2(item, archive / "constant" / item.name)
    movable = [run_dir / "constant" / "polyMesh", *sorted(run_dir.glob("processor[0-9]*"))]
    for path in run_dir.iterdir():
        try:
            float(path.name)
        except ValueError:
            continue
        if path.is_dir():
            movable.append(path)
    for path in movable:
        target = archive / path.relative_to(run_dir)
        if path.exists() and not target.exists():
            path.rename(target)
    (archive / f"{case_name}.foam").touch()


def _map(run_dir: Path, archive: Path, time_name: str, tag: str) -> None:
    """The time folder ``time_name`` on the new mesh: 0.orig's fields, their values mapped from
    the archived run there (mapFieldsPar maps the cell fields; the point displacement, which it
    sets aside as ``.unmapped``, is 0.orig's: the new mesh is undeformed), and its uniform/
    (time, six-DoF state) copied."""
    from foamlib import FoamFile

    target = run_dir / time_name
    shutil.rmtree(target, ignore_errors=True)
    shutil.copytree(run_dir / "0.orig", target)
    # the solver names a time with more digits than timePrecision when fewer would repeat the
    # last step's name (measured: 1.06128378 at timePrecision 8); mapFieldsPar would then write
    # into 1.0612838, and the run restart from two folders of one time
    control = FoamFile(run_dir / "system" / "controlDict")
    digits = len(time_name.replace(".", "").lstrip("0"))
    if digits > int(control["timePrecision"]):
        control["timePrecision"] = digits
    runner.run_app(run_dir, f"{tag}.mapFieldsPar",
                   ["mapFieldsPar", str(archive.resolve()), "-consistent", "-sourceTime",
                    time_name, "-mapMethod", MAP_METHOD], marker=False)
    for unmapped in target.glob("*.unmapped"):  # a field it does not map (points)
        shutil.copyfile(run_dir / "0.orig" / unmapped.stem, target / unmapped.stem)
        unmapped.unlink()
    shutil.copytree(archive / time_name / "uniform", target / "uniform", dirs_exist_ok=True)


def _restart_at(run_dir: Path, state: dict) -> None:
    """The dynamicMeshDict's initial centre of mass, centre of rotation and orientation set to
    the body's ``state``: the mesh as made is where the body is."""
    from foamlib import FoamFile

    cog = [float(v) for v in state["cog"]]
    q = [float(v) for v in state["orientation"].ravel()]
    with FoamFile(run_dir / "constant" / "dynamicMeshDict") as dictionary:
        coeffs = dictionary["sixDoFRigidBodyMotionCoeffs"]
        coeffs["centreOfMass"] = cog
        coeffs["initialCentreOfMass"] = cog
        coeffs["centreOfRotation"] = cog
        coeffs["orientation"] = q
        coeffs["initialOrientation"] = q
        constraints = coeffs.get("constraints") or {}
        for name in list(dict(constraints)):
            if "centreOfRotation" in constraints[name]:
                constraints[name]["centreOfRotation"] = cog
