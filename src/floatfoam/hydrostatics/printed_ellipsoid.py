"""Le Barbier (1817) as printed: any body, equations (11)-(12), and the ellipsoid (pp. 53-61).

Notation and conventions as in :mod:`floatfoam.hydrostatics.printed`. For a body of any shape
the memoir takes, besides the heave zeta, the projections xi (on the xz plane: a rotation about
y, pitch) and psi (on the yz plane: about x, roll) of the inclination, alpha the azimuth of the
plane of inclination, M K^2 the inertia about y and M K'^2 about x (eq. (11), p. 54). Pp and Pq
are the first moments of the heeling wedge per unit angle, so that Pp/cos(alpha) =
int x^2 dA and Pq/sin(alpha) = int y^2 dA over the waterplane. The ellipsoid has the semi-axes
a (along x), b (along y) and c (vertical); the memoir calls them its "axes".

The errata that change results are the ellipsoid of revolution's roll formula (p. 60) and its
stability criterion (pp. 60-61): see :func:`p60_revolution_roll_omega2_as_printed` and
:func:`p61_revolution_kg_limit_as_printed`, and the errata table in docs/memoir.md.
"""

from __future__ import annotations

import math

import numpy as np

from floatfoam.errors import InputError, number
from floatfoam.hydrostatics.printed import draft_below, positive, stiffness_factor

# ------------------------------------------------------------ any body, eq. (12), p. 58

def eq12_heave_omega2(waterplane_area, mass, *, rho=1000.0, g=9.81) -> float:
    """First line of eq. (12), heave: Omega = g rho A / M.

    Parameters
    ----------
    waterplane_area, mass : float
        A (m^2) and M (kg).
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2.

    References
    ----------
    p. 58, eq. (12), with int dv = A zeta from the same page. Ambiguous print: transcribed
    "zeta = eps Cos((g rho / M) A + eps')", the t sqrt(...) of every other solution lost.
    Right with that reading.
    """
    return g * rho * positive(waterplane_area, "waterplane_area") / positive(mass, "mass")


def eq12_xi_omega2(pi_og, pp_over_cos_alpha, gyradius_y, mass, *, rho=1000.0, g=9.81) -> float:
    """Second line of eq. (12), the inclination xi (about y):

        Omega = g rho (Pi.OG + Pp / cos(alpha)) / (M K^2)

    Parameters
    ----------
    pi_og, pp_over_cos_alpha : float
        Pi.OG = V (KB - KG) and Pp / cos(alpha) = int x^2 dA, m^4.
    gyradius_y, mass : float
        K about y (m), M (kg).
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2.

    References
    ----------
    p. 58, eq. (12) ("Fp" is OCR for Pp). Right: Pi.OG + int x^2 dA = V GM_pitch.
    """
    return stiffness_factor(mass, gyradius_y, rho, g) * (number(pi_og, "pi_og")
                                                 + number(pp_over_cos_alpha, "pp_over_cos_alpha"))


def eq12_psi_omega2_as_printed(pi_og, pq_over_sin_alpha, gyradius_y, mass, *, rho=1000.0,
                               g=9.81) -> float:
    """Third line of eq. (12), the inclination psi (about x), as printed:

        Omega = g rho (Pi.OG + Pq / sin(alpha)) / (M K^2)

    with the *same* K as the xi line, the radius of gyration about y.

    Parameters
    ----------
    pi_og, pq_over_sin_alpha : float
        Pi.OG and Pq / sin(alpha) = int y^2 dA, m^4.
    gyradius_y, mass : float
        K about y (m), M (kg).
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2.

    References
    ----------
    p. 58, eq. (12). The wedge term is transcribed "D sin(alpha) / Pq", dimensionally
    impossible and contrary to p. 57: read Pq / sin(alpha). Erratum (or an OCR-dropped prime):
    eq. (11) has M K'^2, K' about x, for this rotation. Wrong when K' != K, by the factor
    (K'/K)^2 on Omega. See :func:`eq12_psi_omega2`.
    """
    return stiffness_factor(mass, gyradius_y, rho, g) * (number(pi_og, "pi_og")
                                                 + number(pq_over_sin_alpha, "pq_over_sin_alpha"))


def eq12_psi_omega2(pi_og, pq_over_sin_alpha, gyradius_x, mass, *, rho=1000.0, g=9.81) -> float:
    """Corrected third line of eq. (12): Omega = g rho (Pi.OG + Pq / sin(alpha)) / (M K'^2),
    K' the radius of gyration about x, as in eq. (11)."""
    return stiffness_factor(mass, gyradius_x, rho, g) * (number(pi_og, "pi_og")
                                                 + number(pq_over_sin_alpha, "pq_over_sin_alpha"))


