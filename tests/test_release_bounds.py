"""Bounds of the inputs that size or place a computation: a decay model's --duration (the
series' memory), the GZ curve's --step, the fluid's depth against the draft, and the release
inside the tank. Each bad value is one line on stderr and exit 2, before anything is written,
in every command that takes it; the library raises InputError naming the key and its valid
range."""

from __future__ import annotations

import math
import re
import time

import numpy as np
import pytest

from floatfoam.bodies.geometry import rotation
from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.errors import InputError
from floatfoam.foam import domain
from floatfoam.hydrostatics.fluid_domain import check_release
from floatfoam.hydrostatics.gz import MAX_STEPS, check_angles, gz_curve
from floatfoam.hydrostatics.theory import equilibrium
from floatfoam.plan.release import release_state
from floatfoam.potential.bounded import Heartbeat
from floatfoam.potential.models import BYTES_PER_SAMPLE, SERIES_MEMORY, check_duration, decay_series
from floatfoam.potential.rigid_body import _to_earth, yaw_matrix
from floatfoam.potential.timedomain import cummins_decay
from floatfoam.tank import Pose


def refused(capsys, argv) -> str:
    """The one stderr line of ``floatfoam argv``, which must exit 2."""
    code = main(argv)
    lines = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(lines) == 1, (code, lines)
    assert "Traceback" not in lines[0]
    return lines[0]


class Recorder:
    """A progress listener that remembers what it heard."""

    def __init__(self):
        self.stages, self.done = [], []

    def stage(self, what, total=None, unit=""):
        self.stages.append((what, total, unit))

    def update(self, done):
        self.done.append(done)


# --- 1. decay-model --duration: bounded by the series' memory -------------------------------

@pytest.mark.parametrize("duration", ["1e9", "1e6"])
def test_a_duration_beyond_the_series_memory_is_one_line(capsys, build, duration):
    """1e9 s was a MemoryError (exit 1); 1e6 s ran over a minute in silence. The sphere's
    step is 2.59 ms: 3.9e8 samples for 1e6 s, ~138 GiB."""
    line = refused(capsys, ["decay-model", "sphere", "--model", "linear", "--duration",
                            duration])
    assert f"--duration {float(duration):g} s" in line and "GiB" in line
    assert "valid is 0.00259 s (one step) to 7241.66 s" in line
    assert not build.exists()


@pytest.mark.parametrize("duration", ["0", "-3", "nan", "inf", "1e-9"])
def test_a_duration_that_is_no_time_is_one_line(capsys, build, duration):
    line = refused(capsys, ["decay-model", "sphere", "--model", "nonlinear", "--duration",
                            duration])
    assert line.startswith("floatfoam decay-model: error: --duration ") and "valid is" in line
    assert not build.exists()


