"""Free-decay analysis of one motion series (heave, roll or pitch): periods and damping.

A body released from an offset oscillates about its equilibrium with a decaying amplitude. For
a linear oscillator ẍ + 2ζω_n ẋ + ω_n² x = 0 the successive extrema of the same sign satisfy

    δ = ln(x_n / x_{n+1}) = ζ ω_n T_d = 2πζ / √(1 − ζ²),  i.e.  ζ = δ / √(4π² + δ²),

with T_d = 2π / (ω_n √(1 − ζ²)) the damped period (Journée & Massie 2001, *Offshore
Hydromechanics*, ch. 6, free decay tests). This module gives both the per-cycle view (periods
between interpolated zero crossings and between polynomial-refined extrema, logarithmic
decrements per half cycle and per cycle) and a least-squares fit of the whole record with 95 %
confidence intervals (:mod:`floatfoam.analysis.decay_fit`). The fit is the headline estimate: on a
short, strongly damped record (3–4 cycles) it uses every sample, while the per-cycle values
show how period and damping change with amplitude.

Units are those of the series (m, or radians for angles in code); periods in s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatfoam.analysis.decay_fit import DecayFit, fit_linear_decay, fit_quadratic_decay
from floatfoam.errors import InputError

MIN_SAMPLES = 20
MIN_CYCLES = 1.5
NOISE_FACTOR = 3.0  # an oscillation counts as signal above 3× the noise rms


def validate_series(time, value, *, name: str = "value") -> tuple[np.ndarray, np.ndarray]:
    """Check a record: 1-D, same length, ≥ MIN_SAMPLES samples, finite, time increasing.

    NaN and inf are refused (never dropped): the error names the first bad sample.
    """
    t = np.asarray(time, dtype=float)
    x = np.asarray(value, dtype=float)
    if t.ndim != 1 or x.shape != t.shape:
        raise InputError(f"{name}: shape {x.shape} does not match time {t.shape}; "
                         "expected two 1-D arrays of equal length")
    if t.size < MIN_SAMPLES:
        raise InputError(f"{name}: {t.size} samples; need at least {MIN_SAMPLES} for a decay "
                         "analysis")
    for label, array in (("time", t), (name, x)):
        bad = np.flatnonzero(~np.isfinite(array))
        if bad.size:
            i = int(bad[0])
            raise InputError(f"{label}: non-finite value {array[i]} at sample {i} "
                             f"({bad.size} in all); NaN and inf are refused, not dropped")
    steps = np.flatnonzero(np.diff(t) <= 0)
    if steps.size:
        i = int(steps[0]) + 1
        raise InputError(f"time: not strictly increasing at sample {i} "
                         f"(t = {t[i]:g} after {t[i - 1]:g})")
    return t, x


def noise_rms(time, value) -> float:
    """Robust rms of the white noise on a densely sampled record.

    Each sample is compared with the linear interpolation of its neighbours (valid for uneven
    steps); for white noise of rms σ that difference has rms σ √(1 + w² + (1 − w)²). The
    median absolute value (× 1.4826) makes the estimate insensitive to the smooth motion, as
    long as the record is sampled densely (curvature adds ~ A (ω Δt)² / 8).
    """
    t, x = np.asarray(time, dtype=float), np.asarray(value, dtype=float)
    left, right = t[1:-1] - t[:-2], t[2:] - t[1:-1]
    w = right / (left + right)
    diff = x[1:-1] - (w * x[:-2] + (1 - w) * x[2:])
    return float(1.4826 * np.median(np.abs(diff) / np.sqrt(1 + w**2 + (1 - w) ** 2)))


def tail_equilibrium(time, value, *, fraction: float = 0.25) -> float:
    """Mean of the last ``fraction`` of the record (by time): the settled level.

    Biased by the remaining oscillation when the record is cut short; the fit of
    :func:`analyse_decay` estimates x_eq without that bias.
    """
    t, x = np.asarray(time, dtype=float), np.asarray(value, dtype=float)
    tail = t >= t[-1] - fraction * (t[-1] - t[0])
    return float(np.mean(x[tail]))


def frequency_guess(time, value) -> float:
    """Angular frequency of the spectral peak of the detrended record, rad/s (a fit seed)."""
    t, x = np.asarray(time, dtype=float), np.asarray(value, dtype=float)
    n = min(t.size, 1 << 14)
    grid = np.linspace(t[0], t[-1], n)
    uniform = np.interp(grid, t, x)
    uniform = uniform - np.polyval(np.polyfit(grid - grid[0], uniform, 1), grid - grid[0])
    spectrum = np.abs(np.fft.rfft(uniform, 8 * n))
    freq = np.fft.rfftfreq(8 * n, grid[1] - grid[0])
    spectrum[freq < 1.0 / (t[-1] - t[0])] = 0.0  # at least one cycle in the record
    if not spectrum.max() > 0:
        raise InputError("value: the record has no oscillation (constant or a straight line); "
                         "nothing to analyse")
    return 2 * math.pi * float(freq[np.argmax(spectrum)])


def find_crossings(time, y, threshold: float) -> tuple[np.ndarray, np.ndarray]:
    """Zero crossings of ``y`` with hysteresis: times and directions (+1 up, −1 down).

    The sign only changes once ``y`` has passed beyond ±threshold, so noise near zero gives one
    crossing, not a burst. The crossing time is the root of a straight line fitted through
    the samples between the last one beyond the band and the first one beyond it on the other
    side (two samples: linear interpolation).
    """
    t, y = np.asarray(time, dtype=float), np.asarray(y, dtype=float)
    beyond = np.flatnonzero(np.abs(y) > threshold)
    sign = np.sign(y[beyond])
    changes = np.flatnonzero(sign[1:] != sign[:-1])
    times = []
    for k in changes:
        i0, i1 = beyond[k], beyond[k + 1]
        ts, ys = t[i0:i1 + 1] - t[i0], y[i0:i1 + 1]
        slope, intercept = np.polyfit(ts, ys, 1)
        root = -intercept / slope if slope != 0 else 0.5 * ts[-1]
        times.append(t[i0] + float(np.clip(root, 0.0, ts[-1])))
    return np.array(times), sign[changes + 1].astype(int)


def _turning_point(t, y, center, lo, hi, half_window, degree):
    """Turning point of a least-squares polynomial of ``degree`` through the samples of
    [lo, hi] (indices) within ±half_window of time ``center``: (time, value) or None."""
    near = np.flatnonzero((np.abs(t - center) <= half_window) & (t >= t[lo]) & (t <= t[hi]))
    if near.size < degree + 3:
        return None
    tau = t[near] - center
    width = float(np.max(np.abs(tau)))
    poly = np.polynomial.Polynomial.fit(tau, y[near], degree, window=[-1, 1],
                                        domain=[-width, width])
    slope, curvature = poly.deriv(1), poly.deriv(2)
    x = 0.0
    for _ in range(20):
        if curvature(x) == 0 or abs(x) > width:
            return None
        step = slope(x) / curvature(x)
        x -= step
        if abs(step) < 1e-12 * width:
            break
    sign = np.sign(np.mean(y[near]))
    if curvature(x) * sign >= 0 or abs(x) > width:  # not a turning point of the right kind
        return None
    return center + x, float(poly(x))


def _refined_extremum(t, y, i, lo, hi, half_window):
    """Turning point near sample ``i``: a parabola through the samples within ±half_window
    locates it; a quartic over the same width re-centred there refines it.

    A parabola over a finite window of a cosine misplaces the peak height by O(w⁴) (0.1 % at
    ±T/12); the quartic's error is O(w⁶). On sparse samples (< 7 in the window) the parabola
    through the three nearest samples is used. Returns (time, value) or None.
    """
    coarse = _turning_point(t, y, t[i], lo, hi, half_window, 2)
    if coarse is None:
        three = np.arange(max(lo, i - 1), min(hi, i + 1) + 1)
        return _three_point(t[three], y[three]) if three.size == 3 else None
    fine = _turning_point(t, y, coarse[0], lo, hi, half_window, 4)
    return fine if fine is not None and abs(fine[0] - coarse[0]) < half_window / 2 else coarse


def _three_point(ts, ys):
    """Vertex of the parabola through three samples (uneven spacing allowed)."""
    c2, c1, c0 = np.polyfit(ts - ts[1], ys, 2)
    if c2 * ys[1] >= 0:
        return None
    x = -c1 / (2 * c2)
    return ts[1] + x, c0 - c1**2 / (4 * c2)


def find_extrema(time, y, crossings, period: float, threshold: float) -> list[tuple]:
    """One extremum per stretch between crossings: (time, value, stretch index).

    The largest |y| sample of each stretch is refined with a least-squares polynomial over
    ±T/12 (:func:`_refined_extremum`). A stretch at either end of the record only yields an
    extremum when that turning point lies inside the record (a release from rest counts, its
    first sample being the turning point; a record that starts or stops mid-swing does not).
    """
    t, y = np.asarray(time, dtype=float), np.asarray(y, dtype=float)
    bounds = [t[0] - 1.0, *crossings, t[-1] + 1.0]
    slack = period / 40
    found = []
    for k in range(len(bounds) - 1):
        inside = np.flatnonzero((t > bounds[k]) & (t < bounds[k + 1]))
        if inside.size == 0:
            continue
        i = int(inside[np.argmax(np.abs(y[inside]))])
        vertex = _refined_extremum(t, y, i, inside[0], inside[-1], period / 12)
        if vertex is None or not (t[0] - slack <= vertex[0] <= t[-1]):
            continue
        t_v, value = max(float(vertex[0]), t[0]), float(vertex[1])
        if i == 0:  # release from rest: the first sample is the turning point itself
            t_v, value = float(t[0]), float(y[0])
        if abs(value) > threshold and math.copysign(1, value) == np.sign(y[i]):
            found.append((t_v, value, k))
    return found


def log_decrement_damping(delta):
    """ζ = δ / √(4π² + δ²) from a logarithmic decrement δ per full cycle."""
    delta = np.asarray(delta, dtype=float)
    return delta / np.sqrt(4 * math.pi**2 + delta**2)


def _pairs(extrema, step):
    """(earlier, later) extrema ``step`` stretches apart (1: half cycle, 2: full cycle)."""
    by_stretch = {k: (t, a) for t, a, k in extrema}
    return [(by_stretch[k], by_stretch[k + step]) for k in by_stretch if k + step in by_stretch]


@dataclass
class DecayResult:
    """Per-cycle values and the least-squares fit of one decay record (code units)."""

    fit: DecayFit
    equilibrium_source: str
    t_first: float
    t_last: float
    t_usable: float
    noise_rms: float
    threshold: float
    crossings: np.ndarray
    directions: np.ndarray
    extrema: list

    @property
    def n_cycles(self) -> float:
        """Usable cycles: the record's duration above the noise, in damped periods."""
        return (self.t_usable - self.t_first) / self.fit.damped_period()[0]

    def periods(self, direction: int = 1) -> np.ndarray:
        """Periods between successive zero-up (direction +1) or zero-down (−1) crossings."""
        return np.diff(self.crossings[self.directions == direction])

    def crossing_amplitudes(self, direction: int = 1) -> np.ndarray:
        """Mean |extremum| within each period of :meth:`periods` (same ``direction``)."""
        ups = self.crossings[self.directions == direction]
        return np.array([np.mean([abs(a) for t, a, _ in self.extrema if lo < t < hi] or [np.nan])
                         for lo, hi in zip(ups[:-1], ups[1:], strict=True)])

    def peak_periods(self) -> np.ndarray:
        """Periods between successive extrema of the same sign (peak to peak)."""
        return np.array([b[0] - a[0] for a, b in _pairs(self.extrema, 2)])

    def half_cycle_decrements(self) -> tuple[np.ndarray, np.ndarray]:
        """ln(|x_n| / |x_{n+½}|) per half cycle (≈ δ/2) and the mean amplitude of each."""
        pairs = _pairs(self.extrema, 1)
        return (np.array([math.log(abs(a[1]) / abs(b[1])) for a, b in pairs]),
                np.array([(abs(a[1]) + abs(b[1])) / 2 for a, b in pairs]))

    def cycle_decrements(self) -> tuple[np.ndarray, np.ndarray]:
        """δ = ln(x_n / x_{n+1}) per cycle (same-sign extrema) and the mean amplitude of each."""
        pairs = _pairs(self.extrema, 2)
        return (np.array([math.log(a[1] / b[1]) for a, b in pairs]),
                np.array([(abs(a[1]) + abs(b[1])) / 2 for a, b in pairs]))

    def summary(self) -> dict:
        """Headline numbers (from the fit), in code units; CIs as [lo, hi]."""
        period, period_hw = self.fit.damped_period()
        natural, natural_hw = self.fit.natural_period()
        zeta, zeta_hw = self.fit.damping_ratio()
        return {"period_mean": period, "period_ci95": [period - period_hw, period + period_hw],
                "natural_period": natural,
                "natural_period_ci95": [natural - natural_hw, natural + natural_hw],
                "damping_ratio": zeta, "damping_ratio_ci95": [zeta - zeta_hw, zeta + zeta_hw],
                "n_cycles": self.n_cycles}


