"""Le Barbier's formulas evaluated for a case, beside the exact theory, two ways.

* :func:`memoir_values`: the memoir's method (:mod:`floatfoam.hydrostatics.memoir`, derived
  again by hand in docs/memoir.md, ``source = "reconstructed"``). These are the *corrected*
  formulas: where the print is right they equal it, where it is wrong they do not.
* :func:`memoir_printed_values`: the formulas as printed (:mod:`floatfoam.hydrostatics.printed`
  and :mod:`~floatfoam.hydrostatics.printed_ellipsoid`, ``source = "printed"``), errata
  included, for the exact theory's draft H and KG, the case's mass M and gyradius about x.
"""

from __future__ import annotations

import math

from floatfoam.hydrostatics import memoir
from floatfoam.hydrostatics import printed as pr
from floatfoam.hydrostatics import printed_ellipsoid as pe
from floatfoam.hydrostatics.verdict import verdict

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
    match body.memoir_family:
        case ("circle", a):
            out = memoir.circular_cylinder(a, ratio, kg, k_roll, length=body.length, **physics)
        case ("conic", n, m):
            out = memoir.conic_cylinder(n, m, draft, kg, k_roll, length=body.length, **physics)
        case ("sphere", a):
            out = memoir.sphere(a, ratio, kg, k_roll, **physics)
        case ("revolution", a, c):
            out = memoir.ellipsoid_of_revolution(a, c, ratio, kg, k_roll, **physics)
        case _:
            return {}
    values = {ours: out[theirs] for ours, theirs in KEYS.items() if theirs in out}
    values["source"] = out.get("source")
    values["reference"] = out.get("reference")
    return values


def memoir_printed_values(case, *, kg: float, draft: float) -> dict:
    """The memoir's formulas *as printed* where it covers the body (G on the vertical axis;
    circular and conic cylinders, the sphere, the ellipsoid of revolution), else {}.

    Keys: ``draft`` and ``KG`` (the exact theory's, the memoir's H and h), ``waterplane_area``
    (as printed), ``heave_period`` and ``roll_period`` (2 pi / sqrt(Omega) of the printed
    Omega; None unless the printed criterion says it oscillates and Omega > 0),
    ``KG_limit_roll`` (the printed criterion's limit on KG), ``GM_roll`` (the criterion's
    margin, KG_limit_roll - KG: for the ellipsoid of revolution this is *not* g GM / K^2 of the
    printed Omega, which the print gets wrong separately), ``verdict_roll``, ``source``
    ("printed"), ``reference``, ``pages`` (the pages and equations used), ``criterion`` (the
    criterion's page) and ``errata`` (the wrong formulas used, empty when all are right).
    """
    body = case.body
    if abs(case.cog[0]) > 0 or abs(case.cog[1]) > 0:
        return {}
    args = {"kg": kg, "gyradius": float(case.gyradius[0]), "mass": case.mass,
            "rho": case.rho, "g": case.g}
    match body.memoir_family:
        case ("circle", a):
            out = _circle(a, draft, length=body.length, **args)
        case ("conic", n, m):
            out = _conic(n, m, draft, length=body.length, **args)
        case ("sphere", a):
            out = _sphere(float(a), draft, **args)
        case ("revolution", a, c):
            out = _revolution(float(a), float(c), draft, **args)
        case _:
            return {}
    out["GM_roll"] = out["KG_limit_roll"] - kg
    out["verdict_roll"] = verdict(out["GM_roll"], body.size)
    omega2_roll = out.pop("omega2_roll")
    out["roll_period"] = pr.period(omega2_roll) if out["verdict_roll"] == "oscillates" else None
    out.update(draft=draft, KG=kg, source="printed", reference=f"{pr.REFERENCE}: {out['pages']}")
    return out


def _circle(a, H, *, length, kg, gyradius, mass, rho, g) -> dict:
    physics = {"length": length, "rho": rho, "g": g}
    return {"waterplane_area": 2 * length * math.sqrt(H * (2 * a - H)),
            "heave_period": pr.period(pr.eq9_circle_heave_omega2(a, H, mass, **physics)),
            "omega2_roll": pr.eq10_circle_roll_omega2(a, H, kg, gyradius, mass, **physics),
            "KG_limit_roll": pr.p53_circle_sphere_kg_limit(a), "errata": [],
            "pages": "p. 48 eqs (9)-(10); criterion p. 53", "criterion": "p. 53"}


def _conic(n, m, H, *, length, kg, gyradius, mass, rho, g) -> dict:
    """Cylinder on y^2 = n x + m x^2: heave p. 49, roll p. 50 with the p. 51 closed form for the
    ellipse. For the parabola and the hyperbola the memoir prints no closed form ("par les
    méthodes connues"): the integrals are the exact ones of closed_forms.conic_integrals."""
    from floatfoam.hydrostatics.closed_forms import conic_integrals

    if m < 0:
        def pi_og(h):
            return 2 * length * pr.p51_ellipse_moment(n, -m, H, h)
        pages = "heave p. 49; roll p. 50 with the ellipse integral of p. 51"
    else:
        i0, i1, _ = conic_integrals(n, m, H)

        def pi_og(h):
            return pr.p50_cylinder_pi_og(i1, i0, h, length=length)
        pages = "heave p. 49; roll p. 50"
    half_breadth = math.sqrt(n * H + m * H * H)
    wedge = pr.p50_cylinder_wedge_moment(half_breadth, length=length)
    # Pi.OG + Pp is linear in h: the criterion's limit is its zero (the sign of Omega, p. 50).
    at0, at1 = pi_og(0.0) + wedge, pi_og(1.0) + wedge
    physics = {"rho": rho, "g": g}
    return {"waterplane_area": 2 * length * half_breadth,
            "heave_period": pr.period(pr.p49_conic_heave_omega2(n, m, H, mass, length=length,
                                                                **physics)),
            "omega2_roll": pr.p50_roll_omega2(pi_og(kg), wedge, gyradius, mass, **physics),
            "KG_limit_roll": at0 / (at0 - at1), "errata": [], "pages": pages,
            "criterion": "p. 50 (sign of Omega)"}


def _sphere(a, H, *, kg, gyradius, mass, rho, g) -> dict:
    return {"waterplane_area": math.pi * (a * a - (a - H) ** 2),
            "heave_period": pr.period(pr.p52_sphere_heave_omega2(a, H, mass, rho=rho, g=g)),
            "omega2_roll": pr.p52_sphere_roll_omega2(a, H, kg, gyradius, mass, rho=rho, g=g),
            "KG_limit_roll": pr.p53_circle_sphere_kg_limit(a), "errata": [],
            "pages": "p. 52; criterion p. 53", "criterion": "p. 53"}


def _revolution(a, c, H, *, kg, gyradius, mass, rho, g) -> dict:
    area = pe.p58_ellipsoid_waterplane_area(a, a, c, H)
    return {"waterplane_area": area,
            "heave_period": pr.period(pe.eq12_heave_omega2(area, mass, rho=rho, g=g)),
            "omega2_roll": pe.p60_revolution_roll_omega2_as_printed(a, c, H, kg, gyradius, mass,
                                                                    rho=rho, g=g),
            "KG_limit_roll": pe.p61_revolution_kg_limit_as_printed(a, c, H),
            "errata": ["p. 60 roll formula", "pp. 60-61 stability criterion"],
            "pages": "eq. (12) and A p. 58 (heave); roll p. 60; criterion pp. 60-61",
            "criterion": "pp. 60-61"}