def test_the_duration_bound_is_the_memory_cap():
    dt = 0.01
    longest = (SERIES_MEMORY // BYTES_PER_SAMPLE - 1) * dt
    assert check_duration(longest, dt) * BYTES_PER_SAMPLE <= SERIES_MEMORY
    with pytest.raises(InputError, match=r"^--duration .* would need ~1 GiB .* to 27962"):
        check_duration(longest + dt, dt)
    with pytest.raises(InputError, match=r"^--duration \(default: ten of the longest period\)"):
        check_duration(1e9, dt, given=False)


def test_the_library_refuses_before_it_allocates():
    """decay_series checks before np.arange: no MemoryError, however long."""
    with pytest.raises(InputError, match=re.escape("--duration 1e+300 s: 3.86e+302 samples")):
        decay_series(load_case("sphere"), "linear", duration=1e300)


def test_a_heartbeat_speaks_only_once_a_stage_runs(capsys):
    with Heartbeat("sphere: decay-model", every=0.02) as beat:
        time.sleep(0.1)  # the input's checks: silent, so a bad input stays one line
        assert capsys.readouterr().err == ""
        beat.stage("nonlinear model", total=10.0, unit="s simulated")
        beat.update(5.0)
        time.sleep(0.1)
        beat.stage("analysing 1,000 samples")
        time.sleep(0.1)
    lines = capsys.readouterr().err.splitlines()
    counted = [x for x in lines if x.startswith("[sphere: decay-model] nonlinear model: "
                                               "5/10 s simulated, 0 s, ETA ")]
    plain = [x for x in lines if x.startswith("[sphere: decay-model] analysing 1,000 samples, ")]
    assert counted and plain and len(counted) + len(plain) == len(lines)


def test_the_models_report_how_far_they_are():
    heard = Recorder()
    series = decay_series(load_case("sphere"), "nonlinear", duration=0.3, progress=heard)
    assert heard.stages == [("nonlinear model", pytest.approx(series["time"][-1]),
                             "s simulated")]
    assert heard.done and max(heard.done) == pytest.approx(series["time"][-1])
    heard = Recorder()
    t = np.linspace(0.0, 1.0, 11)
    cummins_decay([[1.0]], [[1.0]], [[0.0]], [0.0, 1.0], np.zeros((2, 1, 1)), [1.0], t,
                  progress=heard)
    assert heard.done == pytest.approx(t[1:])


def test_angular_velocity_in_earth_axes_is_the_rotation_of_each_sample():
    """The long series' rotation to earth axes is one array pass; it is R_z R_y R_x ω."""
    rng = np.random.default_rng(3)
    heel, trim, yaw = rng.uniform(-3, 3, (3, 50))
    omega = rng.normal(size=(50, 3))
    looped = [yaw_matrix(c) @ rotation(a, b) @ w
              for a, b, c, w in zip(heel, trim, yaw, omega, strict=True)]
    assert np.allclose(_to_earth(heel, trim, yaw, omega), looped, rtol=0, atol=1e-14)


# --- 2. gz --step: at most MAX_STEPS angles -------------------------------------------------

@pytest.mark.parametrize("step", ["1e-9", "nan", "0", "-1", "100"])
def test_a_gz_step_out_of_range_is_one_line(capsys, build, step):
    line = refused(capsys, ["gz", "sphere", "--step", step])
    assert f"--step {float(step):g}" in line and "valid is 0.09 ≤ DEG ≤ --max-angle 90" in line
    assert not build.exists()


def test_the_finest_gz_step_is_a_thousand_steps():
    assert check_angles(90.0, 90.0 / MAX_STEPS) == MAX_STEPS + 1
    with pytest.raises(InputError, match=r"^--step 0.0899: gives 1e\+03 steps"):
        check_angles(90.0, 0.0899)
    with pytest.raises(InputError, match=r"^--max-angle 200: valid is 0 < DEG ≤ 180"):
        gz_curve(load_case("sphere"), 200.0, 1.0)
    heard = Recorder()
    gz_curve(load_case("sphere"), 10.0, 1.0, progress=heard)
    assert heard.stages == [("GZ curve", 11, "angles")] and heard.done == list(range(1, 12))


# --- 3. the release inside the tank, in every command that takes one ------------------------

SPHERE_HEAVE = "valid is -1.9 < heave < 0.5 m"  # a 0.1 m sphere at z_c = 0, tank 2 m + 0.6 m


@pytest.mark.parametrize("argv", [
    ["decay-model", "sphere", "--model", "nonlinear"],
    ["decay-model", "sphere", "--model", "linear"],
    ["mesh", "domain", "sphere"],
    ["mesh", "body", "sphere", "--pose", "release"],
])
@pytest.mark.parametrize("heave, where", [(-2, "lowest point at z = -2.1 m, on or below the "
                                               "tank's bottom (z = -2 m: domain.depth's "
                                               "default"),
                                          (0.6, "top at z = 0.7 m, at or above the tank's top "
                                                "(z = 0.6 m: domain.air_height's default")])
def test_a_release_out_of_the_tank_is_one_line(capsys, build, argv, heave, where):
    """decay-model released the sphere 2 m down, below its tank's (default) bottom, and
    printed a period."""
    line = refused(capsys, [*argv, "--set", f"release.heave={heave}"])
    assert f"release.heave = {heave:g} m puts the body's {where}" in line
    assert line.endswith(f"{SPHERE_HEAVE} (the body inside the tank)")
    assert not build.exists()


def test_a_release_angle_out_of_the_tank_names_its_largest():
    """ellipsoid_roll (semi-axes 0.2, 0.15, 0.1 m) under 0.12 m of air: turned by φ its top
    is at √((0.15 sin φ)² + (0.1 cos φ)²), 0.12 m at φ = 36.4°."""
    case = load_case("ellipsoid_roll", ["domain.air_height=0.12", "release.heel=60"])
    with pytest.raises(InputError) as err:
        decay_series(case, "nonlinear", duration=0.1)
    text = str(err.value)
    assert text.startswith("release.heel = 60° puts the body's top at z = 0.1") and \
        "domain.air_height = 0.12 m" in text
    limit = float(text.split("up to heel +")[1].split("°")[0])
    assert limit == pytest.approx(math.degrees(math.asin(math.sqrt(0.0044 / 0.0125))), abs=0.3)
    inside = load_case("ellipsoid_roll", ["domain.air_height=0.12", f"release.heel={limit}"])
    assert check_release(inside, equilibrium(inside)).heel == pytest.approx(
        math.radians(limit))


def test_a_drop_from_above_the_water_is_a_valid_release():
    """lab_sphere_05D's lowest point starts 0.06 mm above the still water (a 0.5 D drop)."""
    case = load_case("lab_sphere_05D")
    eq = equilibrium(case)
    where = check_release(case, eq)
    assert where.z_c - 0.15 > 0.0
    assert len(decay_series(case, "nonlinear", duration=0.2)["time"]) > 1


@pytest.mark.parametrize("setting, text", [
    ("domain.depth=0.05", "domain.depth = 0.05 m puts the tank's bottom (z = -0.05 m) at or "
                          "above the body's keel at equilibrium (z = -0.1 m); valid is a depth "
                          "greater than 0.1 m"),
    ("domain.air_height=0.05", "domain.air_height = 0.05 m puts the tank's top (z = 0.05 m) at "
                               "or below the body's top at equilibrium (z = 0.1 m)"),
])
def test_a_tank_that_does_not_hold_the_body_at_rest_names_the_tank(setting, text):
    case = load_case("sphere", [setting])
    with pytest.raises(InputError, match="^" + text.replace("(", r"\(").replace(")", r"\)")):
        check_release(case, equilibrium(case))


# --- 4. the depth against the draft, in every command ---------------------------------------

@pytest.mark.parametrize("argv", [["theory", "sphere"], ["gz", "sphere"],
                                  ["potential", "sphere"],
                                  ["decay-model", "sphere", "--model", "linear"],
                                  ["mesh", "domain", "sphere"]])
def test_water_shallower_than_the_draft_is_one_line(capsys, build, argv):
    """theory and gz took 0.01 m of water under a body of draft 0.1 m."""
    line = refused(capsys, [*argv, "--set", "fluid.depth=0.01"])
    assert line.endswith("error: fluid.depth = 0.01 m: the body floats with its keel 0.1 m "
                         "below the still water (its draft), on or below the bottom; valid is "
                         "a depth greater than the draft, 0.1 m")
    assert not build.exists()


def test_the_depth_is_checked_with_the_equilibrium():
    """A 2D section too (potential's own check for sections moved here), heeled or not."""
    for name, draft in (("cylinder_heave", 0.0762), ("sphere", 0.1)):
        with pytest.raises(InputError, match=f"greater than the draft, {draft:g} m$"):
            equilibrium(load_case(name, [f"fluid.depth={draft}"]))
        assert equilibrium(load_case(name, [f"fluid.depth={draft * 1.01}"])).z_c == \
            pytest.approx(equilibrium(load_case(name)).z_c, abs=1e-9)


# --- 5. run: one line, before gmsh and the build folder -------------------------------------

@pytest.fixture
def no_mesh(monkeypatch, tmp_path):
    """A solver file (run checks it exists) and a mesh stage that fails the test if run
    reaches it: the release must be refused first."""
    solver = tmp_path / "interFoam"
    solver.write_text("")

    def reached(*args, **kwargs):
        raise AssertionError("run planned or made a mesh")

    monkeypatch.setattr(domain, "plan", reached)
    monkeypatch.setattr(domain, "generate", reached)
    return f'run.solver="{solver}"'


def test_run_refuses_a_release_below_the_bottom_first(capsys, build, no_mesh):
    """It printed a warning ("an outer distance of at most -3.1 m"), a gmsh line, then the
    error."""
    line = refused(capsys, ["run", "sphere", "--set", "release.heave=-5", "--set", no_mesh])
    assert line.startswith("floatfoam run: error: release.heave = -5 m puts the body's lowest "
                           "point at z = -5.1 m") and SPHERE_HEAVE in line
    assert not build.exists()


def test_the_bottom_warning_never_suggests_a_negative_distance():
    case = load_case("sphere", ['run.mesh_motion="distances"'])  # the warning's motion
    state = release_state(case, equilibrium(case))
    mesh = domain.plan(case, "coarse", state["pose"])  # inner 0.06 m, outer 0.32 m
    below = domain.clamped_bottom(mesh, case, Pose(z_c=-5.0))
    assert "at most -" not in below and "reaches 3.1 m past the tank's bottom" in below
    close = domain.clamped_bottom(mesh, case, Pose(z_c=-1.87))  # 0.03 m over the bottom
    assert "inner and outer distances below 0.03 m keep the bottom out of the zone" in close
    assert domain.clamped_bottom(mesh, case, state["pose"]) is None


# --- 6. the O-grid case: the release named, with its range ----------------------------------

@pytest.mark.parametrize("heave, where", [(-1.2, "lowest point at z = -1.276 m"),
                                          (0.5, "top at z = 0.5762 m")])
def test_an_ogrid_release_out_of_its_tank_names_the_release(capsys, build, monkeypatch,
                                                           tmp_path, heave, where):
    solver = tmp_path / "interFoam"
    solver.write_text("")
    line = refused(capsys, ["run", "cylinder_heave", "--set", f"release.heave={heave}",
                            "--set", f'run.solver="{solver}"'])
    assert f"release.heave = {heave:g} m puts the body's {where}" in line
    assert "valid is -1.143 < heave < 0.3738 m" in line and "square_half_size" not in line
    assert not build.exists()


def test_an_ogrid_square_that_no_longer_fits_gives_the_release_range(capsys, build,
                                                                     tmp_path):
    """0.3 m up, the cylinder is inside the tank but its 0.1 m square leaves the 16 cells above
    it less than the square's 7.1 mm each (0.025 m for 0.114 m): blockMesh would shrink them to
    nothing and stop on inward-pointing faces (exit 1, the run folder written)."""
    solver = tmp_path / "interFoam"
    solver.write_text("")
    line = refused(capsys, ["run", "cylinder_heave", "--set", "release.heave=0.3", "--set",
                            f'run.solver="{solver}"', "--set", 'run.mesh_motion="laplacian"'])
    assert "mesh.square_half_size = 0.1 m: valid is 0.0762 < square_half_size ≤ 0.07 m" \
        in line and line.endswith("release.heave from -0.9049 to 0.2357 m fits this square")
    assert not build.exists()
