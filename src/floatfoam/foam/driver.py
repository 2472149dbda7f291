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

import shutil
import sys
from dataclasses import dataclass
from pathlib import Path

from floatfoam import layout
from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.foam import domain, extension, paraview, remesh, runner
from floatfoam.foam.motionlog import rebuild_motion
from floatfoam.foam.ranks import check_free_cores, check_ranks, solver_lock, solver_turn
from floatfoam.foam.render import render
from floatfoam.foam.runlock import RunLock, lock_path
from floatfoam.foam.timedirs import latest_time, set_aside_incomplete
from floatfoam.hydrostatics.theory import Equilibrium
from floatfoam.plan.record import RunRecord, read_record, write_record
from floatfoam.plan.runplan import RunPlan, resolve
from floatfoam.plan.stamps import solver_path, stamp_words, write_stamp
from floatfoam.scratch import scratch_dir


@dataclass
class RunResult:
    run_dir: Path
    motion_csv: Path
    info: RunRecord
    resumed: bool
    already_finished: bool = False


def existing_run(case: Case, level: str, np_: int, build_dir: Path | None = None,
                 divisor: int = 1, morphing: float = 1.0) -> tuple[Path, bool | None]:
    """The run directory of ``case`` at ``level`` and what it holds (:func:`existing`), the
    run's plan resolved here (:func:`floatfoam.plan.runplan.resolve`). Writes nothing."""
    plan = resolve(case, level, np_, build_dir=build_dir, divisor=divisor, morphing=morphing,
                   solver=False)
    finished, _ = existing(plan)
    return plan.run_dir, finished


def existing(plan: RunPlan) -> tuple[bool | None, str | None]:
    """What the plan's run directory holds: None (nothing), True (a finished run of these
    settings, to reuse: its own end time or a later one), False (a run to resume: unfinished,
    or finished and continued to the command's later end time); and what the command's end
    time makes of it (the change of :func:`floatfoam.foam.extension.end_change`). Raises
    InputError when it holds a run of other settings (or --np), or an unfinished one already
    written past the command's end time. Writes nothing."""
    run_dir = plan.run_dir
    if not run_dir.exists():
        return None, None
    finished = layout.is_finished(run_dir)
    if stamp_words(run_dir) != (plan.digest, str(plan.np)):
        what = "a finished run" if finished else "an unfinished run"
        raise InputError(f"{run_dir} holds {what} with other settings (or --np); valid: "
                         "the same settings to resume, or `floatfoam run` with --force to "
                         "move it aside")
    change = extension.end_change(plan.end_time, run_dir, finished)
    return finished and change != extension.CONTINUE, change


def prepare(plan: RunPlan, force: bool = False) -> tuple[bool, bool]:
    """The plan's run directory made or taken up: whether the run resumes, and whether it is
    already finished. A run of these settings asked for another run.end_time is continued to
    it, or kept when finished past it (:mod:`floatfoam.foam.extension`); one line says which.
    ``force`` moves an earlier run aside."""
    run_dir = plan.run_dir
    if run_dir.exists():
        if force:
            moved = runner.move_aside(run_dir)
            print(f"[{plan.label}] earlier run moved to {moved}")
        else:
            finished, change = existing(plan)
            if change is not None:
                _new_end_time(plan, change)
            return not finished, bool(finished)
    write_stamp(run_dir, plan.digest, plan.np)
    return False, False


def _new_end_time(plan: RunPlan, change: str) -> None:
    """Continue the plan's run to the command's end time, or keep it as it is (``change``:
    :func:`floatfoam.foam.extension.end_change`), and say which in one line."""
    asked, own, label = plan.end_time, extension.own_end_time(plan.run_dir), plan.label
    if change == extension.KEEP:
        print(f"[{label}] the finished run goes to {own:g} s, past run.end_time = {asked:g} s: "
              "kept as it is, its motion.csv (what every analysis of the run reads) longer "
              f"than asked; --force runs it anew to {asked:g} s", file=sys.stderr)
        return
    set_aside(plan.case, plan.run_dir, label)
    extension.continue_to(plan.run_dir, asked, plan.case.settings.run.write_interval)
    print(f"[{label}] run.end_time = {asked:g} s (the run was made to {own:g} s): it "
          f"continues to {asked:g} s", file=sys.stderr)


def run_case(case: Case, level: str = "coarse", np_: int = 1, force: bool = False,
             build_dir: Path | None = None, *, equilibrium: Equilibrium | None = None,
             hostfile: Path | None = None, time_step_divisor: int = 1,
             morphing: float = 1.0) -> RunResult:
    """Run ``case`` at ``level`` on ``np_`` MPI ranks (:func:`run_plan`, its plan resolved by
    :func:`floatfoam.plan.runplan.resolve`); the run directory is
    ``<build_dir>/<case>/<level>`` (:func:`floatfoam.layout.build_dir` by default).
    ``equilibrium`` is the case's (solved here when not given); ``hostfile`` goes to mpirun.
    ``time_step_divisor`` k > 1 divides the level's time-step limits (largest step, Courant
    numbers) by k, in ``<level>-dt<k>``: a time-step study; ``morphing`` f ≠ 1 spreads its
    mesh motion wider or narrower by f (the six-DoF distances × f, the Laplacian's
    diffusivity 1/d, the layered motion's rows over f × the body's height), in
    ``<level>-morph<f>``: a study of the mesh motion."""
    return run_plan(resolve(case, level, np_, build_dir=build_dir,
                            equilibrium=equilibrium, hostfile=hostfile,
                            divisor=time_step_divisor, morphing=morphing), force)


