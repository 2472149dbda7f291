"""Le Barbier (1817) as printed: the cylinders (circle, conic bases) and the sphere.

Each function evaluates one formula of the memoir exactly as it is printed, named by its page
and equation; :mod:`floatfoam.hydrostatics.printed_ellipsoid` does the same for equations (11)-(12)
and the ellipsoid. Where the print is wrong, a function without the ``_as_printed`` suffix
gives the corrected expression beside it. :mod:`floatfoam.hydrostatics.memoir` holds the
memoir's *method*, derived again from first principles (the corrected values throughout).

Source: Le Barbier, "Essai sur les oscillations et l'équilibre des corps flottans", Annales de
mathématiques pures et appliquées (Gergonne) 8 (1817-1818) 37-61, read in an OCR transcription
of the numdam scan AMPA_1817-1818__8__37_0. Page numbers are the printed ones. The
transcription garbles some symbols; each docstring gives the reading chosen and why, and
docs/memoir.md gives the errata table.

Notation (memoir -> floatfoam, docs/conventions.md): H = h + f, the immersion ("enfoncement"),
is ``draft``; h = OD, the height of the centre of gravity O above the keel D, is ``kg``; a is
the radius; n, m the conic base y**2 = n x + m x**2, x up from the vertex (the keel); L the
``length`` of a cylinder; M, M K**2 the ``mass`` and the inertia about the rotation axis
through O (``gyradius`` K); Pi.OG = V (KB - KG), Pi being the displaced volume and OG the
distance from O up to the centre of buoyancy; Pp the heeling wedge's first moment per unit
angle (= the waterplane's second moment I_wp); rho the fluid's density; g gravity.

Every ``*_omega2`` is the Omega of the memoir's solution eps cos(t sqrt(Omega) + eps'); the
memoir gives no pendulum lengths. It keeps M and rho apart, so ``mass`` is an argument
(M = rho V at equilibrium, p. 37).
"""

from __future__ import annotations

import math

from floatfoam.errors import InputError, number

REFERENCE = ("Le Barbier, Ann. math. pures appl. 8 (1817-1818) 37-61, as printed "
             "(numdam AMPA_1817-1818__8__37_0)")


def period(omega2: float) -> float | None:
    """Period 2 pi / sqrt(Omega) of eps cos(t sqrt(Omega) + eps'), s; None when Omega <= 0
    (the body stays put or capsizes). Omega in rad^2/s^2."""
    return 2.0 * math.pi / math.sqrt(omega2) if omega2 > 0 else None


def positive(value, name: str) -> float:
    """``value`` as a float > 0, else an InputError naming ``name``."""
    return number(value, name, minimum=0.0)


def draft_below(draft, top: float, what: str) -> float:
    """The immersion H as a float in (0, top), else an InputError naming the limit."""
    H = positive(draft, "draft")
    if H >= top:
        raise InputError(f"draft = {draft!r}: must be below {what} = {top!r}")
    return H


def stiffness_factor(mass, gyradius, rho, g) -> float:
    """g rho / (M K^2), the factor in front of every printed rotation formula."""
    return g * rho / (positive(mass, "mass") * positive(gyradius, "gyradius") ** 2)


# ------------------------------------------------------ circular cylinder, p. 48, eqs (9)-(10)

def eq9_circle_heave_omega2(radius, draft, mass, *, length=1.0, rho=1000.0, g=9.81) -> float:
    """Heave of a horizontal circular cylinder, eq. (9) as printed.

        Omega = 2 g rho L sqrt(H (2a - H)) / M

    Parameters
    ----------
    radius, draft : float
        a and H, m (0 < H < 2a).
    mass : float
        M, kg, for the length L.
    length, rho, g : float
        L (m), fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2.

    References
    ----------
    p. 48, eq. (9). Right: 2 L sqrt(H (2a - H)) is the waterplane area, Omega = g rho A_wp / M.
    """
    a = positive(radius, "radius")
    H = draft_below(draft, 2.0 * a, "the diameter 2a")
    return 2.0 * g * rho * length * math.sqrt(H * (2.0 * a - H)) / positive(mass, "mass")


