"""Figures of a decay analysis (PNG, matplotlib's Agg canvas; no pyplot state).

One figure per record, four panels:

* the motion beside Cummins' model (:mod:`floatfoam.analysis.cummins`: its series, drawn about
  the record's equilibrium), the least-squares fit, any measured record, a damped reference
  curve when the case has a measured period (at its measured damping, else at the fit's, said
  so in its label), and the undamped linear theory
  x_eq + x₀ cos(2π (t − t₀)/T) from the release offset x₀ as a thin dotted line (no added
  mass, no damping: kept to show what the fluid's inertia changes);
* the amplitude envelope: |extrema| on a log scale with the fitted exponential A e^{−ζω_n s};
* period per cycle versus amplitude;
* damping ratio per cycle (and per half cycle) versus amplitude.

An extinction curve (:mod:`floatfoam.analysis.extinction`) has a figure of its own, two
panels: the decrement per half swing against its mean amplitude, and the equivalent damping
ratio against the amplitude.

All values are drawn in file units (m, deg). The PNG's ``Description`` holds the first panel's
legend, one entry a line: what the figure sets beside the record, for a reader without eyes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from floatfoam import dofs
from floatfoam.analysis.decay import DecayResult, log_decrement_damping
from floatfoam.analysis.extinction import ExtinctionCurve


@dataclass
class Overlay:
    """What to draw next to the record (file units; None: not drawn).

    theory_period : undamped period of the linear theory, s
    equilibrium : the theory's equilibrium level (else the fitted mean is used)
    release : release offset from equilibrium (else the first sample's offset)
    reference_period, reference_damping, reference_source : a measured reference
    measured_time, measured_offset, measured_label : a measured record (time from the release,
        offset from the equilibrium, file units), drawn as it was measured
    model_time, model_offset, model_label : Cummins' model's series (offset from its
        equilibrium, file units; :class:`~floatfoam.analysis.cummins.ModelFit`)
    model_period, model_damping : its damped period (s) and damping ratio, by the decay fit
    """

    theory_period: float | None = None
    equilibrium: float | None = None
    release: float | None = None
    reference_period: float | None = None
    reference_damping: float | None = None
    reference_source: str = ""
    measured_time: np.ndarray | None = None
    measured_offset: np.ndarray | None = None
    measured_label: str = ""
    model_time: np.ndarray | None = None
    model_offset: np.ndarray | None = None
    model_label: str = ""
    model_period: float | None = None
    model_damping: float | None = None


def free_decay_curve(time, t0: float, offset: float, period: float, zeta: float = 0.0):
    """Release from rest: x₀ e^{−ζω_n s} (cos ω_d s + ζω_n/ω_d sin ω_d s), s = t − t₀.

    ``period`` is the damped period T_d = 2π/ω_d; ζ = 0 gives the undamped cosine.
    """
    s = np.asarray(time, dtype=float) - t0
    omega_d = 2 * math.pi / period
    sigma = zeta * omega_d / math.sqrt(1 - zeta**2)
    return offset * np.exp(-sigma * s) * (np.cos(omega_d * s) + sigma / omega_d
                                           * np.sin(omega_d * s))


def _time_panel(ax, time, value, result: DecayResult, overlay: Overlay, scale, unit):
    fit = result.fit
    mean = fit.mean_level(time) * scale
    eq = overlay.equilibrium if overlay.equilibrium is not None else float(mean[0])
    offset = overlay.release if overlay.release is not None else float(value[0] * scale - eq)
    ax.plot(time, value * scale, color="C0", lw=1.6, label="record")
    fitted = time >= fit.t0  # a record analysed from --start is fitted from there on
    ax.plot(time[fitted], fit.evaluate(time[fitted]) * scale, color="C1", lw=1, ls="--",
            label=f"fit: T_d = {fit.damped_period()[0]:.4g} s, ζ = {fit.zeta:.3g}")
    if overlay.model_time is not None:
        shown = overlay.model_time <= time[-1]
        ax.plot(overlay.model_time[shown], eq + overlay.model_offset[shown], color="C3", lw=1.2,
                label=f"{overlay.model_label or 'model'}: T_d = {overlay.model_period:.4g} s, "
                      f"ζ = {overlay.model_damping:.3g}")
    if overlay.theory_period:
        ax.plot(time, eq + free_decay_curve(time, time[0], offset, overlay.theory_period),
                color="0.45", lw=0.7, ls=":",
                label=f"linear theory, no added mass, undamped: T = "
                      f"{overlay.theory_period:.4g} s")
    if overlay.reference_period:
        measured = overlay.reference_damping is not None
        zeta = overlay.reference_damping if measured else fit.zeta  # a period alone: the
        label = f"reference {overlay.reference_source}".strip()  # record's ζ, said so
        damping = f"ζ = {zeta:.3g}" if measured else f"ζ not measured (the fit's, {zeta:.3g})"
        ax.plot(time, eq + free_decay_curve(time, time[0], offset, overlay.reference_period,
                                            zeta),
                color="C2", lw=1, ls="-.",
                label=f"{label}: T = {overlay.reference_period:.4g} s, {damping}")
    if overlay.measured_time is not None:
        shown = (overlay.measured_time >= time[0]) & (overlay.measured_time <= time[-1])
        ax.plot(overlay.measured_time[shown], eq + overlay.measured_offset[shown],
                color="k", lw=0.9, alpha=0.8, label=overlay.measured_label or "measured")
    ax.axhline(eq, color="0.7", lw=0.8)
    if result.t_usable < result.t_last:
        ax.axvline(result.t_usable, color="0.7", lw=0.8, ls="--")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"motion ({unit})")
    ax.legend(fontsize=7, loc="upper right")


def _envelope_panel(ax, result: DecayResult, scale, unit):
    t = np.array([e[0] for e in result.extrema])
    a = np.array([e[1] for e in result.extrema]) * scale
    if t.size:
        ax.semilogy(t[a > 0], a[a > 0], "^", color="C0", label="maxima")
        ax.semilogy(t[a < 0], -a[a < 0], "v", color="C3", label="|minima|")
    grid = np.linspace(result.t_first, result.t_usable, 200)
    ax.semilogy(grid, result.fit.envelope(grid) * scale, color="C1", lw=1,
                label=f"fit A e^(−ζω_n t), ζ = {result.fit.zeta:.3g}")
    if result.threshold > 0:
        ax.axhline(result.threshold * scale, color="0.7", lw=0.8, ls=":",
                   label="noise threshold")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"amplitude ({unit})")
    ax.legend(fontsize=7)


def _band(ax, value, lo, hi, color, label):
    ax.axhline(value, color=color, lw=1, label=label)
    ax.axhspan(lo, hi, color=color, alpha=0.15, lw=0)


def _period_panel(ax, result: DecayResult, overlay: Overlay, scale, unit):
    ax.plot(result.crossing_amplitudes(1) * scale, result.periods(1), "o", color="C0",
            label="zero-up-crossing")
    ax.plot(result.crossing_amplitudes(-1) * scale, result.periods(-1), "s", color="C0",
            mfc="none", label="zero-down-crossing")
    ax.plot(result.cycle_decrements()[1] * scale, result.peak_periods(), "x", color="C3",
            label="peak to peak")
    period, half = result.fit.damped_period()
    _band(ax, period, period - half, period + half, "C1", "fit T_d ± 95 %")
    if overlay.model_period:
        ax.axhline(overlay.model_period, color="C3", label="Cummins' model")
    if overlay.theory_period:
        ax.axhline(overlay.theory_period, color="0.45", ls=":", label="linear theory")
    if overlay.reference_period:
        ax.axhline(overlay.reference_period, color="C2", ls="-.", label="reference")
    ax.set_xlabel(f"amplitude ({unit})")
    ax.set_ylabel("period (s)")
    ax.legend(fontsize=7)


def _damping_panel(ax, result: DecayResult, overlay: Overlay, scale, unit):
    deltas, amps = result.cycle_decrements()
    half, half_amps = result.half_cycle_decrements()
    ax.plot(amps * scale, log_decrement_damping(deltas), "o", color="C0", label="per cycle")
    ax.plot(half_amps * scale, log_decrement_damping(2 * half), ".", color="C0", alpha=0.5,
            label="per half cycle")
    zeta, hw = result.fit.damping_ratio()
    _band(ax, zeta, zeta - hw, zeta + hw, "C1", "fit ζ ± 95 %")
    if overlay.model_damping is not None:
        ax.axhline(overlay.model_damping, color="C3", label="Cummins' model")
    if overlay.reference_damping is not None:
        ax.axhline(overlay.reference_damping, color="C2", ls="-.", label="reference")
    ax.set_xlabel(f"mean amplitude ({unit})")
    ax.set_ylabel("damping ratio ζ")
    ax.legend(fontsize=7)


def _save(fig, path: str | Path, dpi: int = 110, **options) -> Path:
    """Write ``fig`` to ``path`` (its folder made when missing); returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi, **options)
    return path


