"""A run resolved once from the command (:func:`resolve`): the case as the run takes it, its
level, ranks, release and the pose its mesh is made at, its simulated time, its folder and the
settings digest its stamp holds, each checked here before anything is written (the mesh's
plan and the ranks are checked by the driver, :func:`floatfoam.foam.driver.check_plan`, also
before it writes); the driver (:mod:`floatfoam.foam.driver`) and the render take the plan as
it is."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from floatfoam import layout
from floatfoam.case import Case
from floatfoam.hydrostatics.theory import Equilibrium
from floatfoam.plan import zone
from floatfoam.plan.kind import kind_of
from floatfoam.plan.level import level_index
from floatfoam.plan.morphing import check_morphing, scaled_morphing
from floatfoam.plan.release import (
    check_divisor,
    end_time_of,
    mesh_pose,
    release_state,
    smaller_steps,
)
from floatfoam.plan.stamps import (
    check_interface_gravity_solver,
    check_layered_solver,
    settings_digest,
    solver_path,
)
from floatfoam.tank import Pose


@dataclass(frozen=True)
class RunPlan:
    """One run of a case, resolved (lengths in m, times in s).

    command_case : the case as the command gives it (the run's stamp is its digest)
    case : the case as run: its time steps divided by ``divisor``, its mesh motion spread by
        ``morphing`` (:func:`floatfoam.plan.morphing.scaled_morphing`)
    level : "coarse", "medium" or "fine"; np : MPI ranks; hostfile : Open MPI's, or None
        for this machine
    divisor, morphing : a time-step study's divisor, a mesh-motion study's factor (1: none)
    equilibrium : the case's; state : the body at release
        (:func:`floatfoam.plan.release.release_state`, with ``mesh_offset`` for a mesh made at
        equilibrium); made_at : the pose the mesh is made at
    end_time : the simulated time; run_dir : the run's folder; digest : its settings digest
    """

    command_case: Case
    case: Case
    level: str
    np: int
    hostfile: Path | None
    divisor: int
    morphing: float
    equilibrium: Equilibrium
    state: dict
    made_at: Pose
    end_time: float
    run_dir: Path
    digest: str

    @property
    def release(self) -> Pose:
        return self.state["pose"]

    @property
    def local(self) -> bool:
        """The run is on this machine (no hostfile), whose memory bounds its cells."""
        return self.hostfile is None

    @property
    def label(self) -> str:
        """``<case>/<run folder>``, what the run's lines start with."""
        return f"{self.case.name}/{self.run_dir.name}"


def resolve(case: Case, level: str = "coarse", np_: int = 1, *,
            build_dir: Path | None = None, equilibrium: Equilibrium | None = None,
            hostfile: Path | None = None, divisor: int = 1, morphing: float = 1.0,
            solver: bool = True) -> RunPlan:
    """The plan of a run of ``case`` at ``level`` on ``np_`` ranks: ``divisor`` k > 1
    divides the level's time-step limits by k (a time-step study, in ``<level>-dt<k>``),
    ``morphing`` f ≠ 1 spreads the mesh motion by f (in ``<level>-morph<f>``); ``equilibrium``
    is the case's (solved here when not given); ``solver`` False leaves out the check that the
    solver exists (a plan only compared with a run folder's). Raises InputError on bad input;
    writes nothing."""
    level_index(level)
    check_morphing(morphing)
    check_divisor(divisor)
    if solver:
        solver_path(case)  # refused before anything is done when missing
        check_interface_gravity_solver(case)
    if equilibrium is None:
        from floatfoam.hydrostatics.theory import equilibrium as solve

        equilibrium = solve(case)
    state = release_state(case, equilibrium)
    run = smaller_steps(case, divisor, kind_of(case, state["pose"]))
    made_at = mesh_pose(run, state, equilibrium)
    end_time = end_time_of(run)
    run = scaled_morphing(run, state["pose"], morphing)
    if solver and zone.of_case(run, state["pose"]).motion == "layered":
        check_layered_solver(run)
    run_dir = layout.run_dir(case.name, level, build_dir, time_step_divisor=divisor,
                             morphing=morphing)
    digest = settings_digest(case, level, divisor=divisor, morphing=morphing,
                             release=state["pose"])
    return RunPlan(command_case=case, case=run, level=level, np=np_, hostfile=hostfile,
                   divisor=divisor, morphing=morphing, equilibrium=equilibrium, state=state,
                   made_at=made_at, end_time=end_time, run_dir=run_dir, digest=digest)