def eq10_circle_roll_omega2(radius, draft, kg, gyradius, mass, *, length=1.0, rho=1000.0,
                            g=9.81) -> float:
    """Roll of a horizontal circular cylinder, eq. (10) as printed.

        Omega = (a^2 g rho L / (M K^2)) [(H - a) sqrt(H (2a - H)) / a^2
                                         + arcsin((H - a) / a) + pi/2] (a - h)

    Parameters
    ----------
    radius, draft, kg, gyradius : float
        a, H, h (= KG) and K, m.
    mass : float
        M, kg, for the length L.
    length, rho, g : float
        L (m), fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2; negative when h > a (the body capsizes).

    References
    ----------
    p. 48, eq. (10). The transcription prints psi (the tangent angle of p. 46) on the left
    where theta is meant, and eps_1 for the phase eps_1'; both typographical. Right: the
    bracket is the immersed segment's area over a^2, so Omega = g rho V (a - KG) / (M K^2),
    the circle's metacentre being its centre.
    """
    a = positive(radius, "radius")
    H = draft_below(draft, 2.0 * a, "the diameter 2a")
    h = number(kg, "kg")
    bracket = (H - a) * math.sqrt(H * (2 * a - H)) / a**2 + math.asin((H - a) / a) + math.pi / 2
    return a * a * length * stiffness_factor(mass, gyradius, rho, g) * bracket * (a - h)


def p51_circle_roll_omega2(radius, draft, kg, gyradius, mass, *, length=1.0, rho=1000.0,
                           g=9.81) -> float:
    """Roll of the circular cylinder by the second method (p. 51), as printed.

        Omega = (a^2 g rho L / (M K^2)) [(H - a) sqrt(H (2a - H)) / a^2
                                         + 2 arctan sqrt(H / (2a - H))] (a - h)

    Parameters and return value as :func:`eq10_circle_roll_omega2`.

    References
    ----------
    p. 51 (transcribed "t = 1/2 Cos", OCR for theta = eps_1 Cos). Right: equals eq. (10).
    """
    a = positive(radius, "radius")
    H = draft_below(draft, 2.0 * a, "the diameter 2a")
    h = number(kg, "kg")
    bracket = ((H - a) * math.sqrt(H * (2 * a - H)) / a**2
               + 2.0 * math.atan(math.sqrt(H / (2 * a - H))))
    return a * a * length * stiffness_factor(mass, gyradius, rho, g) * bracket * (a - h)


def p51_arc_identity_as_printed(radius, draft) -> float:
    """Right side of the identity printed on p. 51 to show that the two methods agree:

        2 arctan sqrt(H / (2a - H)) = pi/2 + arcsin((H - a) / H)

    Parameters
    ----------
    radius, draft : float
        a and H, m.

    Returns
    -------
    float
        pi/2 + arcsin((H - a) / H), rad.

    References
    ----------
    p. 51. Wrong: (H - a)/H must be (H - a)/a, as in eq. (10); the two agree only at H = a
    (every project case with a circle is half immersed, so the slip is invisible there).
    Undefined for H < a/2. See :func:`arc_identity`.
    """
    a = positive(radius, "radius")
    H = draft_below(draft, 2.0 * a, "the diameter 2a")
    if H < a / 2:
        raise InputError(f"draft = {draft!r}: the printed identity needs H >= a/2 = {a / 2!r} "
                         "(arcsin of (H - a)/H)")
    return math.pi / 2 + math.asin((H - a) / H)


def arc_identity(radius, draft) -> float:
    """Corrected p. 51 identity: 2 arctan sqrt(H / (2a - H)) = pi/2 + arcsin((H - a) / a)."""
    a = positive(radius, "radius")
    H = draft_below(draft, 2.0 * a, "the diameter 2a")
    return math.pi / 2 + math.asin((H - a) / a)


