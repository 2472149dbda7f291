"""Le Barbier's bodies (floatfoam.hydrostatics.memoir) against independent hand derivations.

memoir.py evaluates the memoir's method, derived again from first principles (the corrected
formulas); the formulas as printed are in printed.py and are tested in test_memoir_printed.py
and test_memoir_errata.py. These tests check memoir.py at points where the answer can be
written down by hand. Tolerances: 1e-12 relative for closed forms (round-off only); 1e-9 where
a root finder or adaptive quadrature is involved.
"""

import math

import pytest
from scipy.integrate import quad

from floatfoam.errors import InputError
from floatfoam.hydrostatics import memoir

G = 9.81
CLOSED = 1e-12
NUMERIC = 1e-9


def test_every_result_is_flagged_as_reconstructed():
    results = [
        memoir.circular_cylinder(1.0, 0.3, 0.5, 0.4),
        memoir.conic_cylinder(1.0, 0.0, 0.5, 0.1, 0.3),
        memoir.sphere(1.0, 0.3, 0.5, 0.4),
        memoir.ellipsoid_of_revolution(1.5, 1.0, 0.3, 0.5, 0.4),
    ]
    for res in results:
        assert res["source"] == "reconstructed"
        assert res["verified_against_print"] is False
        assert "Le Barbier" in res["reference"]


# --- circular cylinder, memoir eqs (9)-(10) -------------------------------------------------

def test_half_immersed_circular_cylinder_by_hand():
    # density 1/2: T = a, section pi a^2/2, breadth 2a, KB = a - 4a/(3 pi), KM = a.
    a, kg, k = 2.0, 1.5, 0.9
    res = memoir.circular_cylinder(a, 0.5, kg, k, length=3.0)
    assert res["draft"] == pytest.approx(a, rel=NUMERIC)
    assert res["volume"] == pytest.approx(math.pi * a * a / 2 * 3.0, rel=NUMERIC)
    assert res["waterplane_area"] == pytest.approx(2 * a * 3.0, rel=NUMERIC)
    assert res["kb"] == pytest.approx(a - 4 * a / (3 * math.pi), rel=NUMERIC)
    assert res["km"] == pytest.approx(a, rel=NUMERIC)
    # omega_h^2 = g 2a / (pi a^2 / 2) = 4 g / (pi a); omega_r^2 = g (a - KG) / K^2
    assert res["heave_period"] == pytest.approx(2 * math.pi / math.sqrt(4 * G / (math.pi * a)),
                                                rel=NUMERIC)
    assert res["roll_period"] == pytest.approx(2 * math.pi * k / math.sqrt(G * (a - kg)),
                                               rel=NUMERIC)
    assert res["verdict_roll"] == "oscillates"


@pytest.mark.parametrize("density_ratio", [0.05, 0.3, 0.5, 0.8, 0.97])
def test_circle_metacentre_is_the_centre_at_every_draft(density_ratio):
    # Buoyancy passes through the centre of the circle whatever the heel (memoir p. 52, fig. 2).
    res = memoir.circular_cylinder(1.3, density_ratio, 0.2, 0.5)
    assert res["km"] == pytest.approx(1.3, rel=NUMERIC)


@pytest.mark.parametrize("body", ["circular_cylinder", "sphere"])
def test_circle_and_sphere_verdict_is_kg_against_radius(body):
    # p. 53 (djvu/59), in words: oscillates / stays / capsizes as the height of G is below,
    # at, or above the radius.
    f = getattr(memoir, body)
    assert f(1.0, 0.4, 0.99, 0.5)["verdict_roll"] == "oscillates"
    assert f(1.0, 0.4, 1.0, 0.5)["verdict_roll"] == "neutral"
    capsizes = f(1.0, 0.4, 1.01, 0.5)
    assert capsizes["verdict_roll"] == "capsizes"
    assert capsizes["roll_period"] is None


@pytest.mark.parametrize("body", ["circular_cylinder", "sphere"])
def test_heave_slows_monotonically_with_immersion(body):
    # The exact heave frequency falls steadily from infinity (T -> 0) to 0 (T -> 2a): there is
    # no intermediate immersion with a slowest heave (docs/memoir.md section 4c).
    f = getattr(memoir, body)
    periods = [f(1.0, s, 0.5, 0.5)["heave_period"] for s in (0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99)]
    assert periods == sorted(periods)


