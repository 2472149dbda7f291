"""``floatfoam run``: render, mesh, initialise and run a case at a mesh level, resumably.

Steps (each leaves a marker in ``<run>/.floatfoam/``, so an interrupted run resumes where it
stopped; the solver restarts from its last written time; a finished run asked for a later
run.end_time continues from its last time, :mod:`floatfoam.foam.extension`):

    render → gmshToFoam, patchTypes, checkMesh (or blockMesh) → fields → setAlphaField →
    [decomposePar] → interFoam → [reconstructPar] → finished

The run folder opens in ParaView from the start, by its ``<case>.foam`` file; a parallel run's
fields are gathered into it at the end (:mod:`floatfoam.foam.paraview`).

A mesh made at equilibrium (``[run] mesh_pose``, :func:`to_release_pose`) instead runs
fields → [decomposePar] → releasePose (the solver for no step, the points moved) →
setAlphaField [and setAlphaFieldParallel] → interFoam.

A gmsh mesh (:mod:`floatfoam.foam.domain`) is generated before the run directory is touched, in
a scratch folder, so that a mesh too large for this machine is refused before anything is
written.
"""

from __future__ import annotations

import json
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path

from floatfoam import layout
from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.foam import domain, extension, paraview, runner
from floatfoam.foam.morphing import check_morphing, scaled_morphing
from floatfoam.foam.motionlog import rebuild_motion
from floatfoam.foam.ranks import check_free_cores, check_ranks
from floatfoam.foam.render import end_time_of, release_state, render
from floatfoam.foam.runlock import RunLock, lock_path
from floatfoam.foam.stamps import settings_digest, solver_path, stamped_with
from floatfoam.foam.timedirs import latest_time, set_aside_incomplete
from floatfoam.hydrostatics.theory import Equilibrium
from floatfoam.scratch import scratch_dir


@dataclass
class RunResult:
    run_dir: Path
    motion_csv: Path
    info: dict
    resumed: bool
    already_finished: bool = False


def existing_run(case: Case, level: str, np_: int, build_dir: Path | None = None,
                 divisor: int = 1, morphing: float = 1.0) -> tuple[Path, bool | None]:
    """The run directory and what it holds: None (nothing), True (a finished run of these
    settings, to reuse: its own end time or a later one), False (a run to resume: unfinished,
    or finished and continued to the command's later end time). Raises InputError when it
    holds a run of other settings (or --np), or an unfinished one already written past the
    command's end time (:func:`floatfoam.foam.extension.end_change`). ``case`` is the
    command's, before ``divisor`` and ``morphing`` change it. Writes nothing."""
    run_dir, finished, _ = _existing(case, level, np_, build_dir, divisor, morphing)
    return run_dir, finished


def _existing(case: Case, level: str, np_: int, build_dir: Path | None, divisor: int,
              morphing: float) -> tuple[Path, bool | None, str | None]:
    """:func:`existing_run`, and what the command's end time makes of the run (the change of
    :func:`floatfoam.foam.extension.end_change`)."""
    run_dir = layout.run_dir(case.name, level, build_dir, time_step_divisor=divisor,
                             morphing=morphing)
    if not run_dir.exists():
        return run_dir, None, None
    stamp = run_dir / layout.MARKERS / "settings"
    old = (stamp.read_text().split() if stamp.exists() else []) + ["?", "?"]
    finished = layout.is_finished(run_dir)
    if not stamped_with(case, level, run_dir, divisor, morphing) or old[1] != str(np_):
        what = "a finished run" if finished else "an unfinished run"
        raise InputError(f"{run_dir} holds {what} with other settings (or --np); valid: "
                         "the same settings to resume, or `floatfoam run` with --force to "
                         "move it aside")
    change = extension.end_change(end_time_of(case), run_dir, finished)
    return run_dir, finished and change != extension.CONTINUE, change


