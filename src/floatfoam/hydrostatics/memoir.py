"""Le Barbier (1817): small free oscillations and stability of floating bodies, body by body.

Source: Le Barbier, "Essai sur les oscillations et l'équilibre des corps flottans", Annales de
mathématiques pures et appliquées (Gergonne) 8 (1817-1818) 37 ff. Page numbers below are the
printed ones; the Wikisource scan page is printed page + 6 (p. 48 = djvu/54).

These functions evaluate the results of the memoir's *stated method* (linearised hydrostatics
without the fluid's resistance or inertia, docs/memoir.md section 2), derived again here: they
are the *corrected* formulas. Each result says so: ``source == "reconstructed"`` and
``verified_against_print is False`` (this module is not the print). The formulas as printed,
errata included, are in :mod:`floatfoam.hydrostatics.printed` and
:mod:`~floatfoam.hydrostatics.printed_ellipsoid`; where the print is right (circle, conic
cylinders, sphere) they agree with these functions to round-off; where it is wrong (the
ellipsoid of revolution, pp. 60-61) these give the corrected values (docs/memoir.md, errata).

Linear theory used throughout (the body's mass M equals the displaced mass rho*V):

    heave:  omega_h**2 = g * rho * A_wp / M = g * A_wp / V
    roll:   omega_r**2 = g * rho * V * GM / (M * K**2) = g * GM / K**2,  GM = KB + BM - KG

K is the radius of gyration about the roll axis through G. Horizontal cylinders are prisms of
length ``length`` along x (docs/conventions.md); periods do not depend on it.
"""

from __future__ import annotations

import math

import numpy as np

from floatfoam.errors import InputError, number
from floatfoam.hydrostatics.roots import brentq
from floatfoam.hydrostatics.verdict import verdict as neutral_verdict

_x, _w = np.polynomial.legendre.leggauss(48)
GAUSS_NODES, GAUSS_WEIGHTS = 0.5 * (_x + 1.0), 0.5 * _w  # on [0, 1]
REFERENCE = "Le Barbier, Ann. math. pures appl. 8 (1817-1818) 37 ff."


def _positive(name: str, value) -> float:
    return number(value, name, minimum=0.0)


def _density_ratio(value) -> float:
    number_ = number(value, "density_ratio")
    if not 0.0 < number_ < 1.0:
        raise InputError(f"density_ratio = {value!r}: must lie strictly between 0 and 1 "
                         "(rho_body / rho_fluid of a floating body)")
    return number_


def _linear_result(*, draft, section_or_volume, length, breadth_or_area, kb, bm, kg, gyradius,
                   size, rho, g, ref) -> dict:
    """Assemble the common result dict from the hydrostatic quantities of one body."""
    volume = section_or_volume * length
    waterplane_area = breadth_or_area * length
    km = kb + bm
    gm = km - kg
    verdict = neutral_verdict(gm, size)
    omega_h = math.sqrt(g * waterplane_area / volume)
    roll_period = None
    if verdict == "oscillates":
        roll_period = 2.0 * math.pi * gyradius / math.sqrt(g * gm)
    return {
        "draft": draft, "volume": volume, "mass": rho * volume,
        "waterplane_area": waterplane_area, "kb": kb, "bm": bm, "km": km, "kg": kg, "gm": gm,
        "heave_period": 2.0 * math.pi / omega_h, "roll_period": roll_period,
        "verdict_roll": verdict,
        "source": "reconstructed", "verified_against_print": False,
        "reference": f"{REFERENCE} {ref}",
    }


def circular_cylinder(radius: float, density_ratio: float, kg: float, gyradius: float, *,
                      length: float = 1.0, rho: float = 1000.0, g: float = 9.81) -> dict:
    """Horizontal circular cylinder: heave, roll and capsize verdict (memoir eqs (9), (10)).

    With alpha the half-angle of the immersed arc, ``alpha - sin(alpha) cos(alpha) =
    pi * density_ratio``, draft T = a (1 - cos alpha), waterline breadth B = 2 a sin(alpha),
    section A = a**2 (alpha - sin alpha cos alpha),
    KB = a - 4 a sin(alpha)**3 / (3 (2 alpha - sin 2 alpha)), BM = B**3 / (12 A), so KM = a
    for every draft (the buoyancy always passes through the centre).

        omega_h**2 = g B / A,    omega_r**2 = g (a - KG) / K**2.

    Source: p. 48 (djvu/54), eqs (9) and (10), linearised from (7)-(8); verdict in words on
    p. 53 (djvu/59): oscillates, stays or capsizes as the height of G is below, at or above the
    radius. Derived here; the printed (9), (10) and the p. 53 criterion agree
    (:mod:`floatfoam.hydrostatics.printed`).

    Parameters
    ----------
    radius : float
        a, m.
    density_ratio : float
        rho_body / rho_fluid, in (0, 1).
    kg : float
        Height of G above the keel, m.
    gyradius : float
        K, radius of gyration about the cylinder's axis through G, m.
    length, rho, g : float
        Prism length (m), fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    dict
        draft, volume, mass, waterplane_area, kb, bm, km, kg, gm, heave_period, roll_period
        (None unless it oscillates), verdict_roll, source, verified_against_print, reference.
    """
    a, s = _positive("radius", radius), _density_ratio(density_ratio)
    _positive("gyradius", gyradius)
    alpha = brentq(lambda t: t - math.sin(t) * math.cos(t) - math.pi * s, 0.0, math.pi,
                   xtol=1e-15)
    section = a * a * (alpha - math.sin(alpha) * math.cos(alpha))
    breadth = 2.0 * a * math.sin(alpha)
    kb = a - 4.0 * a * math.sin(alpha) ** 3 / (3.0 * (2.0 * alpha - math.sin(2.0 * alpha)))
    return _linear_result(draft=a * (1.0 - math.cos(alpha)), section_or_volume=section,
                          length=length, breadth_or_area=breadth, kb=kb,
                          bm=breadth**3 / (12.0 * section), kg=kg, gyradius=gyradius, size=a,
                          rho=rho, g=g, ref="p. 48 eqs (9)-(10); verdict p. 53")


