"""Equilibrium, metacentric heights, stiffness, verdicts, periods and GZ."""

import math

import numpy as np
import pytest

from floatfoam.case import load_case
from floatfoam.hydrostatics.gz import gz_curve, righting_arm
from floatfoam.hydrostatics.theory import equilibrium, stiffness_matrix, theory_summary

A = 0.0762


def test_ito_cylinder_theory():
    s = theory_summary(load_case("cylinder_heave")).to_dict()
    assert s["draft"] == pytest.approx(A, rel=1e-9)  # half immersed at density 500
    assert s["waterplane_area"] == pytest.approx(2 * A, rel=1e-12)
    # ω² = ρgA_wp/M = ρg·2a / (ρ_b π a²) = 4g/(π a) for ρ_b = ρ/2 (hand derivation)
    assert s["heave_period"] == pytest.approx(2 * math.pi / math.sqrt(4 * 9.81 / (math.pi * A)),
                                              rel=1e-9)
    assert s["heave_period"] == pytest.approx(0.491, abs=5e-4)  # the 0.491 s
    # a circle's metacentre is its centre: GM = a − KG = 0 with G on the axis
    assert s["verdict_roll"] == "neutral" and s["roll_period"] is None
    assert s["KB"] == pytest.approx(A - 4 * A / (3 * math.pi), rel=1e-12)


@pytest.mark.parametrize("z_g, verdict", [(-0.01, "oscillates"), (0.01, "capsizes")])
def test_circle_verdict_follows_cog(z_g, verdict):
    s = theory_summary(load_case("cylinder_heave", [f"mass.cog=[0.0, 0.0, {z_g}]"])).to_dict()
    assert s["verdict_roll"] == verdict
    assert s["GM_roll"] == pytest.approx(-z_g, rel=1e-9)  # GM = a − KG


def test_sphere_metacentric_height_by_hand():
    """Half-immersed sphere: KB = a − 3a/8, BM = (πa⁴/4)/(2πa³/3) = 3a/8, so GM = a − KG."""
    s = theory_summary(load_case("sphere")).to_dict()
    a, kg = 0.1, 0.08
    assert s["KB"] == pytest.approx(a - 3 * a / 8, rel=1e-12)
    assert s["BM_roll"] == pytest.approx(3 * a / 8, rel=1e-12)
    assert s["GM_roll"] == pytest.approx(a - kg, rel=1e-9)
    k = 0.06325
    expected = 2 * math.pi * math.sqrt(k * k / (9.81 * (a - kg)))  # M = ρV at equilibrium
    assert s["roll_period"] == pytest.approx(expected, rel=1e-9)


def test_stiffness_symmetric_and_consistent():
    case = load_case("ellipsoid")
    c = stiffness_matrix(case)
    np.testing.assert_allclose(c, c.T, atol=1e-12)
    s = theory_summary(case).to_dict()
    rgv = 1000 * 9.81 * s["displaced_volume"]
    assert c[1, 1] == pytest.approx(rgv * s["GM_roll"], rel=1e-12)
    assert c[0, 0] == pytest.approx(1000 * 9.81 * s["waterplane_area"], rel=1e-12)


def test_off_axis_cog_heels_until_b_is_under_g():
    case = load_case("box_bilge", ["mass.cog=[0.0, 0.01, 0.0]"])
    eq = equilibrium(case)
    assert eq.heel != 0.0
    assert eq.immersed.volume == pytest.approx(case.displacement, rel=1e-9)
    # GZ vanishes at the equilibrium heel
    assert righting_arm(case, eq.heel) == pytest.approx(0.0, abs=1e-9)
    # towards G's side (positive y → negative heel with R_x), where the wall-sided righting
    # arm of the symmetric box balances the lever of G: sin φ (GM + ½BM tan²φ) = y_G cos φ
    s = theory_summary(load_case("box_bilge")).to_dict()
    phi = -eq.heel
    assert phi > 0
    lhs = math.sin(phi) * (s["GM_roll"] + 0.5 * s["BM_roll"] * math.tan(phi) ** 2)
    assert lhs == pytest.approx(0.01 * math.cos(phi), rel=1e-5)


@pytest.mark.parametrize("z_g", [-0.02, 0.0, 0.015])
@pytest.mark.parametrize("method", ["auto", "numeric"])
def test_circle_gz_at_all_angles(z_g, method):
    """GZ = (a − KG)·sin θ for a circular cylinder at every angle (the buoyancy always acts
    through the centre). Numeric path: polygon of 2048 vertices, error ~1e-7 m."""
    case = load_case("cylinder_heave", [f"mass.cog=[0.0, 0.0, {z_g}]", "mass.density=380"])
    tol = 1e-12 if method == "auto" else 2e-7
    for deg in range(0, 181, 15):
        theta = math.radians(deg)
        gz = righting_arm(case, theta, method=method)
        assert gz == pytest.approx(-z_g * math.sin(theta), abs=tol)


def test_box_gz_wall_sided_formula():
    """Wall-sided formula GZ = sin φ (GM + ½ BM tan² φ) (e.g. Rawson & Tupper, Basic Ship
    Theory, §4) holds while the waterline stays on the vertical sides: up to deck-edge
    immersion (tan φ = (D − T)/(B/2), 33.7°) and bilge emergence (tan φ = (T − r)/(B/2),
    25.0° here). Checked to 24°, to 1e-7 m (polygon accuracy)."""
    case = load_case("box_bilge")
    s = theory_summary(case).to_dict()
    for deg in np.arange(0.0, 24.1, 2.0):
        phi = math.radians(deg)
        expected = math.sin(phi) * (s["GM_roll"] + 0.5 * s["BM_roll"] * math.tan(phi) ** 2)
        assert righting_arm(case, phi) == pytest.approx(expected, abs=1e-7)


def test_gz_curve_vanishing_angle_box():
    curve = gz_curve(load_case("box_bilge"), max_angle=120.0, step=2.0)
    assert curve.gz[0] == pytest.approx(0.0, abs=1e-12)
    assert curve.vanishing_angle is not None and 45.0 < curve.vanishing_angle < 120.0
    assert np.all(curve.gz[1:10] > 0)


def test_capsizing_body_has_zero_vanishing_angle():
    curve = gz_curve(load_case("parabolic_cylinder"), max_angle=30.0, step=5.0)
    assert curve.vanishing_angle == 0.0 and curve.gz[1] < 0


@pytest.mark.parametrize("case", ["cylinder_heave", "sphere", "ellipsoid", "elliptic_cylinder",
                                  "parabolic_cylinder"])
def test_memoir_method_matches_exact_theory(case):
    """floatfoam.hydrostatics.memoir (the memoir's method, derived by hand in docs/memoir.md) and
    the hydrostatics engine are independent derivations of the same linear theory."""
    s = theory_summary(load_case(case)).to_dict()
    memoir = s["memoir"]
    assert memoir["source"] == "reconstructed"
    for key in ("draft", "waterplane_area", "KB", "BM_roll", "heave_period"):
        assert memoir[key] == pytest.approx(s[key], rel=1e-9), key
    assert memoir["verdict_roll"] == s["verdict_roll"]
    if s["roll_period"] is not None:
        assert memoir["roll_period"] == pytest.approx(s["roll_period"], rel=1e-9)