def prepare(case: Case, level: str, np_: int, force: bool,
            build_dir: Path | None = None, divisor: int = 1,
            morphing: float = 1.0) -> tuple[Path, bool, bool]:
    """The run directory, whether it resumes, and whether it is already finished. ``case``
    is the command's, before ``divisor`` and ``morphing`` change it: the stamp holds them.
    A run of these settings asked for another run.end_time is continued to it, or kept when
    finished past it (:mod:`floatfoam.foam.extension`); one line says which."""
    run_dir = layout.run_dir(case.name, level, build_dir, time_step_divisor=divisor,
                             morphing=morphing)
    digest = settings_digest(case, level, divisor=divisor, morphing=morphing)
    stamp = run_dir / layout.MARKERS / "settings"
    label = f"{case.name}/{run_dir.name}"
    if run_dir.exists():
        if force:
            moved = runner.move_aside(run_dir)
            print(f"[{label}] earlier run moved to {moved}")
        else:
            _, finished, change = _existing(case, level, np_, build_dir, divisor, morphing)
            if change is not None:
                _new_end_time(case, run_dir, change, label)
            return run_dir, not finished, bool(finished)
    (run_dir / layout.MARKERS).mkdir(parents=True)
    stamp.write_text(f"{digest} {np_}\n")
    return run_dir, False, False


def _new_end_time(case: Case, run_dir: Path, change: str, label: str) -> None:
    """Continue the run in ``run_dir`` to the command's end time, or keep it as it is
    (``change``: :func:`floatfoam.foam.extension.end_change`), and say which in one line."""
    asked, own = end_time_of(case), extension.own_end_time(run_dir)
    if change == extension.KEEP:
        print(f"[{label}] the finished run goes to {own:g} s, past run.end_time = {asked:g} s: "
              "kept as it is, its motion.csv (what every analysis of the run reads) longer "
              f"than asked; --force runs it anew to {asked:g} s", file=sys.stderr)
        return
    set_aside(case, run_dir, label)
    extension.continue_to(run_dir, asked, case.settings.run.write_interval)
    print(f"[{label}] run.end_time = {asked:g} s (the run was made to {own:g} s): it "
          f"continues to {asked:g} s", file=sys.stderr)


def run_case(case: Case, level: str = "coarse", np_: int = 1, force: bool = False,
             build_dir: Path | None = None, *, equilibrium: Equilibrium | None = None,
             hostfile: Path | None = None, time_step_divisor: int = 1,
             morphing: float = 1.0) -> RunResult:
    """Run ``case`` at ``level`` on ``np_`` MPI ranks (see the module docstring); the run
    directory is ``<build_dir>/<case>/<level>`` (:func:`floatfoam.layout.build_dir` by
    default). ``equilibrium`` is the case's (solved here when not given); ``hostfile`` goes to
    mpirun. ``time_step_divisor`` k > 1 divides the level's time-step limits (largest step,
    Courant numbers) by k, in ``<level>-dt<k>``: a time-step study; ``morphing`` f ≠ 1
    spreads its mesh motion wider or narrower by f (:func:`scaled_morphing`: the six-DoF
    distances × f, or the Laplacian's diffusivity 1/d), in ``<level>-morph<f>``: a study of
    the mesh motion. Everything is checked before anything is written; the run holds the run
    directory's lock (:mod:`floatfoam.foam.runlock`) from start to end."""
    check_ranks(np_, hostfile)
    check_morphing(morphing)
    command_case = case  # what the run directory's stamp is of (settings_digest)
    case = smaller_steps(case, time_step_divisor)
    solver_path(case)  # refused before anything is done when missing
    if equilibrium is None:
        from floatfoam.hydrostatics.theory import equilibrium as solve

        equilibrium = solve(case)
    state = release_state(case, equilibrium)
    made_at = mesh_pose(case, state, equilibrium)
    local = hostfile is None
    case = scaled_morphing(case, level, state["pose"], morphing, local=local)
    mesh = domain.plan(case, level, state["pose"], local=local)  # bad input fails here
    end_time_of(case)
    name = layout.run_name(level, time_step_divisor, morphing)
    label = f"{case.name}/{name}"
    target = layout.run_dir(case.name, level, build_dir, time_step_divisor=time_step_divisor,
                            morphing=morphing)
    runner.check_path(target)
    runner.check_disk(target)
    warning = domain.clamped_bottom(mesh, case, made_at, case.settings.run.mesh_pose)
    if warning:
        print(f"[{label}] warning: {warning}", file=sys.stderr)
    pose_name = case.settings.run.mesh_pose
    with scratch_dir("mesh") as scratch:
        if mesh.mesher == "gmsh" and (force or not layout.step_done(target, "render")):
            print(f"[{label}] gmsh: meshing the {mesh.kind} domain (the body at "
                  f"{pose_name})", file=sys.stderr)
            mesh = domain.generate(mesh, case, level, equilibrium, Path(scratch), local=local,
                                   pose_name=pose_name)
        with RunLock(lock_path(case.name, name, build_dir), label) as lock:
            if lock.stale_holder():
                print(f"[{label}] the run of PID {lock.stale_holder()} ended without "
                      "finishing; this run takes its place", file=sys.stderr)
            return _locked_run(case, level, np_, force, build_dir, hostfile, state, mesh,
                               lock, label, time_step_divisor, morphing, command_case)