def p53_circle_sphere_kg_limit(radius) -> float:
    """The p. 53 criterion for the circular cylinder and the sphere: the body oscillates, stays
    or capsizes as h <, =, > a, so the limit on KG is the radius.

    References
    ----------
    p. 53, in words. Right: h = OD is the height of G above the keel (KG), and KM = a.
    """
    return positive(radius, "radius")


# ------------------------------------------- cylinders on conic bases, pp. 49-51 (2nd method)

def p49_conic_heave_omega2(n, m, draft, mass, *, length=1.0, rho=1000.0, g=9.81) -> float:
    """Heave of a cylinder on the conic base y^2 = n x + m x^2, as printed.

        Omega = 2 g rho L sqrt(H (n + m H)) / M

    Parameters
    ----------
    n, m : float
        Conic coefficients (n in m, m dimensionless); n = 2a, m = -1 is the circle.
    draft, mass : float
        H (m), M (kg, for the length L).
    length, rho, g : float
        L (m), fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2.

    References
    ----------
    p. 49, unnumbered. Transcribed "2 g L V sqrt(...)": V is OCR for rho, and the amplitude
    eps is dropped. Right: 2 L sqrt(H (n + m H)) is the waterplane area (the "prism" of p. 49).
    """
    H = positive(draft, "draft")
    half_breadth2 = positive(n, "n") * H + number(m, "m") * H * H
    if half_breadth2 <= 0.0:
        raise InputError(f"draft = {draft!r}: above the top of the conic section")
    return 2.0 * g * rho * length * math.sqrt(half_breadth2) / positive(mass, "mass")


def p50_cylinder_wedge_moment(half_breadth, *, length=1.0) -> float:
    """Pp of a cylinder, as printed: the wedge u = P theta = 2 L y^2 theta with its lever
    p = y/3, so Pp = (2/3) L y^3 (m^4), y the waterline half-breadth (m), L the length (m).

    References: p. 50. Right: (2/3) L y^3 = L (2y)^3 / 12, the waterplane's second moment.
    """
    return 2.0 / 3.0 * length * positive(half_breadth, "half_breadth") ** 3


def p50_cylinder_pi_og(int_xy, int_y, kg, *, length=1.0) -> float:
    """Pi.OG = 2 L (int_0^H x y dx - h int_0^H y dx) for a cylinder of half-breadth y(x).

    Parameters
    ----------
    int_xy, int_y : float
        int_0^H x y dx (m^3) and int_0^H y dx (m^2), x up from the keel.
    kg : float
        h, m.
    length : float
        L, m.

    Returns
    -------
    float
        Pi.OG = V (KB - KG), m^4.

    References
    ----------
    p. 50 (with OG = f - 2L int y (H - x) dx / Pi). Right.
    """
    return 2.0 * length * (number(int_xy, "int_xy") - number(kg, "kg") * number(int_y, "int_y"))


def p50_roll_omega2(pi_og, wedge_moment, gyradius, mass, *, rho=1000.0, g=9.81) -> float:
    """Roll of a body with a plane of symmetry by the second method, as printed.

        Omega = g rho (Pi.OG + Pp) / (M K^2)

    Parameters
    ----------
    pi_og, wedge_moment : float
        Pi.OG and Pp, m^4.
    gyradius, mass : float
        K (m), M (kg).
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2; its sign is the verdict (oscillates, stays, capsizes).

    References
    ----------
    p. 50, unnumbered (transcribed "theta = 1/Cos{...}", OCR for theta = eps_1 Cos{...}; the
    lever rule "Pi : a :: PF : OP" before it is inverted, but the OP it yields is right).
    Right: Pi.OG + Pp = V (KB - KG) + I_wp = V GM.
    """
    return (stiffness_factor(mass, gyradius, rho, g)
            * (number(pi_og, "pi_og") + number(wedge_moment, "wedge_moment")))


