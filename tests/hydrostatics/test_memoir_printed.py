"""The memoir as printed (floatfoam.hydrostatics.printed, printed_ellipsoid) against the exact
hydrostatics (floatfoam.hydrostatics.immersion.immersed, theory_summary).

Right formulas must agree with the exact theory to round-off on several bodies. Each erratum is
pinned twice: the printed function equals its own closed form as printed (so it cannot be
"fixed" silently), and it differs from the exact value by more than a stated margin.

Tolerances: CLOSED = 1e-12 relative where both sides are closed forms (round-off only, with an
absolute floor at 1e-12 of the quantity's scale where it passes through zero); ROOT = 1e-9
where the exact side comes from theory_summary, whose draft is a root (Brent, xtol 1e-12 of the
body size); QUAD = 1e-10 where one side is an adaptive quadrature (epsrel 1e-13).
"""

import math

import pytest
from scipy.integrate import quad

from floatfoam.bodies.shapes import ConicCylinder, Ellipsoid, EllipticCylinder
from floatfoam.case import load_case
from floatfoam.hydrostatics import printed as pr
from floatfoam.hydrostatics import printed_ellipsoid as pe
from floatfoam.hydrostatics.immersion import immersed
from floatfoam.hydrostatics.theory import theory_summary
from floatfoam.hydrostatics.verdict import verdict

RHO, G = 1000.0, 9.81
CLOSED, ROOT, QUAD = 1e-12, 1e-9, 1e-10
MEMOIR_CASES = ["cylinder_heave", "elliptic_cylinder", "parabolic_cylinder", "sphere", "ellipsoid"]


def exact(body, draft, kg):
    """Exact upright hydrostatics at ``draft``: volume, waterplane area, KB, GM roll and pitch,
    waterplane second moments (about x: int y^2 dA, about y: int x^2 dA)."""
    z_c = -draft - body.keel_z
    imm = immersed(body, z_c, method="closed")
    kb = imm.centroid[2] - (z_c + body.keel_z)
    i_xx, i_yy, _ = imm.waterplane_inertia
    return {"V": imm.volume, "A": imm.waterplane_area, "KB": kb, "I_xx": i_xx, "I_yy": i_yy,
            "GM_roll": kb + i_xx / imm.volume - kg, "GM_pitch": kb + i_yy / imm.volume - kg}


def close(value, expected, scale=None, rel=CLOSED):
    """``value`` equals ``expected`` to ``rel``, with an absolute floor rel * scale for
    quantities that pass through zero (a margin, a GM)."""
    return value == pytest.approx(expected, rel=rel, abs=rel * (scale or 0.0))


# --- right formulas: the circular cylinder, eqs (9), (10), p. 51 ------------------------------

@pytest.mark.parametrize("a", [0.0762, 1.0, 2.5])
@pytest.mark.parametrize("h_over_a", [0.2, 1.0, 1.8])
@pytest.mark.parametrize("kg_over_a", [0.3, 0.9, 1.2])
def test_circle_eq9_eq10_p51_are_exact(a, h_over_a, kg_over_a):
    H, kg, K, L = h_over_a * a, kg_over_a * a, 0.6 * a, 2.0
    ex = exact(EllipticCylinder(a, a, L), H, kg)
    M = RHO * ex["V"]
    assert close(pr.eq9_circle_heave_omega2(a, H, M, length=L), G * ex["A"] / ex["V"])
    roll = G * ex["GM_roll"] / K**2
    scale = G * a / K**2
    assert close(pr.eq10_circle_roll_omega2(a, H, kg, K, M, length=L), roll, scale)
    assert close(pr.p51_circle_roll_omega2(a, H, kg, K, M, length=L), roll, scale)
    assert close(pr.p53_circle_sphere_kg_limit(a), kg + ex["GM_roll"], a)  # KM = a (p. 53)


def test_p53_verdict_circle_and_sphere():
    a = 0.3
    limit = pr.p53_circle_sphere_kg_limit(a)
    verdicts = [verdict(limit - kg, a) for kg in (a * (1 - 1e-6), a, a * (1 + 1e-6))]
    assert verdicts == ["oscillates", "neutral", "capsizes"]


# --- right formulas: cylinders on conic bases, pp. 49-51 --------------------------------------

CONICS = [  # (body, drafts, KG): wide and tall ellipses, a cut ellipse, parabola, hyperbola
    (EllipticCylinder(0.15, 0.10, 1.0), (0.05, 0.1, 0.16), 0.1),
    (EllipticCylinder(0.10, 0.20, 1.5), (0.1, 0.3), 0.15),
    (ConicCylinder(0.45, -2.25, 0.15, 1.0), (0.04, 0.12), 0.08),
    (ConicCylinder(0.05, 0.0, 0.2, 1.0), (0.05, 0.2 * 0.6 ** (2 / 3)), 0.12),
    (ConicCylinder(0.1, 1.0, 0.3, 2.0), (0.1, 0.2), 0.1),
]