def plot_decay(path: str | Path, time, value, result: DecayResult, *,
               overlay: Overlay | None = None, scale: float = 1.0, unit: str = "",
               title: str = "") -> Path:
    """Write the four-panel decay figure of one record (``value`` in code units) to ``path``."""
    overlay = overlay or Overlay()
    time, value = np.asarray(time, dtype=float), np.asarray(value, dtype=float)
    fig = Figure(figsize=(11, 7.5), layout="constrained")
    grid = fig.add_gridspec(2, 3)
    motion = fig.add_subplot(grid[0, :])
    _time_panel(motion, time, value, result, overlay, scale, unit)
    _envelope_panel(fig.add_subplot(grid[1, 0]), result, scale, unit)
    _period_panel(fig.add_subplot(grid[1, 1]), result, overlay, scale, unit)
    _damping_panel(fig.add_subplot(grid[1, 2]), result, overlay, scale, unit)
    if title:
        fig.suptitle(title)
    legend = "\n".join(motion.get_legend_handles_labels()[1])
    return _save(fig, path, metadata={"Description": legend})


def plot_turn(path: str | Path, time, angle, model=None, *, stable=None, unit: str = "deg",
              title: str = "", label: str = "CFD") -> Path:
    """Write the figure of a body that turns over to ``path``: its attitude ``angle`` (file
    units) against ``time``, beside ``model`` (time, angle: the nonlinear inviscid model) and
    the GZ curve's ``stable`` attitudes (horizontal lines)."""
    fig = Figure(figsize=(9, 4.5), layout="constrained")
    ax = fig.add_subplot()
    ax.plot(time, angle, color="C0", lw=1.6, label=label)
    if model is not None:
        ax.plot(model[0], model[1], color="C1", lw=1.0, ls="--",
                label="nonlinear inviscid model (exact GZ, no added inertia, no damping)")
    for k, value in enumerate(stable or ()):
        ax.axhline(value, color="0.4", lw=0.8, ls=":",
                   label="stable attitudes of the GZ curve" if k == 0 else None)
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"attitude ({unit})")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    if title:
        ax.set_title(title)
    return _save(fig, path)


