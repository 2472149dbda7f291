"""``floatfoam analyse`` in the DoF the run released (floatfoam.analysis.released): run folders
written here by hand (motion.csv and .floatfoam/info.json, as test_validation.py's), no solver."""

import json
import math

import numpy as np
import pytest

from floatfoam import layout
from floatfoam.analysis.released import NOISE_FRACTION, choose, released_by_run
from floatfoam.cli import main
from floatfoam.motion import read_motion, write_motion
from floatfoam.plan.record import read_record

PERIOD, ZETA = 0.868, 0.0265  # elliptic_cylinder_roll's roll (its case.toml)
T = np.arange(0.0, 4.5, 0.005)


def roll_decay(heel=10.0):
    """A damped cosine from ``heel`` degrees (file units)."""
    return heel * np.exp(-ZETA * 2 * math.pi / PERIOD * T) * np.cos(2 * math.pi / PERIOD * T)


def roll_run(build, info):
    """A finished roll release of elliptic_cylinder_roll's section: roll decays from 10°,
    heave swings 70 µm at twice its frequency (the coupled motion the issue saw fitted as
    "ζ −0.052"), G 5 cm below the still water."""
    run = build / "elliptic_cylinder_roll" / "coarse"
    (run / layout.MARKERS).mkdir(parents=True)
    (run / layout.MARKERS / "info.json").write_text(json.dumps(info))
    heave = -0.05 + 70e-6 * np.sin(4 * math.pi / PERIOD * T)
    write_motion(run / "motion.csv", T, z=heave, roll=roll_decay())
    layout.mark_done(run, layout.FINISHED)
    return run


RECORDED = {"mesh": "2d", "heel": math.radians(10.0), "trim": 0.0, "body_size": 0.3,
            "release": {"heave": 0.0, "heel": 10.0, "trim": 0.0}}


@pytest.mark.parametrize("info", [RECORDED, {"mesh": "2d", "heel": math.radians(10.0),
                                             "trim": 0.0}], ids=["release", "heel only"])
def test_a_roll_release_is_analysed_in_roll(tmp_path, capsys, info):
    """No --dof: the DoF the run released, from its info.json (its release table, or, in a
    run recorded without one, its heel) — not heave, whose 70 µm are the roll's coupling."""
    run = roll_run(tmp_path, info)
    assert main(["analyse", str(run), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["dof"] == "roll" and data["dof_from"] == "released by the run"
    assert data["period_mean"] == pytest.approx(PERIOD, rel=1e-6)
    assert main(["analyse", str(run / "motion.csv")]) == 0  # the CSV in a run folder: the same
    assert "roll (deg) (released by the run)" in capsys.readouterr().out


def test_dof_still_overrides_and_says_what_was_released(tmp_path, capsys):
    run = roll_run(tmp_path, RECORDED)
    assert main(["analyse", str(run), "--dof", "roll", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["dof_from"] == "--dof"
    choice = choose(run, read_motion(run / "motion.csv"), "heave")  # 70 µm: above the noise
    assert choice.dofs == ("heave",) and choice.released == ("roll",)


def test_a_run_that_released_several_dofs_gives_one_object_each(tmp_path, capsys):
    run = roll_run(tmp_path, RECORDED | {"release": {"heave": 0.01, "heel": 10.0, "trim": 0.0}})
    heave = -0.05 + 0.01 * np.exp(-0.3 * T) * np.cos(2 * math.pi / 0.76 * T)
    write_motion(run / "motion.csv", T, z=heave, roll=roll_decay())
    assert released_by_run(read_record(run)) == (
        "heave", "roll")
    assert main(["analyse", str(run), "--json"]) == 0
    assert [d["dof"] for d in json.loads(capsys.readouterr().out)] == ["heave", "roll"]


def test_a_csv_of_no_run_is_analysed_in_the_dof_that_moves(tmp_path, capsys):
    """A Cummins roll series of a section with G on the waterline: its heave is 1e-17 m of
    rounding about z = 0. The roll is taken, and said; heave asked for is refused in one
    line (exit 2), below NOISE_FRACTION of the least body size taken."""
    csv = tmp_path / "decay_cummins.csv"
    noise = 1e-17 * np.random.default_rng(1).standard_normal(T.size)
    write_motion(csv, T, z=noise, roll=roll_decay())
    assert main(["analyse", str(csv)]) == 0
    assert "roll (deg) (the largest motion in the file" in capsys.readouterr().out
    assert main(["analyse", str(csv), "--dof", "heave", "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1
    assert "--dof heave" in err and "noise" in err and f"{NOISE_FRACTION:g}" in err
    assert "valid is a DoF the record moves in: roll" in err


def test_a_released_dof_that_does_not_move_is_refused(tmp_path, capsys):
    """A roll release whose roll column stands still (a run whose body was held) has nothing
    to fit: one line, exit 2, nothing printed on stdout."""
    run = roll_run(tmp_path, RECORDED)
    write_motion(run / "motion.csv", T, z=-0.05 + 1e-3 * np.cos(T), roll=np.full_like(T, 1e-9))
    assert main(["analyse", str(run), "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1
    assert "dof roll (released by the run)" in err and "below 1e-06 of 1 rad" in err