def _resolve_equilibrium(t, x, equilibrium):
    if equilibrium is None:
        return None, "fit"
    if isinstance(equilibrium, str):
        if equilibrium != "tail":
            raise InputError(f"equilibrium = {equilibrium!r}; valid: a number, 'tail' or None")
        return tail_equilibrium(t, x), "tail"
    if not math.isfinite(float(equilibrium)):
        raise InputError(f"equilibrium = {equilibrium}; must be a finite number")
    return float(equilibrium), "given"


def _check_signal(fit: DecayFit, t, units) -> float:
    """Refuse an oscillation buried in the noise; return the end of the usable record."""
    scale, unit = units[0], f" {units[1]}".rstrip()
    amplitude = fit.initial_amplitude()
    decay = fit.zeta * fit.omega_n
    peak = amplitude * max(1.0, math.exp(-decay * (t[-1] - t[0])))
    noise = NOISE_FACTOR * fit.residual_rms
    if not peak > noise:
        raise InputError(f"amplitude: fitted oscillation {peak * scale:.3g}{unit} is below "
                         f"{NOISE_FACTOR:g}× the residual rms {fit.residual_rms * scale:.3g}"
                         f"{unit}; too little signal for a decay analysis")
    if decay <= 0 or noise == 0:
        return float(t[-1])
    return float(min(t[-1], t[0] + math.log(amplitude / noise) / decay))


