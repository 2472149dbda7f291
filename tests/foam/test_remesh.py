"""A run's mesh made anew at the body's pose (floatfoam.foam.remesh), without the solver: when
it fires, the pose it reads from the body's six-DoF state, the solver asked to stop, the mesh
made at a pose met on the way. (The remeshed runs: tests/cfd/test_cfd_bodies.py, the capsizing
ellipse.)"""

import math

import numpy as np
import pytest
from conftest import ROOT

from floatfoam.bodies.geometry import rotation
from floatfoam.case import load_case
from floatfoam.errors import InputError
from floatfoam.foam import remesh
from floatfoam.foam.logwatch import Step
from floatfoam.foam.runner import RunError, stop_at_write_now
from floatfoam.hydrostatics.immersion import immersed
from floatfoam.meshing.domains import build_domain
from floatfoam.tank import Pose


class _Mesh:
    def __init__(self, kind, motion="distances"):
        self.kind, self.motion = kind, motion


def test_turn_angle_is_the_rotation_between_two_attitudes():
    q0 = rotation(math.radians(5.0), 0.0)
    for heel in (5.0, 20.0, 35.0, 120.0, 180.0):
        q = rotation(math.radians(heel), 0.0)
        assert math.degrees(remesh.turn_angle(q, q0)) == pytest.approx(heel - 5.0, abs=1e-9)
    # heel and trim together: the angle of the one rotation between them, not their sum
    both = rotation(math.radians(30.0), math.radians(40.0))
    expected = math.degrees(math.acos(math.cos(math.radians(30)) * math.cos(math.radians(40))
                                      * 0.5 + 0.5 * (math.cos(math.radians(30))
                                                     + math.cos(math.radians(40))) - 0.5))
    assert math.degrees(remesh.turn_angle(both, np.eye(3))) == pytest.approx(expected, 1e-9)


def test_the_trigger_fires_at_the_first_step_past_the_angle():
    attitude = rotation(math.radians(5.0), 0.0)
    trigger = remesh.Trigger(attitude, math.radians(30.0))
    steps = [Step(time=0.1 * i, orientation=rotation(math.radians(5.0 + 10.0 * i), 0.0))
             for i in range(3)]  # 0°, 10°, 20° of turn
    assert trigger.check(steps) is None
    reason = trigger.check([Step(time=0.3, orientation=rotation(math.radians(35.1), 0.0))])
    assert reason and "30.1°" in reason and "run.remesh_angle = 30°" in reason


def test_which_runs_are_remeshed():
    case = load_case("ellipsoid_printed_verdict")
    assert remesh.applies(case, _Mesh("3d-half"))
    assert remesh.applies(case, _Mesh("2d"))
    assert not remesh.applies(case, _Mesh("3d-half", "laplacian"))  # its state: a point field
    assert not remesh.applies(case, _Mesh("wedge"))  # upright: nothing to turn
    assert not remesh.applies(case, _Mesh("ogrid"))
    assert not remesh.applies(load_case("ellipsoid_printed_verdict", ["run.remesh_angle=0"]),
                              _Mesh("3d-half"))


@pytest.mark.parametrize("value", ["-1", "181"])
def test_a_remesh_angle_out_of_range_is_refused(value):
    with pytest.raises(InputError, match="run.remesh_angle"):  # the CLI's exit 2
        load_case("ellipsoid_printed_verdict", [f"run.remesh_angle={value}"])


@pytest.mark.parametrize("kind, x_c, heel, trim", [
    ("3d-half", 0.0, 127.3, 0.0), ("3d-half", 0.0, -172.2, 0.0),  # turned over, past 180°
    ("3d", 0.02, 20.0, 120.0),  # pitched past 90° (Euler angles would give roll 180° there)
    ("2d", 0.0, 97.0, 0.0)])
def test_the_pose_read_back_from_the_body_state(kind, x_c, heel, trim):
    """G and the attitude of a body met on its way give back the pose that placed it."""
    case = load_case("ellipsoid_printed_verdict")
    where = Pose(z_c=-0.031, heel=math.radians(heel), trim=math.radians(trim), x_c=x_c,
                 y_c=-0.0335)
    q = rotation(where.heel, where.trim)
    cog = np.array([where.x_c, where.y_c, where.z_c]) + q @ np.asarray(case.cog)
    found = remesh.pose_of(case, _Mesh(kind), {"orientation": q, "cog": cog})
    for name in ("z_c", "heel", "trim", "x_c", "y_c"):
        assert getattr(found, name) == pytest.approx(getattr(where, name), abs=1e-12)


