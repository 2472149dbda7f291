"""A run's mesh motion spread wider or narrower, for a study of it (``floatfoam run
--morphing F``, ``floatfoam validate``): the factor checked (:func:`check_morphing`), the case
as that run takes it (:func:`scaled_morphing`) and what it changes, in words
(:func:`morphing_variant`)."""

from __future__ import annotations

import math

from floatfoam import settings
from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.plan import zone
from floatfoam.tank import Pose


def check_morphing(factor: float, *, study: bool = False) -> None:
    """A morphing factor must be > 0 and name its run folder exactly (at most 6 significant
    digits: ``<level>-morph<F>``); a study's must not be 1, which is the coarse run itself."""
    valid = (not isinstance(factor, bool) and isinstance(factor, (int, float))
             and math.isfinite(factor) and factor > 0 and float(f"{factor:g}") == factor
             and not (study and factor == 1))
    if not valid:
        raise InputError(f"--morphing {factor!r}: valid is a factor > 0 of at most 6 "
                         "significant digits" + (" other than 1 (--no-morphing: no mesh-motion "
                                                 "run)" if study else "") +
                         " (1.5: both morphing distances one and a half times the case's, "
                         "the Laplacian's diffusivity 1/d instead of 1/d², or the layered "
                         "motion's rows that move with the body over 1.5 × their height)")


def scaled_morphing(case: Case, release: Pose, factor: float) -> Case:
    """The case with its mesh motion (:func:`floatfoam.plan.zone.mesh_motion`, the body at
    ``release``) spread wider
    or narrower by ``factor`` > 0 (:func:`morphing_variant` says how, in words):

    * the six-DoF solver's distances — the mesh moves rigidly with the body within
      run.inner_distance and is fixed beyond run.outer_distance, or their defaults from the
      body and the tank (:func:`floatfoam.plan.zone.distances`) — both multiplied by ``factor``, or
      divided by it where the defaults already reach as far as the tank allows
      (:func:`distance_factor`);
    * the layered motion: run.layer_band multiplied by ``factor`` (the rows that move with
      the body span ``factor`` × as much height about its middle); a band narrower than the
      body, which would deform the body, is refused;
    * the Laplacian, for ``factor`` > 1: run.motion_diffusivity "linear", whose 1/d spreads
      the deformation further from the body than the default 1/d². A factor < 1, or a case
      already at 1/d, is refused: no narrower nor wider Laplacian is offered.

    A study of the mesh motion, which a study of mesh levels cannot see since the motion is
    the same on every level: the damping ratio of the laboratory sphere's 0.3 D drop rose from
    0.066 to 0.109 as the distances were widened from 0.09 and 0.48 m to 0.2 and 1.2 m
    (docs/studies/cases/lab_sphere.md)."""
    check_morphing(factor)
    if factor == 1:
        return case
    from floatfoam.case import with_overrides

    mesh = zone.of_case(case, release)
    if mesh.motion == "distances":
        scale = distance_factor(case, factor)
        # named in the run's stamp; "auto" resolves to the distances too once they are set
        # (floatfoam.plan.zone.mesh_motion), so a narrowed zone never varies the solver
        return with_overrides(case, ['run.mesh_motion="distances"',
                                     f"run.inner_distance={mesh.inner * scale!r}",
                                     f"run.outer_distance={mesh.outer * scale!r}"])
    if mesh.motion == "layered":
        return with_overrides(case, [f"run.layer_band={_layer_band(case, factor)!r}"])
    wider = _wider_diffusivity(case, factor)
    return with_overrides(case, [f'run.motion_diffusivity="{wider}"'])


def distance_factor(case: Case, factor: float) -> float:
    """What the six-DoF distances are multiplied by in a run of mesh-motion factor ``factor``:
    ``factor`` itself, but 1 / ``factor`` for a widening (``factor`` > 1) of the defaults,
    whose outer distance already reaches 0.9 × the room to the tank's nearest held wall
    (:func:`floatfoam.plan.zone.distances`): widened, the zone would squeeze the walls'
    first cells; narrowed as much, it says as much of the distances' effect."""
    return 1.0 / factor if factor > 1 and case.settings.run.outer_distance is None else factor


def _layer_band(case: Case, factor: float) -> float:
    """run.layer_band of the layered motion scaled by ``factor``; InputError below 1 (rows
    moving with the body that do not span it would deform it)."""
    band = case.settings.run.layer_band * factor
    if band < 1:
        raise InputError(f"--morphing {factor:g} narrows the layered motion's rows that move "
                         f"with the body to {band:g} × the body's height, which would deform "
                         "the body: valid is a factor ≥ "
                         f"{1 / case.settings.run.layer_band:g} (1.5: rows over 1.5 × its "
                         "height)")
    return band


#: the diffusivity a Laplacian run of a mesh-motion study takes (:func:`scaled_morphing`)
WIDER_DIFFUSIVITY = {"quadratic": "linear"}


def _wider_diffusivity(case: Case, factor: float) -> str:
    """run.motion_diffusivity of the Laplacian spread wider (``factor`` > 1); InputError for
    ``factor`` < 1 or a case whose diffusivity has none wider."""
    now = case.settings.run.motion_diffusivity
    if factor < 1:
        raise InputError(f"--morphing {factor:g} narrows the mesh motion; this run's mesh "
                         "follows the body by the Laplacian, for which no diffusivity narrower "
                         "than 1/d² is offered: valid is a factor > 1 (diffusivity 1/d), or "
                         "--set run.mesh_motion='\"distances\"'")
    if now not in WIDER_DIFFUSIVITY:
        raise InputError(f"--morphing {factor:g} spreads the Laplacian's deformation wider; "
                         f"run.motion_diffusivity = {now!r} (1/d) is the widest offered: valid "
                         "is --no-morphing, or --set run.motion_diffusivity='\"quadratic\"'")
    return WIDER_DIFFUSIVITY[now]


def morphing_variant(case: Case, motion: str, factor: float) -> str:
    """What :func:`scaled_morphing` changes in a run whose mesh follows the body by
    ``motion`` ("layered", "laplacian" or "distances"), in words: "distances × 1.5",
    "diffusivity 1/d instead of 1/d²", "rows moving with the body over 1.5 × its height"."""
    if motion == "layered":
        return (f"rows moving with the body over {_layer_band(case, factor):g} × its height "
                f"instead of {case.settings.run.layer_band:g} ×")
    if motion == "distances":
        scale = distance_factor(case, factor)
        return f"distances × {factor:g}" if scale == factor else \
            f"distances ÷ {factor:g} (their defaults reach as far as the tank allows)"
    now = case.settings.run.motion_diffusivity
    words = settings.MOTION_DIFFUSIVITIES
    return f"diffusivity {words[WIDER_DIFFUSIVITY.get(now, now)]} instead of {words[now]}"