def plot_extinction(path: str | Path, curve: ExtinctionCurve, *, scale: float = 1.0,
                    unit: str = "", title: str = "", references=()) -> Path:
    """Write the extinction figure of one record to ``path`` (file units: ``scale`` × code).

    Left: the decrement Δφ of each half swing against its mean amplitude φ_m, with the fit
    a φ_m + b φ_m² (+ c φ_m³) and its 95 % band. Right: the equivalent damping ratio against
    the amplitude: Δφ/(π φ_m) per half swing, ζ_i per cycle (quasi-linear), the fit's
    ζ_eq = (a + b φ + c φ²)/π with its band and the quasi-linear line ζ1 + ζ2 φ, and beside
    them ``references``: (label, amplitudes in code units, ζ, matplotlib format) each, e.g.
    Ikeda's components and potential flow's.
    """
    grid = np.linspace(0.0, 1.05 * float(np.max(curve.start)), 200)
    fitted, half = curve.fitted_decrement(grid)
    terms = "a φ_m + b φ_m² + c φ_m³" if curve.cubic else "a φ_m + b φ_m²"
    fig = Figure(figsize=(11, 4.5), layout="constrained")
    left, right = fig.subplots(1, 2)
    left.plot(curve.mean_amplitude * scale, curve.decrement * scale, "o", color="C0",
              label="half swings")
    left.plot(grid * scale, fitted * scale, color="C1", label=f"fit {terms}")
    left.fill_between(grid * scale, (fitted - half) * scale, (fitted + half) * scale,
                      color="C1", alpha=0.15, lw=0, label="95 % interval")
    left.set_xlabel(f"mean amplitude φ_m ({unit})")
    left.set_ylabel(f"decrement per half swing Δφ ({unit})")
    left.set_xlim(left=0.0)
    left.legend(fontsize=7)
    zeta = curve.damping_ratio_equivalent(grid)
    zeta_half = curve.damping_ratio_equivalent_ci95(grid)
    right.plot(curve.mean_amplitude * scale, curve.half_swing_damping(), "o", color="C0",
               label="Δφ / (π φ_m) per half swing")
    right.plot(curve.cycle_amplitude * scale, curve.cycle_damping, "s", color="C3", mfc="none",
               label="ln(φ_i / φ_i+2) / 2π per cycle")
    right.plot(grid * scale, zeta, color="C1", label="ζ_eq of the fit")
    right.fill_between(grid * scale, zeta - zeta_half, zeta + zeta_half, color="C1", alpha=0.15,
                       lw=0)
    zeta1, zeta2 = curve.quasi_linear.coefficients
    right.plot(grid * scale, zeta1 + zeta2 * grid, color="C3", ls="--",
               label="quasi-linear ζ1 + ζ2 φ")
    for label, amplitude, value, style in references:
        right.plot(np.asarray(amplitude) * scale, value, style, label=label)
    right.set_xlabel(f"amplitude ({unit})")
    right.set_ylabel("equivalent damping ratio ζ_eq")
    right.set_xlim(left=0.0)
    right.legend(fontsize=7)
    if title:
        fig.suptitle(title)
    return _save(fig, path)