# --- conic cylinders y^2 = n x + m x^2 (pp. 50-51) -------------------------------------------

def test_conic_with_circle_coefficients_reproduces_the_circular_cylinder():
    circle = memoir.circular_cylinder(0.8, 0.35, 0.6, 0.4)
    conic = memoir.conic_cylinder(2 * 0.8, -1.0, circle["draft"], 0.6, 0.4)
    assert conic["conic"] == "circle"
    for key in ("volume", "waterplane_area", "kb", "bm", "heave_period", "roll_period"):
        assert conic[key] == pytest.approx(circle[key], rel=NUMERIC)


def test_parabolic_cylinder_closed_forms():
    # y^2 = n x: A = (4/3) sqrt(n) T^1.5, KB = 3T/5, BM = n/2 (Archimedes), omega_h^2 = 3g/(2T).
    n, T, kg, k = 1.6, 0.7, 0.3, 0.45
    res = memoir.conic_cylinder(n, 0.0, T, kg, k)
    assert res["conic"] == "parabola"
    assert res["volume"] == pytest.approx(4 / 3 * math.sqrt(n) * T**1.5, rel=NUMERIC)
    assert res["kb"] == pytest.approx(0.6 * T, rel=NUMERIC)
    assert res["bm"] == pytest.approx(n / 2, rel=NUMERIC)
    assert res["heave_period"] == pytest.approx(2 * math.pi / math.sqrt(1.5 * G / T), rel=NUMERIC)
    gm = 0.6 * T + n / 2 - kg
    assert res["roll_period"] == pytest.approx(2 * math.pi * k / math.sqrt(G * gm), rel=NUMERIC)


def test_elliptic_cylinder_is_a_stretched_circle():
    # Half beam b, half height c: y^2 = (b/c)^2 (2 c x - x^2). Stretching sideways keeps KB and
    # multiplies BM by (b/c)^2, so KM = c + ((b/c)^2 - 1) BM_circle(c, T).
    b, c, T = 1.7, 1.0, 0.6
    alpha = math.acos(1 - T / c)
    bm_circle = (2 * c * math.sin(alpha)) ** 3 / (
        12 * c * c * (alpha - math.sin(alpha) * math.cos(alpha)))
    res = memoir.conic_cylinder(2 * b * b / c, -((b / c) ** 2), T, 0.2, 0.5)
    assert res["conic"] == "ellipse"
    assert res["km"] == pytest.approx(c + ((b / c) ** 2 - 1) * bm_circle, rel=NUMERIC)


def test_hyperbolic_cylinder_against_direct_quadrature():
    n, m, T = 1.2, 0.8, 0.9

    def y(x):
        return math.sqrt(n * x + m * x * x)

    area = 2 * quad(y, 0, T, epsrel=1e-13)[0]
    kb = 2 * quad(lambda x: x * y(x), 0, T, epsrel=1e-13)[0] / area
    res = memoir.conic_cylinder(n, m, T, 0.1, 0.5)
    assert res["conic"] == "hyperbola"
    assert res["kb"] == pytest.approx(kb, rel=NUMERIC)
    assert res["bm"] == pytest.approx((2 * y(T)) ** 3 / (12 * area), rel=NUMERIC)
    assert res["heave_period"] == pytest.approx(2 * math.pi / math.sqrt(G * 2 * y(T) / area),
                                                rel=NUMERIC)


# --- sphere (p. 52) and ellipsoid of revolution (pp. 58-61) ----------------------------------

def test_half_immersed_sphere_by_hand():
    # T = a, V = 2 pi a^3 / 3, A_wp = pi a^2, KB = 5a/8, BM = 3a/8, omega_h^2 = 3 g / (2a).
    a = 1.5
    res = memoir.sphere(a, 0.5, 1.0, 0.6)
    assert res["draft"] == pytest.approx(a, rel=NUMERIC)
    assert res["volume"] == pytest.approx(2 * math.pi * a**3 / 3, rel=NUMERIC)
    assert res["kb"] == pytest.approx(5 * a / 8, rel=NUMERIC)
    assert res["bm"] == pytest.approx(3 * a / 8, rel=NUMERIC)
    assert res["heave_period"] == pytest.approx(2 * math.pi / math.sqrt(1.5 * G / a), rel=NUMERIC)


