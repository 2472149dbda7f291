"""Time-domain decay models: linear (exact), Cummins (memory, energy), the rigorous nonlinear
rigid body (small-amplitude period, energy, GZ statics), and the decay-model command."""

import argparse
import csv
import math

import numpy as np
import pytest

from floatfoam.bodies.geometry import rotation
from floatfoam.bodies.shapes import EllipticCylinder
from floatfoam.case import load_case
from floatfoam.errors import InputError
from floatfoam.hydrostatics.gz import righting_arm
from floatfoam.hydrostatics.theory import (
    equilibrium,
    sinkage_for_volume,
    stiffness_matrix,
    theory_summary,
)
from floatfoam.motion import MOTION_COLUMNS
from floatfoam.potential import sections as section_bem
from floatfoam.potential.models import decay_series
from floatfoam.potential.rigid_body import RigidBody, nonlinear_decay
from floatfoam.potential.timedomain import (
    cummins_decay,
    energy,
    linear_decay,
    ogilvie_added_mass_inf,
    retardation_kernel,
)

MASS = np.diag([2.0, 0.5, 0.7])
STIFFNESS = np.array([[20.0, 1.0, 0.0], [1.0, 3.0, 0.2], [0.0, 0.2, 5.0]])
X0 = np.array([0.1, 0.05, -0.02])


def test_linear_decay_is_exact():
    t = np.linspace(0.0, 10.0, 501)
    x, v = linear_decay([[2.0]], [[18.0]], [0.1], t)
    np.testing.assert_allclose(x[:, 0], 0.1 * np.cos(3.0 * t), atol=1e-14)
    np.testing.assert_allclose(v[:, 0], -0.3 * np.sin(3.0 * t), atol=1e-14)
    x, _ = linear_decay([[2.0]], [[-8.0]], [0.1], t)  # GM < 0: it capsizes
    np.testing.assert_allclose(x[:, 0], 0.1 * np.cosh(2.0 * t), rtol=1e-12)
    x, v = linear_decay(MASS, STIFFNESS, X0, t)
    e = energy(MASS, STIFFNESS, x, v)
    assert np.ptp(e) < 1e-12 * e[0]


def test_cummins_without_radiation_is_the_linear_model():
    """No memory and A∞ = 0: the trapezoidal scheme follows the exact solution to its phase
    error (ωh)²/12 per radian (h ≈ T/900 here: < 1e-3 of the amplitude over 6 periods) and
    conserves the energy to round-off."""
    t = np.linspace(0.0, 12.0, 4801)
    zero_kernel = np.zeros((2, 3, 3))
    x_lin, v_lin = linear_decay(MASS, STIFFNESS, X0, t)
    x, v = cummins_decay(MASS, STIFFNESS, np.zeros((3, 3)), np.array([0.0, 1.0]), zero_kernel,
                         X0, t)
    assert np.abs(x - x_lin).max() < 1e-3 * np.abs(X0).max()
    e = energy(MASS, STIFFNESS, x, v)
    assert np.ptp(e) < 1e-10 * e[0]
    # with A∞ only, it is the linear model of mass M + A∞
    a_inf = np.diag([0.4, 0.1, 0.0])
    x, _ = cummins_decay(MASS, STIFFNESS, a_inf, np.array([0.0, 1.0]), zero_kernel, X0, t)
    x_lin, _ = linear_decay(MASS + a_inf, STIFFNESS, X0, t)
    assert np.abs(x - x_lin).max() < 1e-3 * np.abs(X0).max()


def test_retardation_kernel_of_a_known_transform():
    """B(ω) = ω² e^{−ω²} gives K(t) = (2/π)∫B cos ωt dω = (1/√π)(½ − t²/4) e^{−t²/4}."""
    omega = np.linspace(0.1, 6.0, 60)
    t = np.linspace(0.0, 8.0, 81)
    kernel = retardation_kernel(omega, omega**2 * np.exp(-(omega**2)), t)
    exact = (0.5 - t**2 / 4.0) * np.exp(-(t**2) / 4.0) / math.sqrt(math.pi)
    assert np.abs(kernel - exact).max() < 2e-3 * exact[0]


@pytest.fixture(scope="module")
def cylinder_coefficients():
    """Heave of the half-immersed circular cylinder a = 1 m, per metre (2D panel method)."""
    nodes = section_bem.panel_nodes(section_bem.wetted_contour(
        EllipticCylinder(1.0, 1.0, 1.0).section_polygon(), 0.0, 0.0))
    omega = np.linspace(0.05, 2.5, 50) * math.sqrt(9.81)
    res = section_bem.radiation_coefficients_2d(nodes, [*omega, np.inf])
    return omega, res["added_mass"][:-1, 1, 1], res["damping"][:-1, 1, 1], \
        res["added_mass"][-1, 1, 1]