def check_run(case: Case, level: str, np_: int, equilibrium: Equilibrium, *,
              build_dir: Path | None = None, time_step_divisor: int = 1,
              morphing: float = 1.0) -> None:
    """Everything :func:`run_case` checks before it writes, for a run to come (a study checks
    runs before the first starts): ranks, solver, the mesh's plan, the end time and
    what the run directory holds. Raises InputError; writes nothing."""
    check_ranks(np_, None)
    check_morphing(morphing)
    command_case = case
    case = smaller_steps(case, time_step_divisor)
    solver_path(case)
    state = release_state(case, equilibrium)
    mesh_pose(case, state, equilibrium)
    pose = state["pose"]
    case = scaled_morphing(case, level, pose, morphing)
    domain.plan(case, level, pose, local=True)
    end_time_of(case)
    existing_run(command_case, level, np_, build_dir, time_step_divisor, morphing)


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


def smaller_steps(case: Case, divisor: int) -> Case:
    """The case with its time-step limits (run.max_delta_t, run.max_courant and
    run.max_alpha_courant) divided by ``divisor``, a whole number ≥ 1."""
    if isinstance(divisor, bool) or not isinstance(divisor, int) or divisor < 1:
        raise InputError(f"--dt-divisor {divisor!r}: valid is a whole number ≥ 1")
    if divisor == 1:
        return case
    from floatfoam.case import with_overrides

    run = case.settings.run
    limits = {"max_delta_t": run.max_delta_t, "max_courant": run.max_courant,
              "max_alpha_courant": run.max_alpha_courant}
    return with_overrides(case, [f"run.{key}={value / divisor!r}"
                                 for key, value in limits.items() if value is not None])


def _locked_run(case, level, np_, force, build_dir, hostfile, state, mesh, lock,
                label, divisor, morphing, command_case) -> RunResult:
    """The steps of :func:`run_case`, under the run directory's lock; ``case`` as run,
    ``command_case`` as the command gave it (the stamp's)."""
    run_dir, resumed, finished = prepare(command_case, level, np_, force, build_dir, divisor,
                                         morphing)
    motion = run_dir / "motion.csv"
    info_file = run_dir / layout.MARKERS / "info.json"
    if finished:
        return RunResult(run_dir, motion, json.loads(info_file.read_text()), False, True)
    if not layout.step_done(run_dir, "render"):
        info = render(case, level, run_dir, state, mesh, np_=np_)
        # what the run released and the body's size (m): `floatfoam analyse`'s default DoFs
        info |= {"release": dict(case.release), "body_size": case.body.size,
                 "case_path": str(case.path)}  # the case's folder, for analyse's model
        info = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in info.items()}
        info_file.write_text(json.dumps(info, indent=2))
        layout.mark_done(run_dir, "render")
    info = json.loads(info_file.read_text())
    paraview.write_foam_file(run_dir, case.name)
    if resumed:
        set_aside(case, run_dir, label)
        restart = latest_time(run_dir) or 0.0
        print(f"[{label}] resuming the run in {run_dir} from t = {restart:g} s")
    check = domain.make_polymesh(mesh, run_dir)
    if check is not None:
        print(mesh_line(label, info, check), file=sys.stderr)
    if not layout.step_done(run_dir, "fields"):
        shutil.rmtree(run_dir / "0", ignore_errors=True)
        shutil.copytree(run_dir / "0.orig", run_dir / "0")
        layout.mark_done(run_dir, "fields")
    if any(info.get("mesh_offset") or ()):
        to_release_pose(case, run_dir, info, np_, hostfile, label)
    else:
        runner.run_app(run_dir, "setAlphaField", ["setAlphaField"])
        if np_ > 1:
            runner.run_app(run_dir, "decomposePar", ["decomposePar", "-force"])
    print(f"[{label}] {info['cells']} cells, {np_} rank(s), {info['end_time']:g} s to "
          f"simulate; log: {run_dir / 'log.interFoam'}")
    limits = runner.Limits(max_courant=case.settings.run.divergence_courant,
                           max_body_speed=case.settings.run.divergence_body_speed,
                           min_delta_t=STALL_FRACTION * case.settings.run.max_delta_t
                           / domain.level_factor(case, level))
    reference = info.get("equilibrium_orientation")
    reached = latest_time(run_dir) if resumed else None
    if reached is not None and reached >= info["end_time"] * (1 - 1e-9):
        # the solver wrote end_time, and its driver stopped before saying so
        print(f"[{label}] the solver had reached end_time ({reached:g} s); the motion "
              "series is rebuilt from its log", file=sys.stderr)
        rebuild_motion(run_dir / "log.interFoam", motion, reference)
    else:
        check_free_cores(np_, hostfile, label=label)
        runner.run_solver(run_dir, [str(solver_path(case))], end_time=info["end_time"],
                          np_=np_, hostfile=hostfile, motion_csv=motion, limits=limits,
                          label=label, log_name="interFoam", keep_fds=(lock.fd,),
                          reference=reference)
    paraview.reconstruct(run_dir)  # a parallel run's times, for ParaView's default reader
    layout.mark_done(run_dir, layout.FINISHED)
    return RunResult(run_dir, motion, info, resumed)


