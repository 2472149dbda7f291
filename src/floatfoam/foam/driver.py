"""``floatfoam run``: render, mesh, initialise and run a case at a mesh level, resumably.

Steps (each leaves a marker in ``<run>/.floatfoam/``, so an interrupted run resumes where it
stopped; the solver restarts from its last written time):

    render → blockMesh → fields → setAlphaField → [decomposePar] → interFoam → finished
"""

from __future__ import annotations

import hashlib
import json
import shutil
from dataclasses import dataclass
from pathlib import Path

from floatfoam import layout
from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.foam import runner
from floatfoam.foam.render import ogrid_for, release_state, render
from floatfoam.hydrostatics.theory import Equilibrium


@dataclass
class RunResult:
    run_dir: Path
    motion_csv: Path
    info: dict
    resumed: bool
    already_finished: bool = False


def settings_digest(case: Case, level: str) -> str:
    """Hash of what a run depends on: the case, the level, the shared dictionaries and the
    solver binary."""
    digest = hashlib.sha256(json.dumps({"case": case.raw, "level": level}, sort_keys=True,
                                       default=str).encode())
    for path in sorted(layout.COMMON_DIR.rglob("*")):
        if path.is_file():
            digest.update(path.read_bytes())
    digest.update(str(solver_path(case)).encode())
    return digest.hexdigest()[:16]


def solver_path(case: Case) -> Path:
    """The interFoam to run: floatfoam's rebuilt one unless [run] solver names another."""
    path = Path(case.settings.run.solver or layout.SOLVER)
    path = path if path.is_absolute() else layout.ROOT / path
    if not path.is_file():
        raise InputError(f"run.solver = {str(path)!r} does not exist; run `make setup` to build "
                         "floatfoam's interFoam (scripts/build_solver.sh)")
    return path


def prepare(case: Case, level: str, np_: int, force: bool,
            build_dir: Path | None = None) -> tuple[Path, bool, bool]:
    """The run directory, whether it resumes, and whether it is already finished."""
    run_dir = layout.run_dir(case.name, level, build_dir)
    digest = settings_digest(case, level)
    stamp = run_dir / layout.MARKERS / "settings"
    if run_dir.exists():
        old = (stamp.read_text().split() if stamp.exists() else []) + ["?", "?"]
        finished = layout.is_finished(run_dir)
        same = old[0] == digest and old[1] == str(np_)
        if force:
            moved = runner.move_aside(run_dir)
            print(f"[{case.name}/{level}] earlier run moved to {moved}")
        elif finished and same:
            return run_dir, False, True
        elif finished or not same:
            what = "a finished run" if finished else "an unfinished run"
            raise InputError(f"{run_dir} holds {what} with other settings (or --np); valid: "
                             "the same settings to resume, or --force to move it aside")
        else:
            return run_dir, True, False
    (run_dir / layout.MARKERS).mkdir(parents=True)
    stamp.write_text(f"{digest} {np_}\n")
    return run_dir, False, False


def run_case(case: Case, level: str = "coarse", np_: int = 1, force: bool = False,
             build_dir: Path | None = None, *, equilibrium: Equilibrium | None = None
             ) -> RunResult:
    """Run ``case`` at ``level`` on ``np_`` MPI ranks (see the module docstring); the run
    directory is ``<build_dir>/<case>/<level>`` (:func:`floatfoam.layout.build_dir` by
    default). ``equilibrium`` is the case's (solved here when not given)."""
    if np_ < 1:
        raise InputError(f"--np {np_}: valid is a whole number ≥ 1")
    solver = solver_path(case)
    if equilibrium is None:
        from floatfoam.hydrostatics.theory import equilibrium as solve

        equilibrium = solve(case)
    state = release_state(case, equilibrium)
    grid = ogrid_for(case, level, state)  # bad input fails here, before anything is written
    run_dir, resumed, finished = prepare(case, level, np_, force, build_dir)
    motion = run_dir / "motion.csv"
    info_file = run_dir / layout.MARKERS / "info.json"
    if finished:
        return RunResult(run_dir, motion, json.loads(info_file.read_text()), False, True)
    label = f"{case.name}/{level}"
    if not layout.step_done(run_dir, "render"):
        info = render(case, level, run_dir, state, grid, np_=np_)
        info = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in info.items()}
        info_file.write_text(json.dumps(info, indent=2))
        layout.mark_done(run_dir, "render")
    info = json.loads(info_file.read_text())
    if resumed:
        print(f"[{label}] resuming the run in {run_dir}")
    runner.run_app(run_dir, "blockMesh", ["blockMesh"])
    if not layout.step_done(run_dir, "fields"):
        shutil.rmtree(run_dir / "0", ignore_errors=True)
        shutil.copytree(run_dir / "0.orig", run_dir / "0")
        layout.mark_done(run_dir, "fields")
    runner.run_app(run_dir, "setAlphaField", ["setAlphaField"])
    if np_ > 1:
        runner.run_app(run_dir, "decomposePar", ["decomposePar", "-force"])
    print(f"[{label}] {info['cells']} cells, {np_} rank(s), {info['end_time']:g} s to simulate; "
          f"log: {run_dir / 'log.interFoam'}")
    limits = runner.Limits(max_courant=case.settings.run.divergence_courant,
                           max_body_speed=case.settings.run.divergence_body_speed)
    runner.run_solver(run_dir, [str(solver)], end_time=info["end_time"], np_=np_,
                      motion_csv=motion, limits=limits, label=label,
                      log_name="interFoam")
    layout.mark_done(run_dir, layout.FINISHED)
    return RunResult(run_dir, motion, info, resumed)