def test_spheroid_with_equal_axes_is_the_sphere():
    s = memoir.sphere(1.1, 0.27, 0.9, 0.5)
    e = memoir.ellipsoid_of_revolution(1.1, 1.1, 0.27, 0.9, 0.5)
    for key in ("draft", "volume", "kb", "bm", "km", "heave_period", "roll_period"):
        assert e[key] == pytest.approx(s[key], rel=CLOSED)


def test_half_immersed_spheroid_by_hand():
    # T = c: V = 2 pi a^2 c / 3, KB = 5c/8, BM = (pi a^4 / 4) / V = 3 a^2 / (8 c).
    a, c = 1.8, 1.2
    res = memoir.ellipsoid_of_revolution(a, c, 0.5, c, 0.7)
    assert res["kb"] == pytest.approx(5 * c / 8, rel=NUMERIC)
    assert res["bm"] == pytest.approx(3 * a * a / (8 * c), rel=NUMERIC)
    assert res["km"] - c == pytest.approx(memoir.ellipsoid_stability_limit(a, c, c), rel=NUMERIC)
    assert res["heave_period"] == pytest.approx(2 * math.pi / math.sqrt(1.5 * G / c), rel=NUMERIC)


def test_oblate_is_stiffer_than_the_sphere_and_prolate_softer():
    # G at the centre (KG = c): oblate oscillates, sphere neutral, prolate capsizes.
    assert memoir.ellipsoid_of_revolution(2.0, 1.0, 0.5, 1.0, 0.8)["verdict_roll"] == "oscillates"
    assert memoir.ellipsoid_of_revolution(1.0, 1.0, 0.5, 1.0, 0.8)["verdict_roll"] == "neutral"
    assert memoir.ellipsoid_of_revolution(1.0, 2.0, 0.5, 2.0, 0.8)["verdict_roll"] == "capsizes"


def test_oblate_criterion_by_hand():
    # Replaces test_an_a_c_exchange_flips_the_criterion, which pinned the hypothesis that the
    # printed criterion exchanges a and c. The print, now read (docs/memoir.md, errata), is not
    # an exchange: tests/hydrostatics/test_memoir_errata.py pins what it is. This keeps the hand
    # value of the exact limit: at half immersion (T = c), 3 (a^2 - c^2) / (8 c).
    a, c = 2.0, 1.0
    assert memoir.ellipsoid_stability_limit(a, c, c) == pytest.approx(3 * (a * a - c * c) / (8 * c),
                                                                      rel=CLOSED)
    assert memoir.ellipsoid_stability_limit(c, a, a) < 0  # prolate: metacentre below the centre


# --- bad input -------------------------------------------------------------------------------

@pytest.mark.parametrize("density_ratio", [0.0, 1.0, 1.2, -0.1])
def test_density_ratio_must_float(density_ratio):
    with pytest.raises(InputError, match="density_ratio"):
        memoir.circular_cylinder(1.0, density_ratio, 0.5, 0.5)


def test_draft_must_stay_inside_a_closed_conic():
    with pytest.raises(InputError, match="draft"):
        memoir.conic_cylinder(2.0, -1.0, 2.0, 0.5, 0.5)


def test_each_shape_says_its_memoir_family():
    from floatfoam.bodies import shapes

    assert shapes.EllipticCylinder(0.5, 0.5, 2.0).memoir_family == ("circle", 0.5)
    # the ellipse as the memoir's conic: n = 2b²/c, m = −b²/c²
    assert shapes.EllipticCylinder(1.0, 0.5, 2.0).memoir_family == ("conic", 4.0, -4.0)
    assert shapes.ConicCylinder(0.3, 0.2, 1.0, 2.0).memoir_family == ("conic", 0.3, 0.2)
    assert shapes.Ellipsoid([0.4, 0.4, 0.4]).memoir_family == ("sphere", 0.4)
    assert shapes.Ellipsoid([0.4, 0.4, 0.6]).memoir_family == ("revolution", 0.4, 0.6)
    assert shapes.Ellipsoid([0.4, 0.5, 0.6]).memoir_family is None
    assert shapes.Box(1.0, 0.5, 2.0).memoir_family is None
