"""Closed forms against independent hand derivations (textbook segment/cap formulas and
direct quadrature of the half-width)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from floatfoam.bodies.shapes import (
    Box,
    ConicCylinder,
    Ellipsoid,
    EllipticCylinder,
    VerticalCylinder,
)
from floatfoam.hydrostatics.immersion import immersed

A = 0.0762


def circular_segment(a, d):
    """Area and centroid height above the keel of a circle of radius a immersed to draft d
    (textbook: area a²·acos((a−d)/a) − (a−d)√(2ad − d²), centroid from the chord moment)."""
    h = a - d
    area = a * a * math.acos(h / a) - h * math.sqrt(2 * a * d - d * d)
    chord = 2 * math.sqrt(2 * a * d - d * d)
    # moment of the segment about the centre: −chord³/12 (below the centre)
    zbar = -(chord**3 / 12.0) / area
    return area, zbar + a


@pytest.mark.parametrize("draft", [0.2 * A, A, 1.7 * A])
def test_circle_segment_matches_textbook(draft):
    body = EllipticCylinder(A, A, 1.0)
    imm = immersed(body, A - draft, method="closed")
    area, kb = circular_segment(A, draft)
    assert imm.volume == pytest.approx(area, rel=1e-12)
    assert imm.centroid[2] - (A - draft) + A == pytest.approx(kb, rel=1e-12)
    half = math.sqrt(2 * A * draft - draft * draft)
    assert imm.waterplane_area == pytest.approx(2 * half, rel=1e-12)
    assert imm.waterplane_inertia[0] == pytest.approx((2 * half) ** 3 / 12, rel=1e-12)


def test_half_circle_values():
    imm = immersed(EllipticCylinder(A, A, 2.0), 0.0, method="closed")
    assert imm.volume == pytest.approx(math.pi * A * A, rel=1e-12)  # πa²/2 · L, L = 2
    assert imm.centroid[2] == pytest.approx(-4 * A / (3 * math.pi), rel=1e-12)


def test_circle_is_rotation_invariant():
    body = EllipticCylinder(A, A, 1.0)
    ref = immersed(body, 0.01)
    for heel in (0.3, 1.2, 2.5):
        imm = immersed(body, 0.01, heel)
        assert imm.volume == pytest.approx(ref.volume, rel=1e-12)
        # B stays directly below the axis: y_B = 0 in the earth frame
        assert imm.centroid[1] == pytest.approx(0.0, abs=1e-14)


@pytest.mark.parametrize("h", [0.03, 0.1, 0.17])
def test_sphere_cap_matches_textbook(h):
    a = 0.1
    imm = immersed(Ellipsoid([a, a, a]), a - h, method="closed")
    assert imm.volume == pytest.approx(math.pi * h * h * (3 * a - h) / 3, rel=1e-12)
    zbar = 3 * (2 * a - h) ** 2 / (4 * (3 * a - h))  # cap centroid below the centre
    assert imm.centroid[2] == pytest.approx((a - h) - zbar, rel=1e-12)
    r2 = 2 * a * h - h * h
    assert imm.waterplane_area == pytest.approx(math.pi * r2, rel=1e-12)
    assert imm.waterplane_inertia[0] == pytest.approx(math.pi * r2 * r2 / 4, rel=1e-12)


def test_half_ellipsoid_values():
    ax, ay, az = 0.3, 0.2, 0.1
    imm = immersed(Ellipsoid([ax, ay, az]), 0.0, method="closed")
    assert imm.volume == pytest.approx(2 / 3 * math.pi * ax * ay * az, rel=1e-12)
    assert imm.centroid[2] == pytest.approx(-3 * az / 8, rel=1e-12)
    assert imm.waterplane_area == pytest.approx(math.pi * ax * ay, rel=1e-12)
    i_xx, i_yy, i_xy = imm.waterplane_inertia
    assert i_xx == pytest.approx(math.pi * ax * ay**3 / 4, rel=1e-12)
    assert i_yy == pytest.approx(math.pi * ay * ax**3 / 4, rel=1e-12)
    assert i_xy == pytest.approx(0.0, abs=1e-15)


def conic_by_quadrature(n, m, d):
    def w(x):
        return math.sqrt(max(n * x + m * x * x, 0.0))

    area = 2 * quad(w, 0, d, epsabs=1e-14, epsrel=1e-13)[0]
    moment = 2 * quad(lambda x: x * w(x), 0, d, epsabs=1e-14, epsrel=1e-13)[0]
    return area, moment / area, 2 * w(d)


@pytest.mark.parametrize("n, m", [(0.05, 0.0), (0.05, 0.8), (0.45, -2.25)])
def test_conic_cylinder_upright_matches_quadrature(n, m):
    height = 0.15
    body = ConicCylinder(n, m, height, 1.0)
    for depth in (0.02, 0.07, 0.13):
        imm = immersed(body, height / 2 - depth, method="closed")
        area, kb, width = conic_by_quadrature(n, m, depth)
        assert imm.volume == pytest.approx(area, rel=1e-9)
        assert imm.centroid[2] - (height / 2 - depth) + height / 2 == pytest.approx(kb, rel=1e-9)
        assert imm.waterplane_area == pytest.approx(width, rel=1e-12)


def test_parabola_hand_formula():
    n, d = 0.05, 0.1
    imm = immersed(ConicCylinder(n, 0.0, 0.2, 1.0), 0.1 - d, method="closed")
    assert imm.volume == pytest.approx(4 / 3 * math.sqrt(n) * d**1.5, rel=1e-12)
    assert imm.centroid[2] + 0.1 == pytest.approx(0.6 * d, abs=1e-14)  # 3d/5 above the vertex


@pytest.mark.parametrize("draft", [0.02, 0.05, 0.15])
def test_box_with_bilge_matches_hand_formula(draft):
    beam, height, r = 0.3, 0.2, 0.03
    body = Box(beam, height, 1.0, r)
    imm = immersed(body, height / 2 - draft, method="closed")

    def w(x):  # half-width at height x above the keel
        return beam / 2 - r + math.sqrt(max(r * r - (r - x) ** 2, 0.0)) if x < r else beam / 2

    area = 2 * quad(w, 0, draft, points=[r] if draft > r else None, epsabs=1e-14)[0]
    if draft >= r:
        assert area == pytest.approx(beam * draft - (4 - math.pi) * r * r / 2, rel=1e-10)
    assert imm.volume == pytest.approx(area, rel=1e-9)
    assert imm.waterplane_area == pytest.approx(2 * w(draft), rel=1e-12)


@pytest.mark.parametrize("draft", [0.03, 0.1, 0.2])
def test_vertical_cylinder_upright_is_a_disc_over_a_prism(draft):
    """Radius 0.1 m, height 0.2 m: V = πr²d, B at d/2 above the keel, the waterplane a disc
    (I = πr⁴/4 about each axis, none when the top is under)."""
    r, h = 0.1, 0.2
    imm = immersed(VerticalCylinder(r, h), h / 2 - draft, method="closed")
    assert imm.volume == pytest.approx(math.pi * r * r * draft, rel=1e-12)
    assert imm.centroid[2] == pytest.approx(-draft / 2, abs=1e-15)  # keel at z = −draft
    disc = 0.0 if draft >= h else math.pi * r * r
    assert imm.waterplane_area == pytest.approx(disc, rel=1e-12, abs=1e-15)
    assert imm.waterplane_inertia[0] == pytest.approx(disc * r * r / 4, rel=1e-12, abs=1e-15)


def test_fully_submerged_and_emerged():
    body = Ellipsoid([0.1, 0.1, 0.1])
    assert immersed(body, -1.0).volume == pytest.approx(4 / 3 * math.pi * 1e-3, rel=1e-12)
    assert immersed(body, -1.0).waterplane_area == pytest.approx(0.0, abs=1e-15)
    assert immersed(body, 1.0).volume == 0.0
    np.testing.assert_allclose(immersed(Box(0.3, 0.2, 1.0), -1.0).volume, 0.06, rtol=1e-12)