STALL_FRACTION = 0.01  # of the level's largest time step: below it, the mesh is giving out


def set_aside(case: Case, run_dir: Path, label: str) -> None:
    """Set a run's incomplete trailing time folders aside
    (:func:`floatfoam.foam.timedirs.set_aside_incomplete`), one line each."""
    for moved in set_aside_incomplete(run_dir, moving=not case.settings.run.static_body):
        print(f"[{label}] an incomplete time folder (a write cut short) is set aside: "
              f"{moved}", file=sys.stderr)


def to_release_pose(case: Case, run_dir: Path, info: dict, np_: int, hostfile: Path | None,
                    label: str) -> None:
    """A mesh made at equilibrium, moved to the release before the first step
    (:mod:`floatfoam.foam.meshpose`): decomposed first, then the solver started for no step
    (end time 0, no function objects) writes its scale field, the points move by it, and the
    water is set on the moved mesh. Each stage runs once (markers)."""
    from foamlib import FoamFile

    from floatfoam.foam import meshpose

    if np_ > 1:
        runner.run_app(run_dir, "decomposePar", ["decomposePar", "-force"])
    if not layout.step_done(run_dir, "releasePose"):
        control = FoamFile(run_dir / "system" / "controlDict")
        control["endTime"] = 0
        try:
            runner.run_app(run_dir, "motionScale", [str(solver_path(case)),
                                                    "-noFunctionObjects"],
                           np_=np_, hostfile=hostfile, marker=False)
        finally:
            control["endTime"] = info["end_time"]
        moved = meshpose.move_to_release(run_dir, info["mesh_offset"])
        print(f"[{label}] mesh made at equilibrium: {moved} points moved to the release "
              f"({info['mesh_offset'][2] * 1000:+.1f} mm)", file=sys.stderr)
        layout.mark_done(run_dir, "releasePose")
    runner.run_app(run_dir, "setAlphaField", ["setAlphaField"])  # the whole case's, for a
    if np_ > 1:  # reconstruction; the ranks' own on their moved meshes
        runner.run_app(run_dir, "setAlphaFieldParallel", ["setAlphaField"], np_=np_,
                       hostfile=hostfile, log_name="setAlphaField.parallel")


def mesh_line(label: str, info: dict, check: dict) -> str:
    """One line on a gmsh mesh: cells, checkMesh's verdict and worst angle, the body patch's
    immersed volume against the exact body's."""
    verdict = "OK" if check.get("mesh_ok") else "reports problems (see log.checkMesh)"
    line = (f"[{label}] {info['mesh']} mesh: {check.get('cells') or info['cells']} cells; "
            f"checkMesh {verdict}, max non-orthogonality "
            f"{check.get('max_non_orthogonality') or 0:.0f}°")
    if info.get("immersed_error") is not None:
        line += f"; body patch immersed volume {info['immersed_error']:+.2e} of the exact body's"
    return line