def plot_convergence(study: dict, quantities, path: str | Path) -> Path:
    """Each quantity of a grid study (``floatfoam.analysis.validation``) against the cell size
    h/h_fine, one row per DoF: the three levels with the fine one's ± U_num, the level run with
    its time step halved (at that level's h), the coarse one with its mesh motion varied, at
    h = 0 the Richardson-extrapolated value, and the case's measurement (a line and
    its uncertainty's band) where its ``[reference]`` has one. One legend for the figure, below
    the panels, the measurements' sources its title: a legend in each panel, with a source
    a hundred characters long, squeezed the panels to slivers."""
    entries = list(study["dofs"].items()) or [("—", {"runs": {}, "quantities": {}})]
    columns = min(3, len(quantities))
    per_dof = -(-len(quantities) // columns)  # rows of panels per DoF
    fig = Figure(figsize=(4 * columns, 3.2 * per_dof * len(entries) + 0.8),
                 layout="constrained")
    axes = fig.subplots(per_dof * len(entries), columns, squeeze=False).ravel()
    sources = []
    for i, (dof, entry) in enumerate(entries):
        panels = axes[i * per_dof * columns:(i + 1) * per_dof * columns]
        for ax, (key, label, unit) in zip(panels, quantities, strict=False):
            if unit == "m or rad":  # a length or an angle, in code units
                unit = "rad" if dof in dofs.NAMES and dofs.dof(dof).is_angle else "m"
            source = _convergence_panel(ax, dof, entry, key, label, unit,
                                        (study.get("mesh_motion") or {}).get("variant"))
            if source and source not in sources:
                sources.append(source)
        for ax in panels[len(quantities):]:
            ax.set_visible(False)
    legend = {}
    for ax in axes:
        for handle, text in zip(*ax.get_legend_handles_labels(), strict=True):
            legend.setdefault(text, handle)
    if legend:
        fig.legend(legend.values(), legend.keys(), loc="outside lower center",
                   ncols=min(len(legend), 6), fontsize=8, title_fontsize=7,
                   title="measured: " + "; ".join(sources) if sources else None)
    fig.suptitle(f"{study['case']}: grid and time-step convergence")
    return _save(fig, path, dpi=100)


def _convergence_panel(ax, dof, entry, key, label, unit, variant=None) -> str | None:
    """One quantity's panel; returns its measurement's source (None without one).
    ``variant``: what the mesh-motion run varied, in words (a study written before it was
    recorded scaled the distances)."""
    runs = entry["runs"]
    fine_cells = (runs.get("fine") or {}).get("cells")
    points = [((fine_cells / run["cells"]) ** (1 / run["dimension"]), run[key],
               run.get("divisor", 1), run.get("morphing", 1.0), name)
              for name, run in runs.items()
              if run.get(key) is not None and run.get("cells") and fine_cells]
    levels = sorted((h, v) for h, v, k, f, _ in points if k == 1 and f == 1)
    if levels:
        ax.plot(*zip(*levels, strict=True), "o-", color="C0", label="levels")
    for h, v, k, f, name in points:
        level = name.split("-")[0]
        if k != 1:
            ax.plot(h, v, "s", color="C3", mfc="none", label=f"{level}, time step / {k}")
        elif f != 1:
            ax.plot(h, v, "^", color="C2", mfc="none",
                    label=f"{level}, {variant or f'morphing distances × {f:g}'}")
    q = entry["quantities"].get(key, {})
    grid = q.get("grid", {})
    if q.get("uncertainty") is not None and "values" in grid:
        fine = grid["values"][0]
        ax.errorbar([1.0], [fine], yerr=abs(fine) * q["uncertainty"], fmt="none", color="C0",
                    capsize=4, label="fine ± U_num")
    kind = grid.get("kind") or grid.get("note") or ""
    if grid.get("extrapolated") is not None:
        ax.plot([0.0], [grid["extrapolated"]], "D", color="C1", label="extrapolated (h = 0)")
        kind = ", ".join(filter(None, [kind, f"p = {grid['order']:.2g}"]))
    measured = entry.get("reference", {}).get(key)
    source = None
    if measured is not None:
        value, uncertainty, source = measured
        ax.axhline(value, color="k", lw=1, label="measured")
        if uncertainty:
            ax.axhspan(value - uncertainty, value + uncertainty, color="0.85", zorder=0,
                       label="its uncertainty")
    ax.set_title(f"{dof}: {label}\n{kind}", fontsize=9)
    ax.set_xlabel("h / h_fine")
    ax.set_ylabel(label.split(" (")[0] + (f" ({unit})" if unit else ""))
    ax.set_xlim(left=-0.1)
    return source or None