# ------------------------------------------------------------------ ellipsoid, pp. 58-60

def p58_ellipsoid_waterplane_area(a, b, c, draft) -> float:
    """Waterplane area of the ellipsoid, as printed: A = (pi a b / c^2) [c^2 - (H - c)^2].

    Parameters
    ----------
    a, b, c, draft : float
        Semi-axes along x, y and the vertical, and H, m (0 < H < 2c).

    Returns
    -------
    float
        A, m^2.

    References
    ----------
    p. 58. Right.
    """
    a, b, c = positive(a, "a"), positive(b, "b"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    return math.pi * a * b / c**2 * (c * c - (H - c) ** 2)


def p58_ellipsoid_pi_og(a, b, c, draft, kg) -> float:
    """Pi.OG of the ellipsoid, as printed, with f = H - h:

        Pi.OG = (pi a b / (12 c^2)) [6 c^2 H (H - 2h) + (H - c)^3 (h - 3f - c) + (4h - c) c^3]

    Parameters
    ----------
    a, b, c, draft, kg : float
        Semi-axes, H and h (= KG), m.

    Returns
    -------
    float
        V (KB - KG), m^4.

    References
    ----------
    p. 58. Right (identical to (pi a b / (12 c^2)) [8 c H^3 - 3 H^4 - 12 h c H^2 + 4 h H^3]).
    """
    a, b, c = positive(a, "a"), positive(b, "b"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    h = number(kg, "kg")
    f = H - h
    return math.pi * a * b / (12 * c * c) * (6 * c * c * H * (H - 2 * h)
                                             + (H - c) ** 3 * (h - 3 * f - c) + (4 * h - c) * c**3)


def p59_wedge_moments_as_printed(a, b, c, draft, alpha, *, nodes: int = 512):
    """(Pp / cos(alpha), Pq / sin(alpha)) from the integrals printed on p. 59:

        Pp = -1/(4 sec(beta)) int_0^2pi {r^4 (sin v cos v - tan(beta) cos^2 v)
                                         + (m tan(beta) - n) r^3 cos v} dv
        Pq = -1/(4 sec(beta)) int_0^2pi {r^4 (sin^2 v - tan(beta) sin v cos v)
                                         + (m tan(beta) - n) r^3 sin v} dv

    with r = a' b' / sqrt(a'^2 sin^2 v + b'^2 cos^2 v), a' = a k / c, b' = b k / c,
    k = sqrt(H (2c - H)), m = -a b k / (c sqrt(a^2 tan^2(alpha) + b^2)), n = -m tan(alpha),
    tan(beta) = b^2 / (a^2 tan(alpha)), sec(beta) = sqrt(a^4 tan^2(alpha) + b^4) /
    (a^2 tan(alpha)). The integrand is smooth and periodic, so the trapezoid rule on ``nodes``
    points is exact to round-off.

    Parameters
    ----------
    a, b, c, draft : float
        Semi-axes and H, m.
    alpha : float
        Azimuth of the plane of inclination from x, rad, 0 < alpha < pi/2.

    Returns
    -------
    tuple of float
        (Pp / cos(alpha), Pq / sin(alpha)), m^4.

    References
    ----------
    p. 59. Wrong for a != b: both come out as
    +-pi a'^3 b'^3 / (4 sqrt(a'^4 sin^2(alpha) + b'^4 cos^2(alpha))), which depends on alpha:
    the wedge's edge is put along the tangent at the end of the diameter in the plane of
    inclination, which is not perpendicular to that plane. Pq has the wrong sign (the point A
    is mirrored), and the r^3 terms need 1/3, not 1/4 (harmless: they integrate to zero). For
    a = b the magnitude is right. See :func:`ellipsoid_waterplane_inertias`.
    """
    a, b, c = positive(a, "a"), positive(b, "b"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    alpha = number(alpha, "alpha", minimum=0.0)
    if alpha >= math.pi / 2:
        raise InputError(f"alpha = {alpha!r}: valid is 0 < alpha < pi/2 (tan and sec of p. 59)")
    k = math.sqrt(H * (2 * c - H))
    ap, bp, ta = a * k / c, b * k / c, math.tan(alpha)
    m = -a * b * k / (c * math.sqrt(a * a * ta * ta + b * b))
    n = -m * ta
    tan_beta = b * b / (a * a * ta)
    sec_beta = math.sqrt(a**4 * ta * ta + b**4) / (a * a * ta)
    v = np.linspace(0.0, 2 * math.pi, nodes, endpoint=False)
    s, co = np.sin(v), np.cos(v)
    r = ap * bp / np.sqrt(ap * ap * s * s + bp * bp * co * co)
    pp = np.sum(r**4 * (s * co - tan_beta * co * co) + (m * tan_beta - n) * r**3 * co)
    pq = np.sum(r**4 * (s * s - tan_beta * s * co) + (m * tan_beta - n) * r**3 * s)
    scale = -(2 * math.pi / nodes) / (4 * sec_beta)
    return float(scale * pp / math.cos(alpha)), float(scale * pq / math.sin(alpha))


def ellipsoid_waterplane_inertias(a, b, c, draft):
    """Corrected p. 59: (int x^2 dA, int y^2 dA) = (pi a'^3 b' / 4, pi a' b'^3 / 4) over the
    waterplane ellipse of semi-axes a', b' (see :func:`p59_wedge_moments_as_printed`),
    independent of alpha; m^4."""
    a, b, c = positive(a, "a"), positive(b, "b"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    k2 = H * (2 * c - H) / c**2
    return math.pi * a**3 * b * k2 * k2 / 4, math.pi * a * b**3 * k2 * k2 / 4


def p60_r4sin2_substitution(z, a_p, b_p):
    """p. 60: r^4 sin^2(v) dv, with z = sqrt((1 + sin v) / (1 - sin v)), per dz:

        2 a'^4 b'^4 (z^2 - 1)^2 (z^2 + 1) / {a'^2 (z^2 - 1)^2 + 4 b'^2 z^2}^2

    ``z`` may be an array. References: p. 60. Right (v from -pi/2 to pi/2 is z from 0 to inf).
    """
    return (2 * a_p**4 * b_p**4 * (z * z - 1) ** 2 * (z * z + 1)
            / (a_p**2 * (z * z - 1) ** 2 + 4 * b_p**2 * z * z) ** 2)


def p60_r4cos2_substitution_as_printed(z, a_p, b_p):
    """p. 60: r^4 cos^2(v) dv, with z = sqrt((1 + cos v) / (1 - cos v)), per dz, as printed:

        -2 a'^4 b'^4 (z^2 - 1)(z^2 + 1) / {b'^2 (z^2 - 1)^2 + 4 a'^2 z^2}^2

    ``z`` may be an array. References: p. 60. Wrong (harmless, or an OCR-dropped exponent):
    (z^2 - 1) must be squared, since r^4 cos^2 v >= 0 cannot change sign at z = 1. See
    :func:`r4cos2_substitution`.
    """
    return (-2 * a_p**4 * b_p**4 * (z * z - 1) * (z * z + 1)
            / (b_p**2 * (z * z - 1) ** 2 + 4 * a_p**2 * z * z) ** 2)


def r4cos2_substitution(z, a_p, b_p):
    """Corrected p. 60: -2 a'^4 b'^4 (z^2 - 1)^2 (z^2 + 1) / {b'^2 (z^2 - 1)^2 + 4 a'^2 z^2}^2
    (v from 0 to pi is z from inf to 0)."""
    return (-2 * a_p**4 * b_p**4 * (z * z - 1) ** 2 * (z * z + 1)
            / (b_p**2 * (z * z - 1) ** 2 + 4 * a_p**2 * z * z) ** 2)


# ------------------------------------------- ellipsoid of revolution (a = b), pp. 60-61

def p60_revolution_wedge_moment_as_printed(a, c, draft) -> float:
    """Ellipsoid of revolution: Pp / cos(alpha) = Pq / sin(alpha) = a^4 H^2 (2c - H)^2 / (4 c^4),
    as printed (m^4).

    References
    ----------
    p. 60 (transcribed "(2c - H)^{2 alpha}", read ^2). Wrong: the factor pi is missing (the
    waterplane disc's second moment is pi a'^4 / 4). The roll formula below has the pi back, so
    the slip does not propagate. See :func:`revolution_wedge_moment`.
    """
    a, c = positive(a, "a"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    return a**4 * H * H * (2 * c - H) ** 2 / (4 * c**4)


def revolution_wedge_moment(a, c, draft) -> float:
    """Corrected p. 60: pi a^4 H^2 (2c - H)^2 / (4 c^4) = I_wp, m^4."""
    return math.pi * p60_revolution_wedge_moment_as_printed(a, c, draft)


def p60_revolution_roll_omega2_as_printed(a, c, draft, kg, gyradius, mass, *, rho=1000.0,
                                          g=9.81) -> float:
    """Roll (= pitch) of the ellipsoid of revolution about its vertical semi-axis c, as printed:

        Omega = (g rho pi / (3 M K^2)) [((a - H)^3 + a^2 (3H - a)) (a - h)
                                        + 3 H^2 (2c - H)^2 (a^4 - c^4) / (4 c^4)]

    Parameters
    ----------
    a, c : float
        Equatorial (horizontal) and vertical semi-axes, m.
    draft, kg, gyradius : float
        H (0 < H < 2c), h (= KG) and K, m.
    mass : float
        M, kg.
    rho, g : float
        Fluid density (kg/m^3), gravity (m/s^2).

    Returns
    -------
    float
        Omega, rad^2/s^2.

    References
    ----------
    p. 60. Readings: "g P^alpha / (3 M K^2)" is g rho pi / (3 M K^2); "(a - H^3 + a^2 (3H - a))"
    is ((a - H)^3 + a^2 (3H - a)), as in the criterion; "(2c - H)^alpha" is (2c - H)^2; the
    phase eps_1' belongs outside the root. Wrong: the first term is the sphere of radius *a*,
    H^2 (3a - H)(a - h), where the spheroid needs (a^2 / c^2) H^2 (3c - H)(c - h), and
    (a^4 - c^4) stands where a^2 (a^2 - c^2) belongs. Right only for a = c. See
    :func:`revolution_roll_omega2`.
    """
    a, c = positive(a, "a"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    h = number(kg, "kg")
    bracket = (((a - H) ** 3 + a * a * (3 * H - a)) * (a - h)
               + 3 * H * H * (2 * c - H) ** 2 * (a**4 - c**4) / (4 * c**4))
    return math.pi / 3 * stiffness_factor(mass, gyradius, rho, g) * bracket


def revolution_roll_omega2(a, c, draft, kg, gyradius, mass, *, rho=1000.0, g=9.81) -> float:
    """Corrected p. 60, in the memoir's form:

        Omega = (g rho pi a^2 / (3 c^2 M K^2)) [((c - H)^3 + c^2 (3H - c)) (c - h)
                                                + 3 H^2 (2c - H)^2 (a^2 - c^2) / (4 c^2)]
              = g rho V (KM - KG) / (M K^2),  KM = c + 3 (a^2 - c^2)(2c - H)^2 / (4 c^2 (3c - H)).

    Arguments as :func:`p60_revolution_roll_omega2_as_printed`; rad^2/s^2.
    """
    a, c = positive(a, "a"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    h = number(kg, "kg")
    bracket = (((c - H) ** 3 + c * c * (3 * H - c)) * (c - h)
               + 3 * H * H * (2 * c - H) ** 2 * (a * a - c * c) / (4 * c * c))
    return math.pi * a * a / (3 * c * c) * stiffness_factor(mass, gyradius, rho, g) * bracket


def p61_revolution_kg_limit_as_printed(a, c, draft) -> float:
    """Stability criterion of the ellipsoid of revolution, as printed: the body oscillates,
    stays or capsizes as h <, =, >

        3 H^2 (2c - H)^2 (a^4 - c^4) / (4 c^4 {(a - H)^3 + a^2 (3H - a)}) + a.

    Parameters
    ----------
    a, c, draft : float
        Semi-axes (horizontal, vertical) and H, m (0 < H < 2c, H != 3a).

    Returns
    -------
    float
        The limit on h = KG, m.

    References
    ----------
    pp. 60-61 (the sentence begins on p. 60, the formula is on p. 61). Wrong, as the roll
    formula it comes from: (a - H)^3 + a^2 (3H - a) = H^2 (3a - H), so the limit is singular at
    H = 3a and changes side beyond (a slender prolate body); at H = 2c it gives h = a, whereas
    the memoir itself says next that the fully immersed body is neutral with G at the centre
    of figure (h = c). See :func:`revolution_kg_limit`.
    """
    a, c = positive(a, "a"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    sphere_part = (a - H) ** 3 + a * a * (3 * H - a)
    if sphere_part == 0.0:
        raise InputError(f"draft = {draft!r}: the printed criterion is singular at H = 3a")
    return 3 * H * H * (2 * c - H) ** 2 * (a**4 - c**4) / (4 * c**4 * sphere_part) + a


def revolution_kg_limit(a, c, draft) -> float:
    """Corrected criterion: h <, =, > KM = c + 3 (a^2 - c^2)(2c - H)^2 / (4 c^2 (3c - H)), m."""
    a, c = positive(a, "a"), positive(c, "c")
    H = draft_below(draft, 2.0 * c, "the height 2c")
    return c + 3 * (a * a - c * c) * (2 * c - H) ** 2 / (4 * c * c * (3 * c - H))
