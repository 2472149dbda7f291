"""The extinction curve of a free-decay record: decrement per half swing against amplitude.

Naval architects reduce a roll decay test to its extinction curve (ITTC Recommended Procedure
7.5-02-07-04.5, *Numerical Estimation of Roll Damping*; Himeno 1981, *Prediction of ship roll
damping — state of the art*, Univ. of Michigan, Dept. of Naval Architecture and Marine
Engineering, Report 239). Per unit of the roll inertia, with φ in rad and ω the natural
frequency,

    φ̈ + 2α φ̇ + β φ̇|φ̇| + γ φ̇³ + ω² φ = 0        (ITTC's p1 = 2α, p2 = β, p3 = γ).

Over a half swing of mean amplitude φ_m the motion is nearly φ_m cos ωt. The damping moment's
work over that half period π/ω, with ∫₀^π sin² = π/2, ∫₀^π |sin|³ = 4/3 and ∫₀^π sin⁴ = 3π/8,

    W = π α ω φ_m² + (4/3) β ω² φ_m³ + (3π/8) γ ω³ φ_m⁴,

equals the loss of restoring energy ω² (φ_i² − φ_{i+1}²)/2 = ω² φ_m Δφ (φ_m the arithmetic mean
of |φ_i| and |φ_{i+1}|, Δφ = |φ_i| − |φ_{i+1}|), so that (Froude's extinction curve)

    Δφ = a φ_m + b φ_m² + c φ_m³,   a = π α / ω,  b = 4 β / 3,  c = 3 π γ ω / 8.

A linear decay loses Δφ / φ_m = π ζ per half swing, hence the equivalent linear damping ratio
at amplitude φ_a,

    ζ_eq(φ_a) = (a + b φ_a + c φ_a²) / π.

The quasi-linear method (the same sources) takes instead the logarithmic decrement of each
whole cycle, ζ_i = ln(|φ_i| / |φ_{i+2}|) / (2π), against the cycle's mean amplitude and fits
ζ = ζ1 + ζ2 φ_m; for small damping ζ1 ≈ a/π and ζ2 ≈ b/π.

A swing's amplitude φ_i is half the peak-to-peak difference of the successive extrema that
bound it, |x_k − x_{k+1}| / 2 (the double amplitude's half), from which the level the record
settles to cancels: amplitudes measured from a fitted mean level that is off by ε change by
±ε, alternately from one half swing to the next, and the decrements by ±2ε — on a CFD roll
record the decay fit's mean (fitted over the whole record, release included) is off by about
0.02°, which moved ζ_eq by ±10 % from one half swing to the next. For a linear decay the
swings decay in the extrema's own ratio, so a, ζ_eq and ζ1 are exact; a quadratic or cubic
term is averaged over two neighbouring half swings, which moves b and c by the second order
of the damping. The extrema are those of
:func:`floatfoam.analysis.decay.analyse_decay`: one turning point per half swing (parabola
vertex refined by a quartic), above the noise and within the usable record. Units are those of
the record (rad or m); :meth:`to_dict` writes file units (degrees, docs/conventions.md).
Intervals are 95 %, Student's t on the residual degrees of freedom; successive decrements share
a swing, so their residuals are not quite independent.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import t as student_t

from floatfoam.analysis.decay import DecayResult
from floatfoam.errors import InputError


@dataclass(frozen=True, eq=False)
class LeastSquares:
    """y ≈ X p by least squares: coefficients p, covariance s² (XᵀX)⁻¹ (s² = RSS / dof)."""

    coefficients: np.ndarray
    covariance: np.ndarray
    dof: int
    residual_rms: float

    def half_width(self, gradient) -> np.ndarray:
        """95 % half-width of g·p for each gradient g (rows of ``gradient``)."""
        g = np.atleast_2d(np.asarray(gradient, dtype=float))
        variance = np.einsum("ij,jk,ik->i", g, self.covariance, g)
        return student_t.ppf(0.975, self.dof) * np.sqrt(np.maximum(variance, 0.0))

    def ci95(self) -> np.ndarray:
        """95 % half-widths of the coefficients."""
        return self.half_width(np.eye(self.coefficients.size))


def least_squares(columns, y) -> LeastSquares:
    """Ordinary least squares of ``y`` on the given ``columns`` (no intercept unless one of
    them is ones); needs more samples than columns."""
    design = np.column_stack(columns)
    y = np.asarray(y, dtype=float)
    coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
    residual = y - design @ coefficients
    dof = y.size - design.shape[1]
    variance = float(residual @ residual) / dof
    covariance = variance * np.linalg.pinv(design.T @ design)
    return LeastSquares(coefficients, covariance, dof, math.sqrt(variance))


@dataclass(frozen=True, eq=False)
class ExtinctionCurve:
    """The half swings of a decay record and the fits of its extinction curve (code units).

    natural_frequency : ω = 2π/T_n of the record's decay fit, rad/s
    times : time of the extremum that starts each half swing, s
    start, end : the amplitudes φ_i and φ_{i+1} of successive swings (half the peak-to-peak
        difference of the extrema bounding each)
    froude : the fit Δφ = a φ_m + b φ_m² (+ c φ_m³), through the origin
    cycle_amplitude, cycle_damping : (|φ_i| + |φ_{i+2}|)/2 and ζ_i = ln(|φ_i|/|φ_{i+2}|)/(2π)
        of each whole cycle
    quasi_linear : the fit ζ = ζ1 + ζ2 φ_m of the per-cycle values
    release_amplitude : |φ| of the first extremum about the decay fit's mean level (the
        release, for a record from rest)
    """

    natural_frequency: float
    times: np.ndarray
    start: np.ndarray
    end: np.ndarray
    froude: LeastSquares
    cycle_amplitude: np.ndarray
    cycle_damping: np.ndarray
    quasi_linear: LeastSquares
    release_amplitude: float

    @property
    def mean_amplitude(self) -> np.ndarray:
        """φ_m,i = (φ_i + φ_{i+1}) / 2 of each half swing (φ_i the swings' amplitudes)."""
        return (self.start + self.end) / 2

    @property
    def decrement(self) -> np.ndarray:
        """Δφ_i = φ_i − φ_{i+1} of each half swing."""
        return self.start - self.end

    @property
    def cubic(self) -> bool:
        """Whether the Froude fit has the cubic term c φ_m³."""
        return self.froude.coefficients.size == 3

    @property
    def a(self) -> float:
        """Linear extinction coefficient a = π α / ω (dimensionless)."""
        return float(self.froude.coefficients[0])

    @property
    def b(self) -> float:
        """Quadratic extinction coefficient b = 4 β / 3 (1/rad or 1/m)."""
        return float(self.froude.coefficients[1])

    @property
    def c(self) -> float:
        """Cubic extinction coefficient c = 3 π γ ω / 8 (0 without the cubic term)."""
        return float(self.froude.coefficients[2]) if self.cubic else 0.0

    def ittc_coefficients(self) -> tuple[np.ndarray, np.ndarray]:
        """(p1, p2[, p3]) = (2α, β[, γ]) = (2ωa/π, 3b/4[, 8c/(3πω)]) and their 95 %
        half-widths (ω taken as exact: its interval is far narrower than a's, b's and c's)."""
        omega = self.natural_frequency
        factors = np.array([2 * omega / math.pi, 0.75, 8 / (3 * math.pi * omega)])
        factors = factors[:self.froude.coefficients.size]
        return factors * self.froude.coefficients, factors * self.froude.ci95()

    def _powers(self, amplitude) -> np.ndarray:
        return np.power.outer(np.atleast_1d(np.asarray(amplitude, dtype=float)),
                              np.arange(self.froude.coefficients.size))

    def damping_ratio_equivalent(self, amplitude) -> np.ndarray:
        """ζ_eq(φ_a) = (a + b φ_a + c φ_a²) / π at the amplitude(s) φ_a."""
        return self._powers(amplitude) @ self.froude.coefficients / math.pi

    def damping_ratio_equivalent_ci95(self, amplitude) -> np.ndarray:
        """95 % half-width of :meth:`damping_ratio_equivalent` (from the fit's covariance)."""
        return self.froude.half_width(self._powers(amplitude) / math.pi)

    def fitted_decrement(self, amplitude) -> tuple[np.ndarray, np.ndarray]:
        """The fit's Δφ = a φ_m + b φ_m² (+ c φ_m³) at the amplitude(s) and its 95 %
        half-width."""
        powers = self._powers(amplitude) * np.atleast_1d(np.asarray(amplitude, float))[:, None]
        return powers @ self.froude.coefficients, self.froude.half_width(powers)

    def half_swing_damping(self) -> np.ndarray:
        """The measured ζ_eq of each half swing, Δφ_i / (π φ_m,i)."""
        return self.decrement / (math.pi * self.mean_amplitude)

    def to_dict(self, *, unit: str, scale: float = 1.0) -> dict:
        """JSON-ready: amplitudes in file units (``scale`` × code units, e.g. 180/π → deg),
        the unit in each key's name (``mean_amplitude_deg``, ``b_per_deg``, ``p3_s_per_deg2``);
        intervals are 95 % [lo, hi]."""
        u = unit

        def pair(value, half, factor=1.0):
            return [float((value - half) * factor), float((value + half) * factor)]

        ab = self.froude.ci95()
        p, p_half = self.ittc_coefficients()
        release = self.release_amplitude
        zeta_release = float(self.damping_ratio_equivalent(release)[0])
        zeta_half = float(self.damping_ratio_equivalent_ci95(release)[0])
        out = {"terms": "a φ_m + b φ_m² + c φ_m³" if self.cubic else "a φ_m + b φ_m²",
               "unit": u,
               "natural_frequency_rad_per_s": self.natural_frequency,
               "natural_period_s": 2 * math.pi / self.natural_frequency,
               "half_swing_time_s": _floats(self.times),
               f"start_amplitude_{u}": _floats(self.start, scale),
               f"end_amplitude_{u}": _floats(self.end, scale),
               f"mean_amplitude_{u}": _floats(self.mean_amplitude, scale),
               f"decrement_{u}": _floats(self.decrement, scale),
               "damping_ratio_equivalent": _floats(self.half_swing_damping()),
               "damping_ratio_equivalent_fit": _floats(
                   self.damping_ratio_equivalent(self.mean_amplitude)),
               "a": self.a, "a_ci95": pair(self.a, ab[0]),
               f"b_per_{u}": self.b / scale, f"b_per_{u}_ci95": pair(self.b, ab[1], 1 / scale),
               "p1_per_s": float(p[0]), "p1_per_s_ci95": pair(p[0], p_half[0]),
               f"p2_per_{u}": float(p[1] / scale),
               f"p2_per_{u}_ci95": pair(p[1], p_half[1], 1 / scale)}
        if self.cubic:
            out |= {f"c_per_{u}2": self.c / scale**2,
                    f"c_per_{u}2_ci95": pair(self.c, ab[2], 1 / scale**2),
                    f"p3_s_per_{u}2": float(p[2] / scale**2),
                    f"p3_s_per_{u}2_ci95": pair(p[2], p_half[2], 1 / scale**2)}
        zeta1, zeta2 = self.quasi_linear.coefficients
        q_half = self.quasi_linear.ci95()
        out |= {f"release_amplitude_{u}": release * scale,
                "damping_ratio_equivalent_release": zeta_release,
                "damping_ratio_equivalent_release_ci95": pair(zeta_release, zeta_half),
                f"residual_rms_{u}": self.froude.residual_rms * scale,
                "fit_dof": self.froude.dof,
                "quasi_linear": {
                    f"mean_amplitude_{u}": _floats(self.cycle_amplitude, scale),
                    "damping_ratio": _floats(self.cycle_damping),
                    "zeta1": float(zeta1), "zeta1_ci95": pair(zeta1, q_half[0]),
                    f"zeta2_per_{u}": float(zeta2 / scale),
                    f"zeta2_per_{u}_ci95": pair(zeta2, q_half[1], 1 / scale),
                    "residual_rms": self.quasi_linear.residual_rms,
                    "fit_dof": self.quasi_linear.dof}}
        return out


def _floats(values, scale: float = 1.0) -> list[float]:
    return [float(v) * scale for v in np.atleast_1d(values)]


def _neighbours(extrema, step: int) -> list[tuple[tuple, tuple]]:
    """(earlier, later) extrema ``step`` half swings apart: stretches k and k + step between
    successive zero crossings, so a turning point not found leaves a gap, never a false pair."""
    by_stretch = {k: (t, value) for t, value, k in extrema}
    return [(by_stretch[k], by_stretch[k + step]) for k in sorted(by_stretch)
            if k + step in by_stretch]


def _swings(extrema) -> list[tuple[float, float, int]]:
    """(time, amplitude, stretch) of the swing between successive extrema k and k + 1: half
    their peak-to-peak difference, |x_k − x_{k+1}| / 2, from which the mean level cancels."""
    by_stretch = {k: (t, value) for t, value, k in extrema}
    return [(by_stretch[k][0], abs(by_stretch[k][1] - by_stretch[k + 1][1]) / 2, k)
            for k in sorted(by_stretch) if k + 1 in by_stretch]


def extinction_curve(result: DecayResult, *, cubic: bool = False,
                     name: str = "record") -> ExtinctionCurve:
    """Half swings and extinction-curve fits of a decay record (see the module docstring).

    Parameters
    ----------
    result : :func:`~floatfoam.analysis.decay.analyse_decay`'s analysis of the record: its
        extrema about the fitted mean level and its natural period T_n (ω = 2π/T_n).
    cubic : fit Δφ = a φ_m + b φ_m² + c φ_m³ instead of a φ_m + b φ_m².
    name : what the record is called in error messages.

    Returns
    -------
    ExtinctionCurve
        Δφ_i = φ_i − φ_{i+1} against φ_m,i = (φ_i + φ_{i+1})/2 (φ_i the swings' amplitudes),
        the least-squares fit through the origin with 95 % intervals (Student's t), ITTC's p1,
        p2, p3, ζ_eq, and the quasi-linear fit ζ_i = ζ1 + ζ2 φ_m of
        ζ_i = ln(φ_i / φ_{i+2}) / (2π).

    Raises
    ------
    InputError
        fewer half swings than the fit's coefficients + 2 (a fit needs two residual degrees
        of freedom for an interval worth the name).
    """
    swings = _swings(result.extrema)
    halves = _neighbours(swings, 1)
    n_terms = 3 if cubic else 2
    if len(halves) < n_terms + 2:
        terms = "a φ_m + b φ_m² + c φ_m³" if cubic else "a φ_m + b φ_m²"
        raise InputError(f"{name}: {len(halves)} half swings above the noise between "
                         f"t = {result.t_first:g} and {result.t_usable:.4g} s; the extinction "
                         f"fit {terms} needs at least {n_terms + 2} (its coefficients + 2); "
                         "valid is a longer record" + (", or no --cubic" if cubic else ""))
    times = np.array([first[0] for first, _ in halves])
    start = np.array([first[1] for first, _ in halves])
    end = np.array([second[1] for _, second in halves])
    mean = (start + end) / 2
    froude = least_squares([mean**k for k in range(1, n_terms + 1)], start - end)
    cycles = _neighbours(swings, 2)
    if len(cycles) < 3:  # only where turning points are missing in the middle of the record
        raise InputError(f"{name}: {len(cycles)} whole cycles of successive extrema between "
                         f"t = {result.t_first:g} and {result.t_usable:.4g} s; the "
                         "quasi-linear fit ζ1 + ζ2 φ_m needs at least 3; valid is a longer or "
                         "less noisy record")
    cycle_start = np.array([first[1] for first, _ in cycles])
    cycle_end = np.array([second[1] for _, second in cycles])
    cycle_amplitude = (cycle_start + cycle_end) / 2
    cycle_damping = np.log(cycle_start / cycle_end) / (2 * math.pi)
    quasi_linear = least_squares([np.ones_like(cycle_amplitude), cycle_amplitude],
                                 cycle_damping)
    first = min(result.extrema, key=lambda e: e[2])
    return ExtinctionCurve(2 * math.pi / result.fit.natural_period()[0], times, start, end,
                           froude, cycle_amplitude, cycle_damping, quasi_linear,
                           abs(float(first[1])))