def analyse_decay(time, value, *, equilibrium: float | str | None = None, drift: bool = False,
                  quadratic: bool = False, t_start: float | None = None,
                  units: tuple[float, str] = (1.0, ""), name: str = "value") -> DecayResult:
    """Periods and damping of a free-decay record.

    Parameters
    ----------
    time, value : the record (s; m or rad). Uneven steps are fine; NaN/inf are refused.
    equilibrium : the level the motion decays to: None fits it (seeded from the whole
        record), ``"tail"`` fixes it at :func:`tail_equilibrium`, a number fixes it (e.g. the
        theory's equilibrium).
    drift : fit a linear drift of the mean level as well.
    quadratic : fit ÿ + 2ζω_n ẏ + c_q|ẏ|ẏ + ω_n² y = 0 instead of the linear model.
    t_start : ignore the record before this time (e.g. a release transient).
    units : (scale, name) from code units to the units used in error messages.
    name : what the record is called in error messages (e.g. the CSV column).

    Raises
    ------
    InputError
        bad samples, fewer than MIN_CYCLES usable cycles, or an amplitude below the noise.
    """
    t, x = validate_series(time, value, name=name)
    if t_start is not None:
        keep = t >= t_start
        t, x = validate_series(t[keep], x[keep], name=f"{name} after t_start = {t_start:g}")
    fixed, source = _resolve_equilibrium(t, x, equilibrium)
    fit = fit_linear_decay(t, x, frequency_guess(t, x), equilibrium=fixed, drift=drift)
    if quadratic:
        fit = fit_quadratic_decay(t, x, fit)
    t_usable = _check_signal(fit, t, units)
    white = noise_rms(t, x)
    threshold = NOISE_FACTOR * min(white, fit.residual_rms)
    window = t <= t_usable
    y = x - fit.mean_level(t)
    crossings, directions = find_crossings(t[window], y[window], threshold)
    period = fit.damped_period()[0]
    n_cycles = (t_usable - t[0]) / period
    if n_cycles < MIN_CYCLES or len(crossings) < 2:
        raise InputError(f"record: {n_cycles:.3g} usable cycles ({len(crossings)} zero crossings) "
                         f"above the noise between t = {t[0]:g} and {t_usable:.4g} s; need at "
                         f"least {MIN_CYCLES:g} (record too short or too noisy; a drifting mean "
                         "needs drift=True, --drift)")
    extrema = find_extrema(t[window], y[window], crossings, period, threshold)
    return DecayResult(fit, source, float(t[0]), float(t[-1]), t_usable, white, threshold,
                       crossings, directions, extrema)


