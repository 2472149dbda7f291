"""A study's runs, start to end: what ``floatfoam validate`` does on this machine, as a library
call (:func:`run_study`). It sits above the run (:mod:`floatfoam.foam`) and the analysis
(:mod:`floatfoam.analysis.validation`): each is used as it is, neither imports this."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from floatfoam import layout
from floatfoam.errors import InputError


@dataclass
class StudyOutcome:
    """What :func:`run_study` gives: the study (``validate_case``'s dict: its ``runs``, each
    quantity's GCI and U_num) and the names of the runs that failed (the study holds the
    others)."""

    study: dict
    failed: list[str] = field(default_factory=list)


def _stderr(line: str) -> None:
    print(line, file=sys.stderr)


def check_study(case, np_: int, runs: list[tuple[str, int, float]], build: Path) -> list:
    """Every run of a study (``runs``: :func:`floatfoam.analysis.validation.plan`'s (level,
    time-step divisor, morphing factor)) checked as :func:`floatfoam.foam.driver.check_run`
    checks one, before the first starts or is submitted; returns their plans
    (:class:`floatfoam.plan.runplan.RunPlan`). Raises InputError; writes nothing."""
    from floatfoam.foam.driver import check_plan, check_ranks
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.plan.runplan import resolve

    check_ranks(np_, None)
    eq = equilibrium(case)
    plans = [resolve(case, level, np_, build_dir=build, equilibrium=eq, divisor=divisor,
                     morphing=factor) for level, divisor, factor in runs]
    for plan in plans:
        check_plan(plan)
    return plans


def run_study(case, np_: int = 1, *, time_level: str = "medium",
              morphing: float | None | Literal["auto"] = "auto", build: Path | None = None,
              run: bool = True, say: Callable[[str], None] = _stderr) -> StudyOutcome:
    """The grid, time-step and mesh-motion study of ``case`` (a :class:`floatfoam.case.Case`)
    on ``np_`` MPI ranks: every run of :func:`floatfoam.analysis.validation.plan` checked
    before the first starts, then each run (a finished one reused, an interrupted one
    resumed), then the study of what finished (``validate_case``). ``morphing``: the mesh
    motion's run's factor, None for none, "auto" as ``floatfoam validate`` takes it (that of
    the study already written when its run is still finished, else 1.5:
    :func:`floatfoam.analysis.validation.study_morphing`). ``run`` False analyses finished
    runs only. A failed run is named in ``failed`` and the others still run; RunLockedError
    (another run holds a run folder) and the interrupts propagate. ``say`` gets the progress lines.

    InputError before any run when the inputs are bad, or when no run has finished and none
    failed (every run failed: an empty study and the failures named)."""
    from floatfoam.analysis.validation import plan, study_morphing, validate_case
    from floatfoam.foam.driver import check_ranks, run_plan
    from floatfoam.foam.runner import RunError

    check_ranks(np_, None)
    build = build or layout.build_dir()
    if morphing == "auto":
        morphing = study_morphing(case.name, build)
    runs = plan(time_level, morphing)
    failed: list[str] = []
    if run:
        plans = check_study(case, np_, runs, build)
        names = [item.run_dir.name for item in plans]
        say(f"[validate {case.name}] {len(runs)} runs on {np_} rank(s): {', '.join(names)} "
            "(finished ones are reused, interrupted ones resume)")
        for i, (item, name) in enumerate(zip(plans, names, strict=True), 1):
            start = time.monotonic()
            say(f"[validate {case.name}] run {i}/{len(runs)}: {name}")
            try:
                done = run_plan(item)
            except RunError as err:
                say(f"floatfoam validate: run {name} failed: {err}")
                failed.append(name)
                continue
            what = "already finished" if done.already_finished else \
                f"{time.monotonic() - start:.0f} s wall"
            say(f"[validate {case.name}] {name}: {done.info.cells} cells, {what}")
    study = validate_case(case, build, time_level, morphing)
    if not study["runs"] and not failed:
        raise InputError(f"case {case.name!r} has no finished run under {build}; valid: run "
                         "`floatfoam validate` without --no-run first")
    return StudyOutcome(study, failed)
