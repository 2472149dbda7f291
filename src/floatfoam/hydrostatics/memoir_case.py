"""Le Barbier's formulas (:mod:`floatfoam.hydrostatics.memoir`) evaluated for a case, beside
the exact theory.

The stored copies of the memoir have its formulas stripped (docs/memoir.md): the values are
what the memoir's method gives ("reconstructed"), flagged so in the output.
"""

from __future__ import annotations

from floatfoam.bodies.shapes import ConicCylinder, Ellipsoid, EllipticCylinder
from floatfoam.hydrostatics import memoir

# theory key <- memoir key
KEYS = {"draft": "draft", "waterplane_area": "waterplane_area", "KB": "kb", "KG": "kg",
        "BM_roll": "bm", "GM_roll": "gm", "heave_period": "heave_period",
        "roll_period": "roll_period", "verdict_roll": "verdict_roll"}


def memoir_values(case, *, kg: float, draft: float) -> dict:
    """Values of the memoir's formulas where it covers the body (G on the vertical axis),
    else {}, for the exact theory's KG and draft. Keys as in
    :meth:`floatfoam.hydrostatics.summary.TheorySummary.to_dict`, plus ``source`` and
    ``reference``."""
    body = case.body
    if abs(case.cog[0]) > 0 or abs(case.cog[1]) > 0:
        return {}
    k_roll = float(case.gyradius[0])
    physics = {"rho": case.rho, "g": case.g}
    ratio = case.mass / (case.rho * body.volume())
    if isinstance(body, EllipticCylinder):
        if body.b == body.c:
            out = memoir.circular_cylinder(body.b, ratio, kg, k_roll, length=body.length,
                                           **physics)
        else:
            n, m = 2 * body.b**2 / body.c, -(body.b**2) / body.c**2
            out = memoir.conic_cylinder(n, m, draft, kg, k_roll,
                                        length=body.length, **physics)
    elif isinstance(body, ConicCylinder):
        out = memoir.conic_cylinder(body.n, body.m, draft, kg, k_roll,
                                    length=body.length, **physics)
    elif isinstance(body, Ellipsoid) and body.axes[0] == body.axes[1]:
        a, c = body.axes[0], body.axes[2]
        if a == c:
            out = memoir.sphere(a, ratio, kg, k_roll, **physics)
        else:
            out = memoir.ellipsoid_of_revolution(a, c, ratio, kg, k_roll, **physics)
    else:
        return {}
    values = {ours: out[theirs] for ours, theirs in KEYS.items() if theirs in out}
    values["source"] = out.get("source")
    values["reference"] = out.get("reference")
    return values
