"""The first extrema of a smooth decay record and the period they give.

A record too damped for the decay fit (a flat section radiating strongly, ζ ≈ 0.2, leaves the
noise after ~1.5 cycles) still times its first cycles by its extrema: the sign changes of its
slope, half a period apart.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def first_extrema(x, count: int) -> np.ndarray:
    """Indices of the first ``count`` (or fewer) extrema of ``x``: where its slope changes sign."""
    slope = np.diff(np.asarray(x, dtype=float))
    return (np.nonzero(np.sign(slope[1:]) != np.sign(slope[:-1]))[0] + 1)[:count]


def period_from_extrema(t, turns) -> float:
    """The period from extrema at the indices ``turns`` (≥ 2): twice their mean spacing."""
    t = np.asarray(t, dtype=float)
    return 2.0 * float(t[turns[-1]] - t[turns[0]]) / (len(turns) - 1)


@dataclass(frozen=True)
class CrossingReduction:
    """A decay record reduced by its zero crossings about the settled level (code units).

    first_period : twice the time from the first down-crossing after the release to the next
        up-crossing (the first trough's half cycle, doubled)
    first_trough : depth of the first trough below the settled level (> 0)
    decay_rate : σ of ln|A| = c − σ t fitted to the first ``n`` extrema (1/s)
    damping_ratio : σ / √(ω_d² + σ²), ω_d = 2π/T from the same extrema's mean spacing
    settled : the settled level, the mean of the record's last ``tail`` fraction
    """

    first_period: float
    first_trough: float
    decay_rate: float
    damping_ratio: float
    settled: float


def crossing_reduction(t, x, *, level: float | None = None, n_extrema: int = 6,
                       tail: float = 0.15) -> CrossingReduction:
    """Reduce a release-from-above decay record as Kramer et al.'s (2021, Energies 14:269)
    sphere benchmark records are reduced by the analysis we compare with (jcerrell-IS/can-it-ford,
    simulation/r5_physics/kramer_benchmark.py): level = mean of the last 15 %; zero crossings by
    linear interpolation; the extrema between successive crossings (the release at t = 0, not
    bracketed, is left out), each refined by the parabola through its three nearest samples;
    σ from a least-squares line through ln|A| of the first six.

    ``level`` replaces the tail's mean where the record ends before it has settled (a CFD record
    of five periods still swings by ~5 % of its release at the end, and its tail's mean is off by
    a few % of that: enough to move the crossings by 0.1 %). Raises ValueError when the record
    has fewer than ``n_extrema`` bracketed extrema."""
    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    settled = float(np.mean(x[t >= t[0] + (1 - tail) * (t[-1] - t[0])])) if level is None \
        else float(level)
    y = x - settled
    above = y >= 0  # a sample exactly on the level counts as above: no crossing is lost
    idx = np.nonzero(above[1:] != above[:-1])[0]
    if idx.size and not above[idx[0]]:
        raise ValueError("the record starts below its settled level; valid is a release from "
                         "above (a positive offset)")
    crossings = t[idx] - y[idx] * (t[idx + 1] - t[idx]) / (y[idx + 1] - y[idx])
    extrema = []
    for a, b in zip(idx[:-1], idx[1:], strict=True):
        k = a + 1 + int(np.argmax(np.abs(y[a + 1:b + 1])))
        extrema.append(parabola_peak(t, y, k))
    if len(extrema) < n_extrema:
        raise ValueError(f"{len(extrema)} extrema between zero crossings; {n_extrema} are "
                         "needed")
    times = np.array([e[0] for e in extrema[:n_extrema]])
    amps = np.abs([e[1] for e in extrema[:n_extrema]])
    sigma = -float(np.polyfit(times, np.log(amps), 1)[0])
    omega = 2 * np.pi / (2 * (times[-1] - times[0]) / (n_extrema - 1))
    return CrossingReduction(first_period=2 * float(crossings[1] - crossings[0]),
                             first_trough=float(-extrema[0][1]), decay_rate=sigma,
                             damping_ratio=sigma / float(np.hypot(omega, sigma)),
                             settled=settled)


def parabola_peak(t, y, k) -> tuple[float, float]:
    """Time and value of the vertex of the parabola through samples k − 1, k, k + 1 (the
    sample itself when the vertex falls outside them, as the reference reduction does)."""
    if k == 0 or k == len(y) - 1:
        return float(t[k]), float(y[k])
    coef = np.polyfit(t[k - 1:k + 2] - t[k], y[k - 1:k + 2], 2)
    if coef[0] == 0:
        return float(t[k]), float(y[k])
    s = -coef[1] / (2 * coef[0])
    if not t[k - 1] - t[k] <= s <= t[k + 1] - t[k]:  # a vertex outside its samples: the sample
        return float(t[k]), float(y[k])
    return float(t[k] + s), float(np.polyval(coef, s))
