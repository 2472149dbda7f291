"""The level a decay record swings about, and its first cycles reduced about it: where a run's
body settles when the physics gives it (:func:`settled_level`), the theory's equilibrium in a
DoF (:func:`theory_equilibrium`), and the first cycles by zero crossings
(:func:`first_cycles`)."""

from __future__ import annotations

import math
from pathlib import Path

from floatfoam import dofs
from floatfoam.analysis.decay import DecayResult
from floatfoam.analysis.extrema import crossing_reduction
from floatfoam.hydrostatics.summary import TheorySummary
from floatfoam.plan.record import record_or_none


def theory_equilibrium(theory: TheorySummary, dof: str) -> float | None:
    """Equilibrium of a DoF in code units (z of G in m; heel, trim in radians)."""
    eq = theory.equilibrium or {}
    entry = dofs.dof(dof)
    if eq.get(entry.equilibrium_key) is None:
        return None
    value = float(eq[entry.equilibrium_key])
    return math.radians(value) if entry.is_angle else value


def first_cycles(time, value, result: DecayResult, settled: float | None = None):
    """The record's first cycles reduced by its zero crossings
    (:func:`floatfoam.analysis.extrema.crossing_reduction`) about the level the body settles
    at: ``settled`` (:func:`settled_level`) where the physics gives it, else the decay fit's
    mean level at the end (five periods of CFD do not settle, so the record's tail cannot
    say). Raises ValueError on too short a record."""
    level = settled if settled is not None else float(result.fit.mean_level(time[-1]))
    return crossing_reduction(time, value, level=level)


#: settled_level: the largest rise of the tank's water, as a fraction of the release, for
#: which the level is taken as known (0.1 % of the release moves the sphere's first period by
#: ~0.08 %, within its grid study's U_num of 0.10 %)
SETTLED_RISE = 1e-3


def settled_level(case, dof: str, run: Path, theory: TheorySummary) -> float | None:
    """Where a run's body settles in ``dof``, in code units, when the physics gives it: in
    heave, the theory's equilibrium of G (the run's info.json), moved by the discrete body's
    own equilibrium shift at the run's mesh level (it displaces a little less than the exact
    body; the run records it: :func:`floatfoam.foam.render.equilibrium_shift`) and raised
    with the tank's water, which the body displaces more of at equilibrium than at its release
    (A_wp × release / the tank's free surface).

    None — the decay fit's level is used — for the angles, without the run's info, when the
    discrete body's equilibrium shift is not known, and where that rise exceeds
    :data:`SETTLED_RISE` of the release: in a 2D slab (1–3 % of it) the displaced water
    spreads along the tank for seconds while the first cycles pass, so the level they swing
    about is not yet the final one (flume_section_heave: the theory's level with the rise, the
    fit's and the tail's differ by up to 0.8 mm). In a wide tank (the
    laboratory sphere's wedge: 0.06 %) it is exact to a few hundredths of a mm: there the first
    period reduced as a basin reduces its records moves by 0.26 % per 0.1 mm of the level, the
    decay fit's mean level lies 0.15–0.16 mm below this one, and fits of the record after its
    first 1.5 s agree with it within 0.04 mm (cases/lab_sphere/README.md)."""
    if dof != "heave":
        return None
    info = record_or_none(run)
    if info is None or info.z_G_equilibrium is None or info.equilibrium_shift is None:
        return None
    from floatfoam.tank import tank

    box, area, release = tank(case), theory.waterplane_area, case.release["heave"]
    free = {"wedge": math.pi * box.half_length**2,
            "3d": 4 * box.half_length * box.half_width,
            "3d-half": 4 * box.half_length * box.half_width}.get(
        info.mesh, 2 * box.half_length * (case.body.length or 1.0)) - area
    rise = area * release / free
    if abs(rise) > SETTLED_RISE * abs(release):
        return None
    return info.z_G_equilibrium + info.equilibrium_shift + rise
