"""Righting-arm (GZ) curve at constant displacement."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatfoam.bodies.geometry import rotation
from floatfoam.case import Case
from floatfoam.hydrostatics.theory import equilibrium, sinkage_for_volume


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


def gz_curve(case: Case, max_angle: float = 90.0, step: float = 1.0, **kw) -> GZCurve:
    """GZ from 0 to ``max_angle`` degrees every ``step`` degrees, at the equilibrium trim."""
    trim = equilibrium(case).trim
    angles = np.arange(0.0, max_angle + 0.5 * step, step)
    gz = np.array([righting_arm(case, math.radians(a), trim, **kw) for a in angles])
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
