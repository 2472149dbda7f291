"""A body held as a rig holds a model: ``[motion] free`` (floatfoam.settings.MotionSettings).

The fast tests check the refusals (one line naming motion.free, exit 2, nothing written), the
six-DoF constraints each choice renders, the domain it picks, and that a case without [motion]
keeps its run stamp; one test (marker ``openfoam``) runs the flume section with its sway held,
as Sundsdal et al.'s rig held it, and checks it against Cummins' model in the same DoFs.
"""

import numpy as np
import pytest

from floatfoam import fields, settings
from floatfoam.case import load_case
from floatfoam.cli import main
from floatfoam.foam.domain import plan
from floatfoam.foam.render import constraints
from floatfoam.hydrostatics.theory import equilibrium
from floatfoam.plan.release import release_state


def _mesh(case):
    return plan(case, "coarse", release_state(case, equilibrium(case))["pose"])


def _kinds(name, free=None):
    """The constraints' types and the domain of case ``name`` with ``motion.free``."""
    overrides = [] if free is None else [f"motion.free={free}"]
    case = load_case(name, overrides)
    mesh = _mesh(case)
    made = constraints(case, mesh, [0.0, 0.0, 0.0])
    return mesh.kind, {key: value["sixDoFRigidBodyMotionConstraint"]
                       for key, value in made.items()}


@pytest.mark.parametrize("name, free, kind, expected", [
    # without [motion]: what the release excites
    ("sphere", None, "wedge", {"heaveOnly": "line", "noRotation": "orientation"}),
    ("elliptic_cylinder_roll", None, "2d", {"inPlane": "plane", "oneAxis": "axis"}),
    ("ellipsoid_pitch", None, "3d-half", {"inPlane": "plane", "oneAxis": "axis"}),
    # a rig: roll alone about G (a fixed axis), heave and roll, sway and roll
    ("elliptic_cylinder_roll", '["roll"]', "2d", {"fixedPoint": "point", "oneAxis": "axis"}),
    ("flume_section_roll_sway_held", None, "2d", {"heaveOnly": "line", "oneAxis": "axis"}),
    ("elliptic_cylinder_roll", '["roll", "sway"]', "2d", {"swayOnly": "line",
                                                         "oneAxis": "axis"}),
    # a DoF out of the half domain's plane: the whole tank; both rotations: no constraint
    # holds yaw alone in v1912, so it is free with them
    ("ellipsoid_roll", '["heave", "roll", "pitch"]', "3d", {"heaveOnly": "line"}),
    # a body of revolution freed in roll leaves its wedge for a half domain
    ("sphere", '["heave", "roll"]', "3d-half", {"heaveOnly": "line", "oneAxis": "axis"}),
])
def test_each_choice_renders_its_constraints(name, free, kind, expected):
    assert _kinds(name, free) == (kind, expected)


def test_the_constraints_hold_the_right_axes():
    """The line runs along the free translation, the plane's normal is the held one, the axis
    is the free rotation's: heave and roll free (a line along z, an axis along x); sway and
    roll (a line along y); a trim's plane y = const. and its axis y."""
    def made(name, free=None):
        case = load_case(name, [] if free is None else [f"motion.free={free}"])
        return constraints(case, _mesh(case), [0.0, 0.0, 0.0])

    held = made("flume_section_roll_sway_held")
    assert held["heaveOnly"]["direction"] == [0.0, 0.0, 1.0]
    assert held["oneAxis"]["axis"] == [1.0, 0.0, 0.0]
    assert made("elliptic_cylinder_roll", '["roll", "sway"]')["swayOnly"]["direction"] == \
        [0.0, 1.0, 0.0]
    trim = made("ellipsoid_pitch")
    assert trim["inPlane"]["normal"] == [0.0, 1.0, 0.0] and trim["oneAxis"]["axis"] == \
        [0.0, 1.0, 0.0]
    assert made("elliptic_cylinder_roll")["inPlane"]["normal"] == [1.0, 0.0, 0.0]


