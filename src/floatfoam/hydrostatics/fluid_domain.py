"""Whether the body is in its fluid: water under the keel at equilibrium, and the release
inside the case's tank. The one home of these checks; every command goes through them.

* :func:`check_depth`: a floating equilibrium needs water under the keel, ``fluid.depth``
  greater than the draft. :func:`floatfoam.hydrostatics.theory.equilibrium` calls it, so every
  command that solves the equilibrium (theory, gz, potential, decay-model, mesh, run …)
  refuses a shallower fluid.
* :func:`check_release`: a decay test starts from the release
  (:func:`floatfoam.tank.pose`: the equilibrium displaced by the ``[release]``
  offsets), which must keep the body inside the case's tank
  (:func:`floatfoam.tank.tank`): above its bottom (``fluid.depth``, else
  ``domain.depth`` or its deep-water default) and below its top (``domain.air_height`` or its
  default). Every command that takes a release calls it before it computes or writes
  anything: decay-model (:func:`floatfoam.potential.models.decay_series`), run and the
  studies' checks (:func:`floatfoam.plan.release.release_state`), mesh at the release pose.
  One tank for all of them: a release the models accept is one the CFD can start from.

A body released wholly above the water is not refused: that is a drop, and a valid one —
lab_sphere_05D releases its sphere with the lowest point 0.06 mm above the still water (the
0.5 D drops of Kramer et al. 2021). Only the tank's top bounds it.
"""

from __future__ import annotations

import math

from floatfoam.bodies.geometry import rotation
from floatfoam.errors import InputError

BISECTIONS = 40  # halvings of a release angle's range: 2⁻⁴⁰ of it, well below a display digit


def vertical_extent(case, placement) -> tuple[float, float]:
    """z of the body's lowest and highest points in the earth frame at ``placement``
    (anything with z_c, heel and trim: an equilibrium or a pose), from its surface mesh;
    upright, the body's exact bounding box."""
    if placement.heel == 0.0 and placement.trim == 0.0:
        return (float(case.body.lo[2]) + placement.z_c,
                float(case.body.hi[2]) + placement.z_c)
    vertices, _ = case.body.surface_mesh()
    z = vertices @ rotation(placement.heel, placement.trim)[2]  # (v Rᵀ)_z = v · R[2]
    return float(z.min()) + placement.z_c, float(z.max()) + placement.z_c


def check_depth(case, eq) -> None:
    """Refuse a finite ``fluid.depth`` that does not exceed the draft at the equilibrium
    ``eq``: the body would rest on the bottom, not float. One line naming fluid.depth, its
    value and the draft it must exceed."""
    if not math.isfinite(case.depth):
        return
    draft = -min(vertical_extent(case, eq)[0], 0.0)
    if case.depth <= draft:
        raise InputError(f"fluid.depth = {case.depth:g} m: the body floats with its keel "
                         f"{draft:.4g} m below the still water (its draft), on or below the "
                         f"bottom; valid is a depth greater than the draft, {draft:.4g} m")


def check_release(case, eq):
    """The release pose of ``case`` from its equilibrium ``eq``, refused when it puts the body
    outside the tank (module docstring): one line naming the release key, its value, where the
    body then reaches and the key's valid range. A tank that does not hold the body even at
    equilibrium names the tank's key instead."""
    from floatfoam.tank import Pose, pose, tank

    box = tank(case)
    bottom, top = -box.depth, box.air_height
    released = pose(case, "release", eq)
    if _inside(case, released, bottom, top):
        return released
    at_rest = Pose(eq.z_c, eq.heel, eq.trim)
    low, high = vertical_extent(case, at_rest)
    if not low > bottom:  # fluid.depth is checked with the equilibrium: domain.depth here
        raise InputError(f"{_bottom_key(case, box)} puts the tank's bottom (z = {bottom:.4g} m) "
                         f"at or above the body's keel at equilibrium (z = {low:.4g} m); valid "
                         f"is a depth greater than {-low:.4g} m")
    if not high < top:
        raise InputError(f"{_top_key(case, box)} puts the tank's top (z = {top:.4g} m) at or "
                         f"below the body's top at equilibrium (z = {high:.4g} m); valid is an "
                         f"air height greater than {high:.4g} m")
    turned = Pose(eq.z_c, released.heel, released.trim)  # the release's attitude, no heave
    if _inside(case, turned, bottom, top):
        _refuse_heave(case, box, released, turned)
    _refuse_angles(case, box, at_rest, turned)