def conic_kind(n: float, m: float) -> str:
    """Name of the base curve y**2 = n x + m x**2 (x up from the vertex): p. 50-51 (djvu/56-57)."""
    if m < 0:
        return "circle" if math.isclose(m, -1.0) else "ellipse"
    return "parabola" if m == 0 else "hyperbola"


def conic_cylinder(n: float, m: float, draft: float, kg: float, gyradius: float, *,
                   length: float = 1.0, rho: float = 1000.0, g: float = 9.81) -> dict:
    """Horizontal cylinder on a conic base y**2 = n x + m x**2, vertex down (pp. 50-51).

    x is the height above the keel (the vertex), y the half-breadth. m < 0: ellipse of half
    beam b and half height c for n = 2 b**2 / c, m = -b**2 / c**2 (circle: n = 2a, m = -1),
    height -n/m; m = 0: parabola (latus rectum n); m > 0: hyperbola. Open curves are closed
    by a flat deck above the waterline, which does not enter the linear theory; the mass
    follows from equilibrium, M = rho A L. With draft T,

        A = 2 int_0^T y dx,  KB = 2 int_0^T x y dx / A,  B = 2 y(T),  BM = B**3 / (12 A),
        omega_h**2 = g B / A,  omega_r**2 = g (KB + BM - KG) / K**2.

    The integrals are evaluated after x = T s**2, which removes the square-root singularity at
    the vertex. Closed forms: parabola KB = 3T/5, BM = n/2, omega_h**2 = 3g/(2T); ellipse =
    circle of its vertical semi-axis stretched sideways (docs/memoir.md section 5).

    Source: general formula p. 50 (djvu/56), applied to ellipse and circle p. 51 (djvu/57).
    Derived here; the printed pp. 49-51 formulas agree.

    Parameters
    ----------
    n, m : float
        Coefficients of the base curve; n in m, m dimensionless; n > 0.
    draft : float
        T, m; below the top of a closed (elliptic) section.
    kg, gyradius : float
        Height of G above the keel and radius of gyration about the axis through G, m.
    length, rho, g : float
        Prism length (m), fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    dict
        As :func:`circular_cylinder`, plus ``conic``.
    """
    n, T = _positive("n", n), _positive("draft", draft)
    _positive("gyradius", gyradius)
    if m < 0 and T >= -n / m:
        raise InputError(f"draft = {draft!r}: must be below the top of the elliptic section, "
                         f"-n/m = {-n / m!r}")

    def half_width_integral(power: int) -> float:  # int_0^T x**(power) y dx, with x = T s**2
        # s = 1 - w**2 makes the integrand analytic in w even when the draft reaches the top
        # of an ellipse (n + m T = 0); 48 Gauss-Legendre nodes then agree with adaptive
        # quadrature (scipy's quad, epsrel 1e-13) to 5e-15 relative on the project's conics.
        w = GAUSS_NODES
        s = 1.0 - w * w
        f = s ** (2 + 2 * power) * np.sqrt(np.maximum(n + m * T * s * s, 0.0)) * 2.0 * w
        return 2.0 * T ** (1.5 + power) * float(GAUSS_WEIGHTS @ f)

    half_area = half_width_integral(0)
    section = 2.0 * half_area
    breadth = 2.0 * math.sqrt(n * T + m * T * T)
    out = _linear_result(draft=T, section_or_volume=section, length=length,
                         breadth_or_area=breadth, kb=half_width_integral(1) / half_area,
                         bm=breadth**3 / (12.0 * section), kg=kg, gyradius=gyradius,
                         size=max(T, breadth), rho=rho, g=g, ref="pp. 50-51")
    out["conic"] = conic_kind(n, m)
    return out


def _cap_draft(density_ratio: float) -> float:
    """t = T/c of a sphere (or spheroid) immersed to volume fraction s: t**2 (3 - t) = 4 s."""
    s = _density_ratio(density_ratio)
    return brentq(lambda t: t * t * (3.0 - t) - 4.0 * s, 0.0, 2.0, xtol=1e-15)