def test_a_held_axis_is_the_centre_of_mass():
    """The point, line and plane pass through G as the solver starts (its centre of
    rotation): the roll is about an axis through G."""
    g = [0.0, 0.01, -0.02]
    for free, name in (('["roll"]', "fixedPoint"), ('["heave", "roll"]', "heaveOnly"),
                       (None, "inPlane")):
        case = load_case("elliptic_cylinder_roll", [] if free is None else
                         [f"motion.free={free}"])
        made = constraints(case, _mesh(case), g)
        assert made[name]["centreOfRotation"] == g and made["oneAxis"]["axis"] == [1, 0, 0]


@pytest.mark.parametrize("value, words", [
    ('"roll"', 'valid is a non-empty list of names'),
    ("[]", "valid is a non-empty list of names"),
    ('["roll", "yaw"]', "'yaw' is not a DoF; valid names are heave, roll, pitch, surge, sway"),
    ('["roll", "roll"]', "a DoF is named twice"),
    ('["heave"]', "the release displaces roll, which it holds"),
    ('["roll", "pitch"]', "meshed in a 2D slab, where the body cannot move in pitch; valid "
                          "names are heave, roll, sway"),
])
def test_a_bad_choice_is_one_line_and_writes_nothing(tmp_path, monkeypatch, capsys, value,
                                                     words):
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / "build"))
    code = main(["run", "elliptic_cylinder_roll", "--set", f"motion.free={value}"])
    out, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert code == 2 and out == "" and len(lines) == 1
    assert "motion.free" in lines[0] and words in lines[0]
    assert not (tmp_path / "build").exists()


def test_a_case_without_the_table_keeps_its_stamp():
    """[motion] at its default stamps nothing (runs made before it stay theirs); a choice is
    in the stamp (a run with another hold is another run)."""
    assert "motion" not in fields.stamped(settings.Settings())
    held = load_case("flume_section_roll_sway_held").settings
    assert fields.stamped(held)["motion"] == {"free": ("heave", "roll")}


def test_cummins_solves_the_dofs_the_case_frees():
    """Cummins' model takes [motion] free as the CFD does (radiation coefficients of the
    section: 2D BEM, a second)."""
    from floatfoam.potential.models import decay_series

    held = decay_series(load_case("flume_section_roll_sway_held"), "cummins", duration=0.2)
    assert held["dofs"] == ["heave", "roll"]
    assert np.all(held["y"] == held["y"][0])  # the sway held
    free = decay_series(load_case("flume_section_roll"), "cummins", duration=0.2)
    assert free["dofs"] == ["heave", "roll", "sway"]


@pytest.mark.openfoam
def test_the_flume_section_rolls_with_its_sway_held(tmp_path):
    """flume_section_roll_sway_held (the rig's sway clamped: heave and roll free), 3.0 s on one
    rank at the default step: G never leaves its vertical line, and the roll matches Cummins'
    model in heave and roll over the same 3.0 s. Measured on this record: T_d 1.2693 s against
    1.2740 s (−0.36 %), ζ 0.0440 against 0.0466 (−5.6 %); the free body's model (sway free:
    flume_section_roll) gives 1.2606 s and ζ 0.013, which the ζ check tells apart.
    Tolerances: 1 % on T_d, as the roll sections' coarse records against Cummins' (within
    1.8 %, test_cfd_bodies.test_section_roll); 20 % on ζ, which halving the step's limits
    moves by up to 3 % (docs/studies/time-step-limits.md) and the mesh motion by 1.3 % (the
    diffusivity 1/d: flume_section_roll's README), against 72 % between held and free."""
    from cfdcases import analysed, cfd, cummins

    from floatfoam.analysis.decay import analyse_decay

    case, _, motion, _ = cfd("flume_section_roll_sway_held", tmp_path,
                             ["run.end_time=3.0"])
    assert np.ptp(motion["y"]) == 0.0 and np.ptp(motion["x"]) == 0.0  # held by the solver
    decay = analysed(motion, "roll")
    model = cummins(case, duration=3.0)
    expected = analyse_decay(model["time"], np.radians(model["roll"])).summary()
    assert decay["period_mean"] == pytest.approx(expected["period_mean"], rel=0.01)
    assert decay["damping_ratio"] == pytest.approx(expected["damping_ratio"], rel=0.20)