def run_plan(plan: RunPlan, force: bool = False) -> RunResult:
    """Run a resolved plan (see the module docstring). Everything is checked before anything
    is written; the run holds the run directory's lock (:mod:`floatfoam.foam.runlock`) from
    start to end. ``force`` moves an earlier run aside and runs anew."""
    check_ranks(plan.np, plan.hostfile)
    solver_lock()
    case, run_dir, label = plan.case, plan.run_dir, plan.label
    mesh = domain.plan(case, plan.level, plan.release, local=plan.local)  # bad input fails here
    runner.check_path(run_dir)
    runner.check_disk(run_dir)
    pose_name = case.settings.run.mesh_pose
    warning = domain.clamped_bottom(mesh, case, plan.made_at, pose_name)
    if warning:
        print(f"[{label}] warning: {warning}", file=sys.stderr)
    with scratch_dir("mesh") as scratch:
        if mesh.mesher == "gmsh" and (force or not layout.step_done(run_dir, "render")):
            print(f"[{label}] gmsh: meshing the {mesh.kind} domain (the body at "
                  f"{pose_name})", file=sys.stderr)
            mesh = domain.generate(mesh, case, plan.level, plan.equilibrium, Path(scratch),
                                   local=plan.local, pose_name=pose_name)
        lock = lock_path(run_dir.parent.name, run_dir.name, run_dir.parent.parent)
        with RunLock(lock, label) as held:
            if held.stale_holder():
                print(f"[{label}] the run of PID {held.stale_holder()} ended without "
                      "finishing; this run takes its place", file=sys.stderr)
            return _locked_run(plan, mesh, force, held)


def check_run(case: Case, level: str, np_: int, equilibrium: Equilibrium, *,
              build_dir: Path | None = None, time_step_divisor: int = 1,
              morphing: float = 1.0) -> None:
    """Everything :func:`run_plan` checks before it writes, for a run to come: ranks, solver,
    the plan (:func:`floatfoam.plan.runplan.resolve`) and :func:`check_plan`. Raises
    InputError; writes nothing."""
    check_ranks(np_, None)
    solver_lock()
    check_plan(resolve(case, level, np_, build_dir=build_dir, equilibrium=equilibrium,
                       divisor=time_step_divisor, morphing=morphing))


def check_plan(plan: RunPlan) -> None:
    """What :func:`run_plan` checks of a resolved plan before it writes (a study checks its runs
    before the first starts): the mesh's plan and what the run directory holds. Raises
    InputError; writes nothing."""
    domain.plan(plan.case, plan.level, plan.release, local=plan.local)
    existing(plan)