def test_ogilvie_relation_recovers_a_inf(cylinder_coefficients):
    """A∞ = A(ω) + (1/ω)∫K sin ωt dt at every frequency (Ogilvie 1964) equals the panel
    method's infinite-frequency solve. 0.5 %: K is built from B sampled at 50 frequencies
    (the lowest ω, where the 2D heave A diverges logarithmically, are left out)."""
    omega, added, damping, a_inf = cylinder_coefficients
    t = np.linspace(0.0, 2 * math.pi / (omega[1] - omega[0]), 3000)
    kernel = retardation_kernel(omega, damping, t)
    recovered = ogilvie_added_mass_inf(omega, added, t, kernel)
    np.testing.assert_allclose(recovered[5:], a_inf, rtol=0.005)


def test_cummins_energy_never_grows(cylinder_coefficients):
    """With the radiation memory the mechanical energy ½(M + A∞)ẋ² + ½Cx² may oscillate (the
    memory gives energy back) but never exceeds its initial value, and it decays."""
    omega, _, damping, a_inf = cylinder_coefficients
    rho, g = 1000.0, 9.81
    mass, stiffness = rho * math.pi / 2.0, rho * g * 2.0
    period = 2 * math.pi * math.sqrt((mass + a_inf) / stiffness)
    t = np.arange(0.0, 8 * period, period / 200)
    kernel = retardation_kernel(omega, damping[:, None, None], t)
    x, v = cummins_decay([[mass]], [[stiffness]], [[a_inf]], t, kernel, [0.1], t)
    e = energy([[mass + a_inf]], [[stiffness]], x, v)
    assert e.max() <= e[0] * (1.0 + 1e-9)
    assert e[-1] < 0.05 * e[0]


def _zero_crossing_period(t, y):
    up = np.nonzero((y[:-1] < 0.0) & (y[1:] >= 0.0))[0]
    times = t[up] - y[up] * (t[up + 1] - t[up]) / (y[up + 1] - y[up])
    return float(np.diff(times).mean())


def _released(case, dz=0.0, dheel=0.0, periods=4, key="roll_period"):
    eq = equilibrium(case)
    z_g = float((rotation(eq.heel, eq.trim) @ case.cog)[2] + eq.z_c)
    period = theory_summary(case).to_dict()[key]
    t = np.linspace(0.0, periods * period, 200 * periods + 1)
    res = nonlinear_decay(RigidBody.from_case(case), z_g + dz, eq.heel + dheel, eq.trim, t)
    return eq, z_g, period, res


@pytest.mark.parametrize("name", ["box_bilge", "ellipsoid", "elliptic_cylinder"])
def test_nonlinear_small_amplitude_roll_period_is_linear(name):
    """Released at 0.5° the rigorous model rolls with Le Barbier's linear period: 0.2 %
    (the amplitude correction ∝ φ₀² is ~1e-4 here; DOP853 at rtol 1e-10)."""
    case = load_case(name)
    eq, _, period, res = _released(case, dheel=math.radians(0.5))
    assert _zero_crossing_period(res["time"], res["heel"] - eq.heel) == \
        pytest.approx(period, rel=0.002)


def test_nonlinear_small_heave_period_and_energy():
    case = load_case("sphere")
    _, z_g, period, res = _released(case, dz=0.001, key="heave_period")
    assert _zero_crossing_period(res["time"], res["z"] - z_g) == pytest.approx(period, rel=0.002)
    rigid = RigidBody.from_case(case)
    e = np.array([rigid.energy(res["z"][i], res["heel"][i], res["trim"][i], res["w"][i],
                               res["omega_body"][i]) for i in range(0, len(res["time"]), 40)])
    e_eq = rigid.energy(z_g, 0.0, 0.0, 0.0, np.zeros(3))
    assert np.ptp(e) < 1e-6 * (e[0] - e_eq)


def test_large_heel_changes_the_period():
    """The box's GZ curve stiffens past the wall-sided range (GZ = sinφ(GM + ½BM tan²φ)): at
    30° the roll period is clearly shorter than the linear one."""
    case = load_case("box_bilge")
    eq, _, period, res = _released(case, dheel=math.radians(30.0))
    assert _zero_crossing_period(res["time"], res["heel"] - eq.heel) < 0.95 * period