def _inside(case, where, bottom: float, top: float) -> bool:
    low, high = vertical_extent(case, where)
    return low > bottom and high < top


def _where(case, box, where) -> str:
    """Which bound the body at ``where`` passes: the bottom or the top, with the key."""
    low, high = vertical_extent(case, where)
    if not low > -box.depth:
        return (f"the body's lowest point at z = {low:.4g} m, on or below the tank's bottom "
                f"(z = {-box.depth:.4g} m: {_bottom_key(case, box)})")
    return (f"the body's top at z = {high:.4g} m, at or above the tank's top "
            f"(z = {box.air_height:.4g} m: {_top_key(case, box)})")


def _refuse_heave(case, box, released, turned) -> None:
    """The heave alone takes the body out: its valid range at the release's attitude."""
    low, high = vertical_extent(case, turned)
    lowest, highest = -box.depth - low, box.air_height - high  # offsets to each bound
    raise InputError(f"release.heave = {case.release['heave']:g} m puts "
                     f"{_where(case, box, released)}; valid is {lowest:.4g} < heave < "
                     f"{highest:.4g} m (the body inside the tank)")


def _refuse_angles(case, box, at_rest, turned) -> None:
    """The release's heel and trim take the body out even without its heave: the largest
    fraction of them (both scaled together) that keeps it in, by bisection from the
    equilibrium attitude (inside) towards the release's (outside)."""
    from floatfoam.tank import Pose

    def at(fraction):
        return Pose(at_rest.z_c, at_rest.heel + fraction * (turned.heel - at_rest.heel),
                    at_rest.trim + fraction * (turned.trim - at_rest.trim))

    inside, outside = 0.0, 1.0
    for _ in range(BISECTIONS):
        middle = 0.5 * (inside + outside)
        if _inside(case, at(middle), -box.depth, box.air_height):
            inside = middle
        else:
            outside = middle
    keys = [k for k in ("heel", "trim") if case.release[k]]
    given = ", ".join(f"release.{k} = {case.release[k]:g}°" for k in keys)
    limits = " and ".join(f"{k} {inside * case.release[k]:+.4g}°" for k in keys)
    both = " (both scaled together)" if len(keys) > 1 else ""
    raise InputError(f"{given} puts {_where(case, box, turned)}; valid from the equilibrium "
                     f"attitude is up to {limits} that way{both}, which keeps the body inside "
                     "the tank")


def _bottom_key(case, box) -> str:
    """The key that sets the tank's bottom, and its value."""
    from floatfoam.tank import DOMAIN_DEFAULTS

    if math.isfinite(case.depth):
        return f"fluid.depth = {case.depth:g} m"
    if case.settings.domain.depth is not None:
        return f"domain.depth = {box.depth:g} m"
    return (f"domain.depth's default when fluid.depth is infinite, "
            f"{DOMAIN_DEFAULTS['deep_depth']:g} × the body's span")


def _top_key(case, box) -> str:
    """The key that sets the tank's top, and its value."""
    from floatfoam.tank import DOMAIN_DEFAULTS

    if case.settings.domain.air_height is not None:
        return f"domain.air_height = {box.air_height:g} m"
    return f"domain.air_height's default, {DOMAIN_DEFAULTS['air_height']:g} × the body's span"