def sphere(radius: float, density_ratio: float, kg: float, gyradius: float, *,
           rho: float = 1000.0, g: float = 9.81) -> dict:
    """Floating sphere: heave, roll (= pitch) and capsize verdict (p. 52, djvu/58).

    Draft from T**2 (3a - T) = 4 s a**3; V = pi T**2 (3a - T) / 3; waterplane radius
    r**2 = T (2a - T); KB = a - 3 (2a - T)**2 / (4 (3a - T)); BM = pi r**4 / (4 V); KM = a.

        omega_h**2 = g pi r**2 / V = 3 g (2a - T) / (T (3a - T)),
        omega_r**2 = g (a - KG) / K**2.

    Source: p. 52 (djvu/58), same notation as the cylinder; verdict in words p. 53 (djvu/59).
    Derived here; the printed p. 52 formulas and the p. 53 criterion agree.

    Parameters
    ----------
    radius, density_ratio, kg, gyradius : float
        a (m), rho_body / rho_fluid in (0, 1), height of G above the keel (m), radius of
        gyration about a horizontal axis through G (m).
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    dict
        As :func:`circular_cylinder` (``volume`` and areas for the whole sphere).
    """
    return _spheroid(_positive("radius", radius), _positive("radius", radius), density_ratio,
                     kg, gyradius, rho=rho, g=g, ref="p. 52; verdict p. 53")


def ellipsoid_of_revolution(a: float, c: float, density_ratio: float, kg: float,
                            gyradius: float, *, rho: float = 1000.0, g: float = 9.81) -> dict:
    """Ellipsoid of revolution, axis of revolution vertical: heave, roll, verdict (pp. 58-61).

    x**2/a**2 + y**2/a**2 + z**2/c**2 = 1 with c the vertical semi-axis (the memoir's
    vertical axis, p. 58) and a the equatorial one. It is a sphere of radius c stretched
    sideways by a/c, so T/c solves t**2 (3 - t) = 4 s, KB is the sphere's and BM is
    (a/c)**2 times the sphere's:

        KB = c - 3 (2c - T)**2 / (4 (3c - T)),   BM = (a**2/c**2) 3 (2c - T)**2 / (4 (3c - T)),
        KM - c = 3 (a**2 - c**2) (2c - T)**2 / (4 c**2 (3c - T)),
        omega_h**2 = 3 g (2c - T) / (T (3c - T)),   omega_r**2 = g (KM - KG) / K**2.

    An oblate body (a > c) has its metacentre above the centre, a prolate one below.

    Source: linearised equations (11)-(12), pp. 54-58; ellipsoid of revolution and its
    oscillate / stay / capsize criterion pp. 60-61. Derived here: these are the corrected
    formulas. The printed roll formula and criterion are wrong for a != c
    (:func:`floatfoam.hydrostatics.printed_ellipsoid.p60_revolution_roll_omega2_as_printed`,
    docs/memoir.md errata).

    Parameters
    ----------
    a, c : float
        Equatorial (horizontal) and polar (vertical) semi-axes, m.
    density_ratio, kg, gyradius : float
        rho_body / rho_fluid in (0, 1), height of G above the keel (m), radius of gyration
        about a horizontal axis through G (m).
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    dict
        As :func:`circular_cylinder`.
    """
    return _spheroid(_positive("a", a), _positive("c", c), density_ratio, kg, gyradius,
                     rho=rho, g=g, ref="eqs (11) pp. 57-58; criterion pp. 60-61")


def _spheroid(a, c, density_ratio, kg, gyradius, *, rho, g, ref) -> dict:
    _positive("gyradius", gyradius)
    T = c * _cap_draft(density_ratio)
    stretch = (a / c) ** 2
    volume = stretch * math.pi * T * T * (3.0 * c - T) / 3.0
    r2 = stretch * T * (2.0 * c - T)
    kb = c - 3.0 * (2.0 * c - T) ** 2 / (4.0 * (3.0 * c - T))
    return _linear_result(draft=T, section_or_volume=volume, length=1.0,
                          breadth_or_area=math.pi * r2, kb=kb,
                          bm=math.pi * r2 * r2 / (4.0 * volume), kg=kg, gyradius=gyradius,
                          size=max(a, c), rho=rho, g=g, ref=ref)


def ellipsoid_stability_limit(a: float, c: float, draft: float) -> float:
    """Height of G above the centre at which a floating spheroid is neutral: KM - c.

        KM - c = 3 (a**2 - c**2) (2c - T)**2 / (4 c**2 (3c - T)),   0 < T < 2c.

    The body oscillates, stays or capsizes as G's height above the centre is below, at or
    above this value (pp. 60-61). Derived here (docs/memoir.md section 7): the corrected
    criterion; the printed one is
    :func:`floatfoam.hydrostatics.printed_ellipsoid.p61_revolution_kg_limit_as_printed`.
    """
    a, c, T = _positive("a", a), _positive("c", c), _positive("draft", draft)
    if T >= 2.0 * c:
        raise InputError(f"draft = {draft!r}: must be below the top of the body, 2c = {2 * c!r}")
    return 3.0 * (a * a - c * c) * (2.0 * c - T) ** 2 / (4.0 * c * c * (3.0 * c - T))
