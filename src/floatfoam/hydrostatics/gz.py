"""Righting-arm (GZ) curve at constant displacement."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatfoam.bodies.geometry import rotation
from floatfoam.case import Case
from floatfoam.errors import InputError, is_number
from floatfoam.hydrostatics.theory import equilibrium, sinkage_for_volume

MAX_STEPS = 1000  # heel steps of a GZ curve (check_angles)


@dataclass(frozen=True)
class GZCurve:
    """GZ (m) at heel angles (degrees); the angle of vanishing stability (degrees, None when
    GZ stays positive up to the last angle), the largest GZ and its angle."""

    angles: np.ndarray
    gz: np.ndarray
    vanishing_angle: float | None
    max_gz: float
    max_gz_angle: float

    def as_dict(self) -> dict:
        return {
            "angles": self.angles.tolist(),
            "GZ": self.gz.tolist(),
            "angle_of_vanishing_stability": self.vanishing_angle,
            "max_GZ": self.max_gz,
            "angle_of_max_GZ": self.max_gz_angle,
        }


def righting_arm(case: Case, heel: float, trim: float = 0.0, **kw) -> float:
    """GZ at ``heel`` (radians), fixed trim, constant displacement M/ρ:

        GZ = y_G − y_B  (earth frame),

    so that the righting moment about x is ρ g V · GZ (positive rights the body).
    """
    z_c, imm = sinkage_for_volume(case, case.displacement, heel, trim, **kw)
    g = rotation(heel, trim) @ case.cog
    return float(g[1] - imm.centroid[1])


def check_angles(max_angle: float, step: float) -> int:
    """The number of heel angles of a GZ curve to ``max_angle`` every ``step`` degrees; an
    InputError naming --max-angle or --step, the value and the valid range otherwise. At most
    :data:`MAX_STEPS` steps: each angle is a root solve (superellipsoid_buoy, an implicit
    surface, takes 72 ms per angle: 1000 steps ≈ 72 s, with a progress line every 10 s)."""
    if not (is_number(max_angle) and 0.0 < max_angle <= 180.0):
        raise InputError(f"--max-angle {_text(max_angle)}: valid is 0 < DEG ≤ 180")
    finest = max_angle / MAX_STEPS
    if not (is_number(step) and finest <= step <= max_angle):
        count = f" gives {max_angle / step:.3g} steps;" if is_number(step) and step > 0 else ""
        raise InputError(f"--step {_text(step)}:{count} valid is {finest:.4g} ≤ DEG ≤ --max-angle "
                         f"{max_angle:g} (at most {MAX_STEPS} steps)")
    return len(np.arange(0.0, max_angle + 0.5 * step, step))


def _text(value) -> str:
    return f"{value:g}" if isinstance(value, (int, float)) else repr(value)


def gz_curve(case: Case, max_angle: float = 90.0, step: float = 1.0, *, progress=None,
             **kw) -> GZCurve:
    """GZ from 0 to ``max_angle`` degrees every ``step`` degrees (:func:`check_angles`), at
    the equilibrium trim; ``progress`` (a :class:`~floatfoam.potential.bounded.Heartbeat`)
    hears of each angle."""
    count = check_angles(max_angle, step)
    trim = equilibrium(case).trim
    angles = np.arange(0.0, max_angle + 0.5 * step, step)
    if progress is not None:
        progress.stage("GZ curve", total=count, unit="angles")
    gz = np.empty(len(angles))
    for i, a in enumerate(angles):
        gz[i] = righting_arm(case, math.radians(a), trim, **kw)
        if progress is not None:
            progress.update(i + 1)
    vanishing = None
    positive = gz[1:] > 0
    if len(positive) and positive[0]:
        drops = np.nonzero(~positive)[0]
        if len(drops):
            i = drops[0] + 1  # first angle with GZ <= 0 after the positive range
            a0, a1, g0, g1 = angles[i - 1], angles[i], gz[i - 1], gz[i]
            vanishing = float(a0 + (a1 - a0) * g0 / (g0 - g1))
    elif len(positive):
        vanishing = 0.0
    k = int(np.argmax(gz))
    return GZCurve(angles, gz, vanishing, float(gz[k]), float(angles[k]))


def plot_gz(curve: GZCurve, path, title: str = "") -> None:
    """Write the GZ curve as a PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=120)
    ax.plot(curve.angles, curve.gz * 1000.0, color="tab:blue")
    ax.axhline(0.0, color="0.5", lw=0.8)
    if curve.vanishing_angle is not None:
        ax.axvline(curve.vanishing_angle, color="tab:red", ls="--", lw=0.8,
                   label=f"vanishing stability {curve.vanishing_angle:.1f}°")
        ax.legend()
    ax.set_xlabel("heel angle (deg)")
    ax.set_ylabel("GZ (mm)")
    ax.set_title(title or "Righting arm at constant displacement")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