def conic_coefficients(body):
    if isinstance(body, EllipticCylinder):
        return 2 * body.b**2 / body.c, -(body.b**2) / body.c**2
    return body.n, body.m


@pytest.mark.parametrize("body, drafts, kg", CONICS)
def test_conic_p49_heave_and_p50_roll_are_exact(body, drafts, kg):
    n, m = conic_coefficients(body)
    L, K = body.length, 0.09
    for H in drafts:
        ex = exact(body, H, kg)
        M = RHO * ex["V"]
        assert close(pr.p49_conic_heave_omega2(n, m, H, M, length=L), G * ex["A"] / ex["V"])
        y = math.sqrt(n * H + m * H * H)
        wedge = pr.p50_cylinder_wedge_moment(y, length=L)
        assert close(wedge, ex["I_xx"])  # Pp = I_wp
        pi_og = ex["V"] * (ex["KB"] - kg)  # Pi.OG, exact, fed to the p. 50 formula
        assert close(pr.p50_roll_omega2(pi_og, wedge, K, M), G * ex["GM_roll"] / K**2,
                     G * H / K**2)


@pytest.mark.parametrize("b, c, L", [(0.15, 0.10, 1.0), (0.10, 0.20, 1.5), (1.0, 1.0, 1.0)])
@pytest.mark.parametrize("fraction", [0.2, 0.5, 0.9])
def test_p51_ellipse_integral_is_exact(b, c, L, fraction):
    # y^2 = n x - m x^2 with n = 2 b^2 / c, m = b^2 / c^2 (the p. 51 sign); 2 L times the
    # integral is Pi.OG = V (KB - KG), checked against the exact segment (ellipse_section).
    n51, m51 = 2 * b * b / c, b * b / (c * c)
    H, kg = fraction * 2 * c, 0.7 * c
    ex = exact(EllipticCylinder(b, c, L), H, kg)
    two_l_j = 2 * L * pr.p51_ellipse_moment(n51, m51, H, kg)
    assert close(two_l_j, ex["V"] * (ex["KB"] - kg), ex["V"] * c)


def test_p51_reading_of_the_exponents_is_pinned():
    # The transcription prints m^(1/2) and (1 + z^2)^(3/2); read m^(3/2) and (1 + z^2)^3.
    # On the elliptic_cylinder case (n = 0.45, m = 2.25, H = h = 0.1) the reading gives the
    # integral, -5.0e-4 m^3; the transcribed exponents would give -3.18e-3 (6x off).
    n, m, H, h = 0.45, 2.25, 0.1, 0.1
    assert pr.p51_ellipse_moment(n, m, H, h) == pytest.approx(-5.0e-4, rel=CLOSED)
    z = math.sqrt(H / (n / m - H))
    q = 1 + z * z
    ocr = n**2 / (24 * m**0.5 * q**1.5) * (3 * (z**5 - z + q**3 * math.atan(z)) * (n / m - 2 * h)
                                          - 8 * n / m * z**3)
    assert ocr == pytest.approx(-3.18198e-3, rel=1e-5)


# --- right formulas: the sphere, p. 52 ------------------------------------------------------

@pytest.mark.parametrize("a", [0.1, 1.3])
@pytest.mark.parametrize("h_over_a", [0.1, 1.0, 1.7])
@pytest.mark.parametrize("kg_over_a", [0.5, 0.8, 1.1])
def test_sphere_p52_is_exact(a, h_over_a, kg_over_a):
    H, kg, K = h_over_a * a, kg_over_a * a, 0.63 * a
    ex = exact(Ellipsoid([a, a, a]), H, kg)
    M = RHO * ex["V"]
    assert close(pr.p52_sphere_heave_omega2(a, H, M), G * ex["A"] / ex["V"])
    assert close(pr.p52_sphere_roll_omega2(a, H, kg, K, M), G * ex["GM_roll"] / K**2,
                 G * a / K**2)


# --- right formulas: any body, eq. (12) and the ellipsoid, pp. 58-60 ------------------------

ELLIPSOIDS = [(0.2, 0.12, 0.1), (0.15, 0.15, 0.1), (0.1, 0.1, 0.15), (0.3, 0.3, 0.3)]