def test_a_turn_about_the_vertical_is_refused():
    case = load_case("ellipsoid_printed_verdict")
    yawed = np.array([[math.cos(0.1), -math.sin(0.1), 0.0], [math.sin(0.1), math.cos(0.1), 0.0],
                      [0.0, 0.0, 1.0]])
    with pytest.raises(RunError, match="about the vertical"):
        remesh.pose_of(case, _Mesh("3d"), {"orientation": yawed, "cog": np.zeros(3)})


def test_the_solver_is_asked_to_write_now_and_the_end_time_put_back(tmp_path):
    (tmp_path / "system").mkdir()
    source = (ROOT / "cases" / "_common" / "system" / "controlDict").read_text()
    (tmp_path / "system" / "controlDict").write_text(source)
    stop_at_write_now(tmp_path)
    text = (tmp_path / "system" / "controlDict").read_text()
    assert "stopAt writeNow;" in text and "runTimeModifiable yes;" in text
    assert text.replace("stopAt writeNow;", "") == source.replace(
        "stopAt            endTime;", "")
    stop_at_write_now(tmp_path, False)
    assert "stopAt endTime;" in (tmp_path / "system" / "controlDict").read_text()


def test_the_body_state_gives_g_from_the_centre_of_rotation(tmp_path):
    """v1912's centreOfMass(): the centre of rotation + Q·Q₀ᵀ·(initial G − initial centre of
    rotation); here the constraints' centre lies 0.1 m below G and the body has turned 90°."""
    (tmp_path / "constant").mkdir()
    (tmp_path / "0.5" / "uniform").mkdir(parents=True)
    (tmp_path / "constant" / "dynamicMeshDict").write_text(
        "FoamFile { version 2.0; format ascii; class dictionary; object dynamicMeshDict; }\n"
        "sixDoFRigidBodyMotionCoeffs { centreOfMass (0 0 0.1); orientation (1 0 0 0 1 0 0 0 1);"
        " constraints { inPlane { sixDoFRigidBodyMotionConstraint plane;"
        " centreOfRotation (0 0 0); normal (1 0 0); } } }\n")
    turned = rotation(math.radians(90.0), 0.0)
    (tmp_path / "0.5" / "uniform" / "sixDoFRigidBodyMotionState").write_text(
        "FoamFile { version 2.0; format ascii; class dictionary; "
        "object sixDoFRigidBodyMotionState; }\n"
        "centreOfRotation (0 0.02 -0.01);\n"
        f"orientation ({' '.join(f'{v:.17g}' for v in turned.ravel())});\n")
    state = remesh.body_state(tmp_path, "0.5")
    assert state["cog"] == pytest.approx([0.0, 0.02 - 0.1, -0.01], abs=1e-12)
    assert state["orientation"] == pytest.approx(turned, abs=1e-15)


@pytest.mark.parametrize("name, kind", [("elliptic_cylinder_capsize", "2d"),
                                        ("ellipsoid_printed_verdict", "3d-half"),
                                        ("stl_pontoon", "3d-half")])  # triangles, layers
def test_a_mesh_made_at_a_pose_met_on_the_way(tmp_path, name, kind):
    """A body heeled past 90° and swayed is meshed there, its body patch's immersed volume
    within 1 % of the exact body's at that pose (the discrete body's own error: −0.38 % at the
    ellipsoid's release; a body given by triangles is its triangles, and its prism layers are
    grown at that pose)."""
    case = load_case(name)
    where = Pose(z_c=-0.012, heel=math.radians(127.0), y_c=-0.03)
    result = build_domain(case, "coarse", kind, path=tmp_path / "m.msh", where=where)
    assert result["body_patch"]["immersed_exact"] == pytest.approx(
        immersed(case.body, where.z_c, where.heel, 0.0).volume, rel=1e-12)
    assert abs(result["body_patch"]["immersed_error"]) < 0.01
