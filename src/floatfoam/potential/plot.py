"""Plot of the radiation coefficients A(ω), B(ω) with the natural frequencies marked."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from floatfoam.dofs import COUPLED
from floatfoam.potential.radiation import RadiationCoefficients
from floatfoam.potential.summary import PotentialSummary


def plot_coefficients(coef: RadiationCoefficients, path: str | Path, *,
                      summary: PotentialSummary | None = None, title: str = "") -> Path:
    """PNG of A_ii(ω) (with A∞ dashed) and B_ii(ω) for the covered DoFs; the natural
    frequencies of ``summary`` (:func:`~floatfoam.potential.radiation.potential_summary`) as
    lines."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    dofs = [i for i, ok in enumerate(coef.covered) if ok]
    fig, axes = plt.subplots(2, len(dofs), figsize=(3.6 * len(dofs), 5.6), dpi=120,
                             squeeze=False, sharex=True)
    for col, i in enumerate(dofs):
        name = COUPLED[i].name
        unit_a, unit_b = COUPLED[i].inertia_unit, COUPLED[i].damping_unit
        ax_a, ax_b = axes[0, col], axes[1, col]
        ax_a.plot(coef.omega, coef.added_mass[:, i, i], "o-", ms=3, color="tab:blue")
        ax_a.axhline(coef.added_mass_inf[i, i], color="tab:blue", ls="--", lw=0.8,
                     label="A∞")
        ax_b.plot(coef.omega, coef.damping[:, i, i], "o-", ms=3, color="tab:red")
        omega_n = summary.dof(name).natural_frequency if summary else None  # surge, sway: None
        for ax in (ax_a, ax_b):
            if omega_n:
                ax.axvline(omega_n, color="0.4", lw=0.8, ls=":", label="ω_n")
            ax.grid(alpha=0.3)
        ax_a.set_title(name)
        ax_a.set_ylabel(f"A ({unit_a})")
        ax_b.set_ylabel(f"B ({unit_b})")
        ax_b.set_xlabel("ω (rad/s)")
        ax_a.legend(fontsize=8)
        ax_b.set_ylim(bottom=min(0.0, float(np.min(coef.damping[:, i, i]))))
    fig.suptitle(title or f"Radiation coefficients ({coef.method}, {coef.panels} panels)")
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return path