@pytest.mark.parametrize("a, b, c", ELLIPSOIDS)
@pytest.mark.parametrize("h_over_c", [0.3, 1.0, 1.6])
def test_eq12_with_p58_is_exact_on_ellipsoids(a, b, c, h_over_c):
    H, kg, k_y, k_x = h_over_c * c, 0.8 * c, 0.09, 0.07
    ex = exact(Ellipsoid([a, b, c]), H, kg)
    M = RHO * ex["V"]
    area = pe.p58_ellipsoid_waterplane_area(a, b, c, H)
    assert close(area, ex["A"])
    pi_og = pe.p58_ellipsoid_pi_og(a, b, c, H, kg)
    assert close(pi_og, ex["V"] * (ex["KB"] - kg), ex["V"] * c)
    assert close(pe.eq12_heave_omega2(area, M), G * ex["A"] / ex["V"])
    int_x2, int_y2 = pe.ellipsoid_waterplane_inertias(a, b, c, H)
    assert close(int_x2, ex["I_yy"]) and close(int_y2, ex["I_xx"])
    scale = G * c / min(k_x, k_y) ** 2
    assert close(pe.eq12_xi_omega2(pi_og, int_x2, k_y, M), G * ex["GM_pitch"] / k_y**2, scale)
    assert close(pe.eq12_psi_omega2(pi_og, int_y2, k_x, M), G * ex["GM_roll"] / k_x**2, scale)


def test_p60_sin2_substitution_is_right():
    # int_{-pi/2}^{pi/2} r^4 sin^2 v dv = int_0^inf (p. 60 integrand) dz, a' = 0.13, b' = 0.08.
    ap, bp = 0.13, 0.08

    def r4(v):
        return (ap * bp / math.sqrt(ap**2 * math.sin(v) ** 2 + bp**2 * math.cos(v) ** 2)) ** 4

    direct = quad(lambda v: r4(v) * math.sin(v) ** 2, -math.pi / 2, math.pi / 2, epsrel=1e-13)[0]
    via_z = quad(lambda z: pe.p60_r4sin2_substitution(z, ap, bp), 0, math.inf, epsrel=1e-13,
                 limit=400)[0]
    assert via_z == pytest.approx(direct, rel=QUAD)
    assert direct == pytest.approx(1.045522035115e-4, rel=1e-11)


@pytest.mark.parametrize("h_over_a", [0.2, 1.0, 1.5])
@pytest.mark.parametrize("kg_over_a", [0.4, 1.0, 1.3])
def test_printed_ellipsoid_reduces_to_the_sphere(h_over_a, kg_over_a):
    # The memoir's own check (p. 61): at a = c the printed roll and criterion are the sphere's.
    a = 0.2
    H, kg, K, M = h_over_a * a, kg_over_a * a, 0.1, 7.0
    sphere = pr.p52_sphere_roll_omega2(a, H, kg, K, M)
    assert close(pe.p60_revolution_roll_omega2_as_printed(a, a, H, kg, K, M), sphere,
                 G * RHO * a**4 / (M * K**2))
    assert pe.p61_revolution_kg_limit_as_printed(a, a, H) == pytest.approx(a, rel=CLOSED)


# --- right formulas, case by case: theory --json -------------------------------------------

VARIANTS = [("cylinder_heave", []),
            ("cylinder_heave", ["mass.density=200", "mass.cog=[0.0, 0.0, -0.03]"]),
            ("cylinder_heave", ["mass.cog=[0.0, 0.0, 0.01]"]),
            ("elliptic_cylinder", []),
            ("elliptic_cylinder", ["body.half_beam=0.1", "body.half_height=0.2",
                                   "mass.density=700", "mass.cog=[0.0, 0.0, -0.08]"]),
            ("parabolic_cylinder", []),
            ("parabolic_cylinder", ["mass.cog=[0.0, 0.0, -0.03]", "mass.density=400"]),
            ("sphere", []),
            ("sphere", ["body.radius=0.25", "mass.density=300", "mass.cog=[0.0, 0.0, -0.1]"])]


@pytest.mark.parametrize("case, overrides", VARIANTS)
def test_printed_equals_exact_theory_where_the_print_is_right(case, overrides):
    s = theory_summary(load_case(case, overrides)).to_dict()
    p = s["memoir_printed"]
    assert p["source"] == "printed" and p["errata"] == []
    assert p["verdict_roll"] == s["verdict_roll"] and p["verdict_roll_matches_exact"]
    for key in ("waterplane_area", "heave_period", "roll_period", "GM_roll"):
        if s[key] is None:
            assert p[key] is None, key
        else:
            assert close(p[key], s[key], s["draft"], rel=ROOT), key


def test_bodies_outside_the_memoir_have_no_printed_values():
    for case in ("box_bilge", "superellipsoid_buoy"):
        assert theory_summary(load_case(case)).memoir_printed == {}