def _floats(values, scale: float = 1.0) -> list[float]:
    return [float(v) * scale for v in np.atleast_1d(values)]


def decay_dict(result: DecayResult, *, scale: float = 1.0, unit: str = "",
               dof: str | None = None) -> dict:
    """JSON-ready summary; amplitudes in file units (``scale`` × code units, e.g. 180/π → deg).

    Keys: ``periods`` (zero-up-crossing period per cycle, s), ``periods_zero_down``,
    ``periods_peak_to_peak``, ``period_amplitudes``, ``period_mean`` (the damped period of the
    fit: the record's best estimate), ``period_ci95`` ([lo, hi], 95 %), ``natural_period``
    (2π/ω_n) and ``natural_period_ci95``, ``period_crossing_mean`` (mean of the
    zero-crossing periods), ``damping_ratio`` and ``damping_ratio_ci95`` ([lo, hi]; for the
    quadratic model the linear part), ``log_decrements`` and ``damping_ratios`` per cycle with
    ``damping_amplitudes``, ``log_decrements_half`` per half cycle with
    ``half_cycle_amplitudes``, ``n_cycles``, the mean level, the fit's diagnostics and, for
    the quadratic model, ``quadratic_damping`` (c_q in 1/unit) and
    ``damping_ratio_equivalent`` (ζ + 4 c_q A₀ / 3π at the initial amplitude A₀).
    """
    fit = result.fit
    deltas, cycle_amps = result.cycle_decrements()
    half, half_amps = result.half_cycle_decrements()
    zero_periods = np.concatenate([result.periods(1), result.periods(-1)])
    out = {"dof": dof, "unit": unit, "model": fit.model,
           "periods": _floats(result.periods(1)),
           "periods_zero_down": _floats(result.periods(-1)),
           "periods_peak_to_peak": _floats(result.peak_periods()),
           "period_amplitudes": _floats(result.crossing_amplitudes(1), scale),
           **result.summary(),
           "period_crossing_mean": float(np.mean(zero_periods)) if zero_periods.size else None,
           "log_decrements": _floats(deltas),
           "damping_ratios": _floats(log_decrement_damping(deltas)),
           "damping_amplitudes": _floats(cycle_amps, scale),
           "log_decrements_half": _floats(half),
           "half_cycle_amplitudes": _floats(half_amps, scale),
           "amplitude": fit.initial_amplitude() * scale,
           "equilibrium": float(fit.mean_level(result.t_first)) * scale,
           "equilibrium_source": result.equilibrium_source,
           "drift": fit.param("drift") * scale,
           "extrema": [[float(t), a * scale] for t, a, _ in result.extrema],
           "t_first": result.t_first, "t_last": result.t_last, "t_usable": result.t_usable,
           "noise_rms": result.noise_rms * scale, "residual_rms": fit.residual_rms * scale,
           "fit_dof": fit.dof}
    if fit.model != "linear":
        c_q, c_q_hw = fit.param("c_q"), fit.ci95({"c_q": 1.0})
        out["quadratic_damping"] = c_q / scale
        out["quadratic_damping_ci95"] = [(c_q - c_q_hw) / scale, (c_q + c_q_hw) / scale]
        out["damping_ratio_equivalent"] = (fit.zeta + 4 * c_q * fit.initial_amplitude()
                                           / (3 * math.pi))
    return out
