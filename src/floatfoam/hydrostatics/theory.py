"""Linear hydrostatic theory of a floating body (Le Barbier 1817, without the fluid's
resistance): equilibrium, metacentric heights, stiffness, verdicts and natural periods."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatfoam.bodies.geometry import rotation
from floatfoam.case import Case
from floatfoam.hydrostatics.fluid_domain import check_depth, vertical_extent
from floatfoam.hydrostatics.immersion import Immersed, immersed
from floatfoam.hydrostatics.roots import brentq
from floatfoam.hydrostatics.summary import DofTheory, TheorySummary
from floatfoam.hydrostatics.verdict import verdict


@dataclass(frozen=True)
class Equilibrium:
    """Floating position: z_c (height of the geometric centre above the free surface, m),
    heel and trim (radians), and the immersed part there."""

    z_c: float
    heel: float
    trim: float
    immersed: Immersed


def sinkage_for_volume(case: Case, volume: float, heel: float = 0.0, trim: float = 0.0,
                       **kw) -> tuple[float, Immersed]:
    """Height z_c at which the body, at the given heel and trim, displaces ``volume``.

    The immersed volume falls monotonically as z_c rises, so it is bracketed between the body
    fully submerged and fully emerged (the radius of its bounding box) and found by Brent's
    method.
    """
    reach = float(np.linalg.norm(np.maximum(abs(case.body.lo), abs(case.body.hi))))

    def excess(z_c):
        return immersed(case.body, z_c, heel, trim, **kw).volume - volume

    z_c = brentq(excess, -reach, reach, xtol=1e-12 * reach, rtol=1e-14, maxiter=200)
    return z_c, immersed(case.body, z_c, heel, trim, **kw)


def equilibrium(case: Case, **kw) -> Equilibrium:
    """Equilibrium of ``case``: ρV = M and B on the vertical through G (Le Barbier's two
    conditions). Upright when G lies on the body's vertical axis; otherwise heel and trim are
    solved for from the upright position (Powell's hybrid method). Raises InputError when a
    finite fluid.depth does not exceed the draft there
    (:func:`floatfoam.hydrostatics.fluid_domain.check_depth`): every command solves it here."""
    eq = _floating_position(case, **kw)
    check_depth(case, eq)
    return eq


def _floating_position(case: Case, **kw) -> Equilibrium:
    """:func:`equilibrium`'s solution, in a fluid without a bottom."""
    volume = case.displacement
    z_c, imm = sinkage_for_volume(case, volume, **kw)
    if abs(case.cog[0]) < 1e-12 * case.body.size and abs(case.cog[1]) < 1e-12 * case.body.size:
        return Equilibrium(z_c, 0.0, 0.0, imm)
    from scipy.optimize import root  # only for a body that heels or trims at rest

    free = [abs(case.cog[1]) > 0, abs(case.cog[0]) > 0 and not case.body.is_section]
    size = case.body.size

    def residual(x):
        heel = x[1] if free[0] else 0.0
        trim = x[-1] if free[1] else 0.0
        imm = immersed(case.body, x[0], heel, trim, **kw)
        g = rotation(heel, trim) @ case.cog + np.array([0.0, 0.0, x[0]])
        out = [(imm.volume - volume) / volume]
        if free[0]:
            out.append((imm.centroid[1] - g[1]) / size)
        if free[1]:
            out.append((imm.centroid[0] - g[0]) / size)
        return out

    start = [z_c] + [0.0] * sum(free)
    sol = root(residual, start, method="hybr", options={"xtol": 1e-12})
    heel = sol.x[1] if free[0] else 0.0
    trim = sol.x[-1] if free[1] else 0.0
    return Equilibrium(sol.x[0], heel, trim, immersed(case.body, sol.x[0], heel, trim, **kw))


def stiffness_matrix(case: Case, eq: Equilibrium | None = None) -> np.ndarray:
    """Hydrostatic stiffness for (heave, roll, pitch) about the vertical through G,
    Newman (1977, Marine Hydrodynamics, §6.16):

        C33 = ρgA,  C34 = ρg∫(y − y_G)dA,  C35 = −ρg∫(x − x_G)dA,
        C44 = ρg[∫(y − y_G)²dA + V z_B] − Mg z_G,  C55 = ρg[∫(x − x_G)²dA + V z_B] − Mg z_G,
        C45 = −ρg∫(x − x_G)(y − y_G)dA,

    with the waterplane integrals over the equilibrium waterplane and z measured from it.
    """
    eq = eq or equilibrium(case)
    imm = eq.immersed
    g_pos = rotation(eq.heel, eq.trim) @ case.cog + np.array([0.0, 0.0, eq.z_c])
    area = imm.waterplane_area
    dx, dy = imm.waterplane_centroid - g_pos[:2]
    i_xx, i_yy, i_xy = imm.waterplane_inertia
    rg = case.rho * case.g
    c = np.zeros((3, 3))
    c[0, 0] = rg * area
    c[0, 1] = c[1, 0] = rg * area * dy
    c[0, 2] = c[2, 0] = -rg * area * dx
    vertical = rg * imm.volume * imm.centroid[2] - case.mass * case.g * g_pos[2]
    c[1, 1] = rg * (i_xx + area * dy**2) + vertical
    c[2, 2] = rg * (i_yy + area * dx**2) + vertical
    c[1, 2] = c[2, 1] = -rg * (i_xy + area * dx * dy)
    return c


def natural_period(stiffness: float, inertia: float) -> float | None:
    """Undamped period T = 2π √(inertia / stiffness), None when the stiffness is not positive."""
    return 2.0 * math.pi * math.sqrt(inertia / stiffness) if stiffness > 0 else None


def theory_summary(case: Case, eq: Equilibrium | None = None) -> TheorySummary:
    """Everything the linear theory says about ``case``, in SI units, seconds and degrees
    (``eq``: its equilibrium, solved here when not given).

    Heave: ω² = ρgA/M; roll and pitch: ω² = ρgV·GM/(M K²) (Le Barbier 1817), with GM from the
    stiffness: GM = C44/(ρgV) and C55/(ρgV).
    """
    eq = eq or equilibrium(case)
    imm = eq.immersed
    c = stiffness_matrix(case, eq)
    rgv = case.rho * case.g * imm.volume
    b_body = rotation(eq.heel, eq.trim).T @ (imm.centroid - np.array([0.0, 0.0, eq.z_c]))
    keel = case.body.keel_z
    gm_roll, gm_pitch = c[1, 1] / rgv, c[2, 2] / rgv
    verdicts = [verdict(gm, case.body.size, imm.exact) for gm in (gm_roll, gm_pitch)]
    kx, ky, _ = case.gyradius
    inertia = np.diag([case.mass, case.mass * kx**2, case.mass * ky**2])
    periods = [
        natural_period(c[0, 0], case.mass),
        natural_period(c[1, 1], inertia[1, 1]) if verdicts[0] == "oscillates" else None,
        natural_period(c[2, 2], inertia[2, 2]) if verdicts[1] == "oscillates" else None,
    ]
    i_xx, i_yy, _ = imm.waterplane_inertia
    g_earth = rotation(eq.heel, eq.trim) @ case.cog + np.array([0.0, 0.0, eq.z_c])
    draft, kg = -float(min(lowest_point(case, eq), 0.0)), float(case.cog[2] - keel)
    from floatfoam.hydrostatics.memoir_case import memoir_printed_values, memoir_values

    printed = memoir_printed_values(case, kg=kg, draft=draft)
    if printed:
        printed["verdict_roll_matches_exact"] = printed["verdict_roll"] == verdicts[0]

    return TheorySummary(
        case=case.name,
        body=type(case.body).__name__,
        section_length=case.body.length,
        mass=case.mass,
        draft=draft,
        displaced_volume=imm.volume,
        waterplane_area=imm.waterplane_area,
        KB=float(b_body[2] - keel),
        KG=kg,
        dofs={"heave": DofTheory(periods[0]),
              "roll": DofTheory(periods[1], gm_roll, i_xx / imm.volume, verdicts[0]),
              "pitch": DofTheory(periods[2], gm_pitch, i_yy / imm.volume, verdicts[1])},
        equilibrium={
            "z_centre": eq.z_c,
            "z_G": float(g_earth[2]),
            "heel": math.degrees(eq.heel),
            "trim": math.degrees(eq.trim),
            "centre_of_buoyancy": imm.centroid.tolist(),
        },
        stiffness=c.tolist(),
        exact=imm.exact,
        memoir=memoir_values(case, kg=kg, draft=draft),
        memoir_printed=printed,
        file_origin=None if getattr(case.body, "file_origin", None) is None
        else [float(v) for v in case.body.file_origin],
    )


def lowest_point(case: Case, placement) -> float:
    """z of the body's lowest point in the earth frame at ``placement`` (anything with z_c, heel
    and trim: an :class:`Equilibrium` or a mesh pose), from its surface mesh; upright, the
    body's exact keel (:func:`floatfoam.hydrostatics.fluid_domain.vertical_extent`)."""
    return vertical_extent(case, placement)[0]