def p51_ellipse_moment(n51, m51, draft, kg) -> float:
    """int_0^H x y dx - h int_0^H y dx for the ellipse y^2 = n x - m x^2, the memoir's closed
    form. With z = sqrt(H / (n/m - H)):

        n^2 / (24 m^(3/2) (1 + z^2)^3) {3 [z^5 - z + (1 + z^2)^3 arctan z] (n/m - 2h)
                                        - 8 (n/m) z^3}

    Parameters
    ----------
    n51, m51 : float
        Coefficients in the p. 51 convention y^2 = n x - m x^2 (m > 0; the circle of radius a is
        n = 2a, m = 1). The general conic's m (p. 46) is -m51.
    draft, kg : float
        H and h, m (0 < H < n/m, the height of the ellipse).

    Returns
    -------
    float
        m^3; 2 L times it is Pi.OG (:func:`p50_cylinder_pi_og`).

    References
    ----------
    p. 51. Ambiguous print, right with the reading chosen: the transcription has the
    exponents m^(1/2) and (1 + z^2)^(3/2); only m^(3/2) and (1 + z^2)^3 make the expression
    the integral (its dimensions need m^(3/2); on the elliptic_cylinder case the transcribed
    exponents give -3.18e-3 m^3 against -5.0e-4). The circle (m = 1) cannot tell the two apart.
    """
    n, m = positive(n51, "n51"), positive(m51, "m51")
    H = draft_below(draft, n / m, "the height of the ellipse n/m")
    h = number(kg, "kg")
    z = math.sqrt(H / (n / m - H))
    q = 1.0 + z * z
    return n * n / (24.0 * m**1.5 * q**3) * (
        3.0 * (z**5 - z + q**3 * math.atan(z)) * (n / m - 2.0 * h) - 8.0 * n / m * z**3)


# ----------------------------------------------------------------------- sphere, pp. 52-53

def p52_sphere_heave_omega2(radius, draft, mass, *, rho=1000.0, g=9.81) -> float:
    """Heave of a floating sphere, as printed: Omega = g rho pi [a^2 - (a - H)^2] / M.

    Parameters
    ----------
    radius, draft, mass : float
        a (m), H (m, 0 < H < 2a), M (kg).
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2.

    References
    ----------
    p. 52. Ambiguous print: the factor is transcribed "rho p^inf / M", read g rho pi / M (the
    dimensions need g; pi [a^2 - (a - H)^2] is the waterplane disc). Right with that reading.
    """
    a = positive(radius, "radius")
    H = draft_below(draft, 2.0 * a, "the diameter 2a")
    return g * rho * math.pi * (a * a - (a - H) ** 2) / positive(mass, "mass")


def p52_sphere_roll_omega2(radius, draft, kg, gyradius, mass, *, rho=1000.0, g=9.81) -> float:
    """Roll (= pitch) of a floating sphere, as printed.

        Omega = (g rho pi / (3 M K^2)) [(H - a)(3a^2 - (H - a)^2) + 2a^3] (a - h)

    Parameters
    ----------
    radius, draft, kg, gyradius : float
        a, H, h (= KG) and K, m.
    mass : float
        M, kg.
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2; negative when h > a.

    References
    ----------
    p. 52. Ambiguous print of the factor, read g rho pi as for the heave. Right: the bracket is
    H^2 (3a - H) = 3 V / pi, and KM = a (the buoyancy passes through the centre, p. 52).
    """
    a = positive(radius, "radius")
    H = draft_below(draft, 2.0 * a, "the diameter 2a")
    h = number(kg, "kg")
    bracket = (H - a) * (3 * a * a - (H - a) ** 2) + 2 * a**3
    return math.pi / 3.0 * stiffness_factor(mass, gyradius, rho, g) * bracket * (a - h)