@pytest.mark.parametrize("heel_deg", [10.0, 20.0, 30.0])
def test_nonlinear_restoring_moment_is_the_gz_curve(heel_deg):
    """At constant displacement the rigorous model's moment about G is −ρgV·GZ, with GZ from
    floatfoam.hydrostatics.gz and, for a circle with G a distance OG below its centre, GZ = OG sin φ
    exactly (B stays below the centre)."""
    og = 0.02
    case = load_case("cylinder_heave", [f"mass.cog=[0.0, 0.0, {-og}]"])
    heel = math.radians(heel_deg)
    z_c, imm = sinkage_for_volume(case, case.displacement, heel)
    rigid = RigidBody.from_case(case)
    z_g = z_c + float((rotation(heel, 0.0) @ case.cog)[2])
    force, moment, _ = rigid.hydrostatics(z_g, heel, 0.0)
    rgv = case.rho * case.g * imm.volume
    assert abs(force) < 1e-8 * rgv
    assert moment[0] == pytest.approx(-rgv * righting_arm(case, heel), rel=1e-9)
    assert moment[0] == pytest.approx(-rgv * og * math.sin(heel), rel=1e-5)


def test_wall_sided_box_gz():
    """Box section, waterline on its vertical walls (below 20°): the moment is the wall-sided
    formula −ρgV sinφ (GM + ½ BM tan²φ) (e.g. Rawson & Tupper, Basic Ship Theory, §4)."""
    case = load_case("box_bilge")
    eq = equilibrium(case)
    rigid = RigidBody.from_case(case)
    volume = case.displacement
    gm = stiffness_matrix(case, eq)[1, 1] / (case.rho * case.g * volume)
    bm = eq.immersed.waterplane_inertia[0] / volume
    for heel in np.radians([5.0, 10.0, 15.0]):
        z_c, _ = sinkage_for_volume(case, volume, heel)
        _, moment, _ = rigid.hydrostatics(z_c + float((rotation(heel, 0.0) @ case.cog)[2]),
                                          heel, 0.0)
        wall_sided = -case.rho * case.g * volume * math.sin(heel) * (
            gm + 0.5 * bm * math.tan(heel) ** 2)
        assert moment[0] == pytest.approx(wall_sided, rel=1e-6)


def test_negative_gm_capsizes_linear_and_nonlinear():
    """G raised above the metacentre: the linear solution grows exponentially (so the linear
    decay model refuses such a body, issue 13); the rigorous one leaves the upright position
    and lolls to large angles."""
    case = load_case("box_bilge", ["mass.cog=[0.0, 0.0, 0.06]", "release.heel=1.0"])
    eq = equilibrium(case)
    stiffness = stiffness_matrix(case, eq)
    mass = np.diag([case.mass, case.mass * case.gyradius[0] ** 2,
                    case.mass * case.gyradius[1] ** 2])
    t = np.linspace(0.0, 1.0, 201)
    x, _ = linear_decay(mass, stiffness, [0.0, math.radians(1.0), 0.0], t)
    assert abs(math.degrees(x[-1, 1])) > 5.0
    with pytest.raises(InputError, match=r"roll capsizes \(GM = -"):
        decay_series(case, "linear", duration=1.0)
    nonlinear = decay_series(case, "nonlinear", duration=3.0)
    assert np.abs(nonlinear["roll"]).max() > 10.0


def _cli(argv):
    from floatfoam.cli import decay_model

    parser = argparse.ArgumentParser()
    decay_model.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(argv)
    return args.func(args)


@pytest.mark.parametrize("model", ["linear", "nonlinear", "cummins"])
def test_cli_decay_model_writes_motion_csv(capsys, tmp_path, model):
    out = tmp_path / f"{model}.csv"
    assert _cli(["decay-model", "cylinder_heave", "--model", model, "--duration", "2",
                 "--out", str(out)]) == 0
    with out.open() as handle:
        rows = list(csv.reader(handle))
    assert tuple(rows[0]) == MOTION_COLUMNS
    first = dict(zip(rows[0], map(float, rows[1]), strict=True))
    case = load_case("cylinder_heave")
    eq = equilibrium(case)
    assert first["z"] == pytest.approx(eq.z_c + case.release["heave"], abs=1e-9)
    assert float(rows[-1][0]) == pytest.approx(2.0, abs=0.01)
    text = capsys.readouterr().out
    assert "period" in text