def _locked_run(plan: RunPlan, mesh, force: bool, lock) -> RunResult:
    """The steps of :func:`run_plan`, under the run directory's lock."""
    case, np_, hostfile, label = plan.case, plan.np, plan.hostfile, plan.label
    resumed, finished = prepare(plan, force)
    run_dir = plan.run_dir
    motion = run_dir / "motion.csv"
    if finished:
        return RunResult(run_dir, motion, read_record(run_dir), False, True)
    if not layout.step_done(run_dir, "render"):
        write_record(run_dir, render(plan, mesh))
        layout.mark_done(run_dir, "render")
    info = read_record(run_dir)
    paraview.write_foam_file(run_dir, case.name)
    if resumed:
        set_aside(case, run_dir, label)
        restart = latest_time(run_dir) or remesh.stopped_at(run_dir) or 0.0
        print(f"[{label}] resuming the run in {run_dir} from t = {restart:g} s")
    check = domain.make_polymesh(mesh, run_dir)
    if check is not None:
        print(mesh_line(label, info, check), file=sys.stderr)
    if not layout.step_done(run_dir, "fields"):
        shutil.rmtree(run_dir / "0", ignore_errors=True)
        shutil.copytree(run_dir / "0.orig", run_dir / "0")
        layout.mark_done(run_dir, "fields")
    if any(info.mesh_offset or ()):
        with solver_turn(label, np_, hostfile):  # its solver and setAlphaField on the ranks
            to_release_pose(case, run_dir, info, np_, hostfile, label)
    else:
        runner.run_app(run_dir, "setAlphaField", ["setAlphaField"])
        if np_ > 1:
            runner.run_app(run_dir, "decomposePar", ["decomposePar", "-force"])
    print(f"[{label}] {info.cells} cells, {np_} rank(s), {info.end_time:g} s to "
          f"simulate; log: {run_dir / 'log.interFoam'}")
    limits = runner.Limits(max_courant=case.settings.run.divergence_courant,
                           max_body_speed=case.settings.run.divergence_body_speed,
                           min_delta_t=stall_step(case.settings.run.max_delta_t,
                                                  mesh.factor))
    reference = info.equilibrium_orientation
    log = run_dir / "log.interFoam"
    if resumed and log.is_file():
        # the record from the log, which holds every step: a driver stopped after the
        # solver's last step, or killed with SIGKILL while its solver ran on until the
        # watchdog stopped it (floatfoam.foam.processes), left steps, a time folder among
        # them, that reached the log alone
        rebuild_motion(log, motion, reference)
    reached = latest_time(run_dir) if resumed else None
    if reached is not None and reached >= info.end_time * (1 - 1e-9):
        # the solver wrote end_time, and its driver stopped before saying so
        print(f"[{label}] the solver had reached end_time ({reached:g} s); the motion "
              "series is rebuilt from its log", file=sys.stderr)
    else:
        with solver_turn(label, np_, hostfile) as turn:  # FLOATFOAM_SOLVER_LOCK's cores
            check_free_cores(np_, hostfile, label=label)
            while True:
                if remesh.pending(run_dir):  # the solver stopped for it: a mesh anew
                    remesh.remesh(plan, mesh, run_dir, hostfile, label)
                stop = remesh.trigger(case, mesh, run_dir)
                runner.run_solver(run_dir, [str(solver_path(case))], end_time=info.end_time,
                                  np_=np_, hostfile=hostfile, motion_csv=motion,
                                  limits=limits, label=label, log_name="interFoam",
                                  keep_fds=(lock.fd, *turn), reference=reference, stop=stop)
                if stop is None or not stop.fired:
                    break
                remesh.mark_stopped(run_dir)
    paraview.reconstruct(run_dir)  # a parallel run's times, for ParaView's default reader
    layout.mark_done(run_dir, layout.FINISHED)
    return RunResult(run_dir, motion, info, resumed)


# 100 steps in a row below the stall step stop the run (the mesh giving out, or the flow
# blowing up). Measured: collapses fall to 3–10 µs (runner.Limits); a body turning over
# legitimately to 55 µs (ellipsoid_printed_verdict, the air over it at 9 m/s), which a floor
# of 50 µs stopped within 10 %. 25 µs is 2 × either way; a largest step under 40 × that
# (1 ms) lowers it in proportion, so that a run's every step is not below it.
STALL_STEP = 25e-6
STALL_FRACTION = 1 / 40


def stall_step(max_delta_t: float, factor: float) -> float:
    """The stall floor of a level whose cells are ``factor`` times finer than the coarse one's
    (its steps as much shorter): ``STALL_STEP``, or ``STALL_FRACTION`` of a largest step
    ``max_delta_t`` smaller than 1 ms, over ``factor``."""
    return min(STALL_STEP, STALL_FRACTION * max_delta_t) / factor


def set_aside(case: Case, run_dir: Path, label: str) -> None:
    """Set a run's incomplete trailing time folders aside
    (:func:`floatfoam.foam.timedirs.set_aside_incomplete`), one line each."""
    for moved in set_aside_incomplete(run_dir, moving=not case.settings.run.static_body):
        print(f"[{label}] an incomplete time folder (a write cut short) is set aside: "
              f"{moved}", file=sys.stderr)


def to_release_pose(case: Case, run_dir: Path, info: RunRecord, np_: int,
                    hostfile: Path | None, label: str) -> None:
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
            control["endTime"] = info.end_time
        moved = meshpose.move_to_release(run_dir, info.mesh_offset)
        print(f"[{label}] mesh made at equilibrium: {moved} points moved to the release "
              f"({info.mesh_offset[2] * 1000:+.1f} mm)", file=sys.stderr)
        layout.mark_done(run_dir, "releasePose")
    runner.run_app(run_dir, "setAlphaField", ["setAlphaField"])  # the whole case's, for a
    if np_ > 1:  # reconstruction; the ranks' own on their moved meshes
        runner.run_app(run_dir, "setAlphaFieldParallel", ["setAlphaField"], np_=np_,
                       hostfile=hostfile, log_name="setAlphaField.parallel")


def mesh_line(label: str, info: RunRecord, check: dict) -> str:
    """One line on a gmsh mesh: cells, checkMesh's verdict and worst angle, the body patch's
    immersed volume against the exact body's."""
    verdict = "OK" if check.get("mesh_ok") else "reports problems (see log.checkMesh)"
    line = (f"[{label}] {info.mesh} mesh: {check.get('cells') or info.cells} cells; "
            f"checkMesh {verdict}, max non-orthogonality "
            f"{check.get('max_non_orthogonality') or 0:.0f}°")
    if info.immersed_error is not None:
        line += f"; body patch immersed volume {info.immersed_error:+.2e} of the exact body's"
    return line
