"""The report's figures of a case (:mod:`floatfoam.analysis.report`): each CFD record's decay
beside Cummins' model and any measurement, a roll record's extinction curve beside Ikeda's
components and potential flow (:func:`record_figures`), the attitude of a body that turns over
beside the nonlinear inviscid model (:func:`turn_figures`), and the righting arm GZ and the
radiation coefficients (:func:`case_figures`)."""

from __future__ import annotations

from pathlib import Path

from floatfoam.analysis.compare import Comparison
from floatfoam.analysis.document import Document
from floatfoam.analysis.overlay import decay_overlay
from floatfoam.analysis.plots import plot_decay, plot_turn
from floatfoam.analysis.sources import Sources
from floatfoam.errors import InputError
from floatfoam.motion import file_unit


def record_figures(case, theory, comparison: Comparison, out_dir: Path,
                   sources: Sources | None = None) -> list[tuple[str, str]]:
    """Each CFD record's decay figure, and a roll record's extinction curve: (file, caption)
    pairs under ``out_dir``."""
    images = []
    for run in comparison.analyses:
        scale, unit = file_unit(run.dof)
        name = f"{case.name}/{run.level}_{run.dof}.png"
        model = comparison.models.get(run.dof)
        plot_decay(out_dir / name, run.time, run.value, run.result,
                   overlay=decay_overlay(case, theory, run.dof, model), scale=scale, unit=unit,
                   title=f"{case.name}, {run.level} mesh: {run.dof} decay")
        beside = f" beside {model.label}" if model else ""
        images.append((name, f"{case.name} {run.level} {run.dof} decay{beside}"))
        if run.dof == "roll":
            images += extinction_plot(case, run, out_dir, scale, unit, sources)
    return images


def turn_figures(case, theory, runs, out_dir: Path) -> list[tuple[str, str]]:
    """A body released in a DoF the theory says capsizes (roll or pitch): each CFD record's
    attitude against time (``runs``: (level, motion.csv) pairs) beside the nonlinear inviscid
    model (exact GZ, no added inertia, no damping: `floatfoam decay-model CASE --model
    nonlinear`), whose record a decay fit has no period for. (file, caption) pairs under
    ``out_dir``."""
    from floatfoam import dofs
    from floatfoam.motion import read_motion
    from floatfoam.potential.models import decay_series

    turning = [d.name for d in dofs.released(case.release)
               if d.name in theory.dofs and theory.dofs[d.name].verdict == "capsizes"]
    images = []
    for dof in turning:
        column, (_, unit) = dofs.dof(dof).column, file_unit(dof)
        for level, path in runs:
            motion = read_motion(path)
            try:
                model = decay_series(case, "nonlinear", duration=float(motion["time"][-1]))
                beside = (model["time"], model[column])
            except (InputError, ValueError, RuntimeError):
                beside = None
            name = f"{case.name}/{level}_{dof}_turn.png"
            plot_turn(out_dir / name, motion["time"], motion[column], beside, unit=unit,
                      title=f"{case.name}, {level} mesh: {dof} (capsizes)")
            images.append((name, f"{case.name} {level}: {dof} of a body that turns over, "
                                 "beside the nonlinear inviscid model"))
    return images


def extinction_plot(case, run, out_dir: Path, scale: float, unit: str,
                     sources: Sources | None = None) -> list:
    """The roll record's extinction curve (:mod:`floatfoam.analysis.extinction`) beside Ikeda's
    components and potential flow's wave damping for a 2D section (:func:`_ikeda_lines`), or
    nothing when the record holds too few half swings for its fit."""
    from floatfoam.analysis.extinction import extinction_curve
    from floatfoam.analysis.plots import plot_extinction

    try:
        curve = extinction_curve(run.result, name=f"{case.name} {run.level}")
    except InputError:
        return []
    lines = _ikeda_lines(case, sources, float(max(curve.start)))
    name = f"{case.name}/{run.level}_{run.dof}_extinction.png"
    plot_extinction(out_dir / name, curve, scale=scale, unit=unit, references=lines,
                    title=f"{case.name}, {run.level} mesh: {run.dof} extinction curve")
    beside = "; beside Ikeda's components and potential flow" if lines else ""
    return [(name, f"{case.name} {run.level} {run.dof} extinction curve: decrement per half "
                   f"swing and equivalent damping ratio against amplitude{beside}")]


def _ikeda_lines(case, sources: Sources | None, largest: float) -> list:
    """ζ against amplitude (rad) of Ikeda's total (friction + eddy + wave, about a fixed axis
    through G) and of potential flow's wave damping, fixed axis and sway free, for a 2D
    section whose potential flow the report has; none otherwise."""
    if sources is None or sources.potential is None or not case.body.is_section:
        return []
    import numpy as np

    from floatfoam.damping.ikeda import roll_damping
    from floatfoam.hydrostatics.theory import equilibrium

    try:
        potential, eq = sources.potential(case), equilibrium(case)
        degrees = np.linspace(0.25, min(45.0, np.degrees(largest) * 1.05), 40)
        results = [roll_damping(case, eq, potential, float(a)) for a in degrees]
    except InputError:
        return []
    angle = np.radians(degrees)
    lines = [("Ikeda: friction + eddy + wave (fixed axis)", angle,
              [r.zeta(r.total) for r in results], "k-."),
             ("potential flow: wave (fixed axis)", angle, [r.zeta(r.wave) for r in results],
              "k:")]
    if results[0].wave_zeta_sway_free is not None:
        lines.append(("potential flow: wave (sway free)", angle,
                      [results[0].wave_zeta_sway_free] * len(angle), "C2:"))
    return lines


def case_figures(doc: Document, case, sources: Sources, out_dir: Path) -> None:
    """The righting arm GZ(φ) of a case released heeled (``sources.gz``, as ``floatfoam gz``:
    to 90° by 1°) and the radiation coefficients A(ω), B(ω) of its potential flow
    (``sources.coefficients``, as ``floatfoam potential --plot``); a line saying why where
    one cannot be drawn."""
    images = []
    heeled = float((getattr(case, "release", None) or {}).get("heel", 0.0) or 0.0) != 0.0
    if sources.gz is not None and heeled:
        from floatfoam.hydrostatics.gz import plot_gz

        try:
            plot_gz(sources.gz(case), out_dir / case.name / "gz.png",
                    title=f"{case.name}: righting arm")
            images.append((f"{case.name}/gz.png", f"{case.name}: righting arm GZ against heel"))
        except (InputError, ValueError, RuntimeError) as err:
            doc.paragraph(f"GZ curve: not drawn ({err})", note=True)
    if sources.coefficients is not None:
        from floatfoam.potential.plot import plot_coefficients

        try:
            coefficients = sources.coefficients(case)
            summary = sources.potential(case) if sources.potential else None
        except (ImportError, InputError, NotImplementedError, RuntimeError) as err:
            doc.paragraph(f"A(ω), B(ω): not drawn ({str(err).splitlines()[0]})", note=True)
        else:
            plot_coefficients(coefficients, out_dir / case.name / "potential.png",
                              summary=summary, title=f"{case.name}: radiation coefficients")
            images.append((f"{case.name}/potential.png", f"{case.name}: added mass A(ω) and "
                                                         "radiation damping B(ω)"))
    if images:
        doc.heading("Stability and potential flow", 3)
        for src, alt in images:
            doc.image(src, alt)
