"""Comparison table on a fake case and SYNTHETIC motion records (known answers, no solver).

The case, its theory, its potential-flow results and Cummins' model are stand-ins with round
numbers, so the table's arithmetic (relative differences, units, omitted sources) is checked
independently of the physics modules. The motion.csv files and the model's series are synthetic
free decays, not OpenFOAM output.
"""

from __future__ import annotations

import csv
import math
import types
from pathlib import Path

import numpy as np
import pytest

from floatfoam.analysis.compare import compare_case, excited_dofs
from floatfoam.analysis.comparison_table import (
    TABLE_HEADER,
    comparison_markdown,
    comparison_table,
    write_comparison,
)
from floatfoam.analysis.cummins import MODEL, ModelRecord
from floatfoam.analysis.measured import reference_entry
from floatfoam.analysis.runs import cfd_runs
from floatfoam.errors import InputError
from floatfoam.hydrostatics.summary import TheorySummary
from floatfoam.layout import mark_done
from floatfoam.motion import write_motion
from floatfoam.potential.summary import PotentialSummary

PERIOD, ZETA = 0.63, 0.15  # synthetic "CFD" record: damped period (s) and damping ratio
THEORY_PERIOD = 0.49  # s, stand-in for the exact linear theory (undamped)
MODEL_PERIOD, MODEL_ZETA = 0.61, 0.11  # stand-in for Cummins' model: its damped period, ζ


def synthetic_decay(t, offset, eq, period=PERIOD, zeta=ZETA):
    omega_d = 2 * math.pi / period
    sigma = zeta * omega_d / math.sqrt(1 - zeta**2)
    return eq + offset * np.exp(-sigma * t) * (np.cos(omega_d * t)
                                               + sigma / omega_d * np.sin(omega_d * t))


def fake_case(tmp_path, name="fake_cylinder", release=None, reference=None):
    release = release if release is not None else {"heave": 0.0254, "heel": 0.0, "trim": 0.0}
    raw = {"case": {"title": "Fake cylinder"}, "release": release}
    if reference is not None:
        raw["reference"] = reference
    return types.SimpleNamespace(name=name, path=tmp_path / "cases" / name, raw=raw,
                                 release=release, reference=reference or {})


THEORY_DICT = {"heave_period": THEORY_PERIOD, "roll_period": 1.2, "pitch_period": None,
               "verdict_roll": "oscillates", "verdict_pitch": "oscillates",
               "equilibrium": {"z_G": -0.001, "heel": 0.0, "trim": 0.0},
               "memoir": {"heave_period": 0.5, "source": "reconstructed"}}
THEORY = TheorySummary.from_dict(THEORY_DICT)
REFERENCE = {"heave_period": {"value": 0.60, "uncertainty": 0.01, "source": "Ito 1977"},
             "heave_damping_ratio": {"value": 0.12, "uncertainty": 0.02, "source": "Ito 1977"}}


@pytest.fixture
def potential():
    """A stand-in potential-flow source."""
    return lambda case: PotentialSummary.from_dict({"heave_period": 0.62,
                                                    "heave_damping_ratio": 0.10})


@pytest.fixture
def model():
    """A stand-in Cummins' model: a damped heave series about z = −0.001 m, from the release,
    as long as it is asked for (3 s here, the synthetic CFD record's span)."""
    def cummins(case, duration):
        t = np.arange(0.0, (duration or 3.0) + 1e-9, 2e-3)
        z = synthetic_decay(t, case.release["heave"], -0.001, MODEL_PERIOD, MODEL_ZETA)
        return ModelRecord({"time": t, "z": z}, ("heave",), False, 0.003)

    return cummins


@pytest.fixture
def no_potential():
    """A potential-flow source whose module cannot be imported."""
    def unavailable(case):
        raise ImportError("No module named 'capytaine'")

    return unavailable


def write_run(build, case, level, t, **columns):
    """A finished run as the driver leaves it: motion.csv and the finished marker."""
    path = write_motion(Path(build, case, level, "motion.csv"), t, **columns)
    mark_done(path.parent, "finished")
    return path


def rows_by_source(comparison, dof="heave"):
    return {r["source"]: r for r in comparison.rows if r["dof"] == dof}


def test_full_table_against_model_and_reference(tmp_path, potential, model):
    """Δ against Cummins' model (fitted over the CFD's 3 s as the CFD is) and, in its own
    columns, against the reference; the linear theory keeps its row."""
    case = fake_case(tmp_path, reference=REFERENCE)
    t = np.arange(0.0, 3.0, 2e-3)
    write_run(tmp_path / "build", case.name, "coarse", t, z=synthetic_decay(t, 0.0254, -0.001))
    comparison = compare_case(case, build_dir=tmp_path / "build", theory=THEORY,
                              potential=potential, model=model)
    rows = rows_by_source(comparison)
    assert list(rows) == ["memoir (corrected)", "linear theory (exact)", "potential flow",
                          MODEL, "CFD coarse", "reference"]
    cfd, cummins = rows["CFD coarse"], rows[MODEL]
    # Clean synthetic records: the fit is exact to ~1e-10; 1e-6 leaves room for round-off.
    assert cfd["period"] == pytest.approx(PERIOD, rel=1e-6)
    assert cfd["damping_ratio"] == pytest.approx(ZETA, rel=1e-6)
    assert cummins["period"] == pytest.approx(MODEL_PERIOD, rel=1e-6)
    assert cummins["damping_ratio"] == pytest.approx(MODEL_ZETA, rel=1e-6)
    assert "fitted over 3 s, as the CFD's record" in cummins["note"]
    assert cfd["period_rel_diff"] == pytest.approx(PERIOD / MODEL_PERIOD - 1, rel=1e-6)
    assert cfd["damping_rel_diff"] == pytest.approx(ZETA / MODEL_ZETA - 1, rel=1e-6)
    assert cfd["period_rel_diff_measured"] == pytest.approx(PERIOD / 0.60 - 1, rel=1e-6)
    assert cfd["damping_rel_diff_measured"] == pytest.approx(ZETA / 0.12 - 1, rel=1e-6)
    assert "Δ period vs Cummins' model" in cfd["basis"] and "vs reference" in cfd["basis"]
    assert rows["linear theory (exact)"]["period_rel_diff"] == pytest.approx(
        THEORY_PERIOD / MODEL_PERIOD - 1, rel=1e-6)
    assert rows["linear theory (exact)"]["period_rel_diff_measured"] == pytest.approx(
        THEORY_PERIOD / 0.60 - 1)
    assert rows["potential flow"]["damping_rel_diff_measured"] == pytest.approx(0.10 / 0.12 - 1)
    assert cummins["period_rel_diff_measured"] == pytest.approx(MODEL_PERIOD / 0.60 - 1,
                                                                rel=1e-6)
    assert rows["reference"]["period_ci"] == pytest.approx([0.59, 0.61])
    assert rows["reference"]["note"] == "Ito 1977"
    assert "m from the theory's equilibrium" in cfd["note"]
    assert len(comparison.analyses) == 1
    fit = comparison.models["heave"]  # for the figure: its offset from its equilibrium
    assert fit.offset[0] == pytest.approx(0.0254) and fit.label.startswith(MODEL)
    header, cells = comparison_table(comparison.rows)
    assert header == list(TABLE_HEADER)
    assert cells[4][4] == f"{100 * (PERIOD / MODEL_PERIOD - 1):+.2f} %"  # CFD, Δ vs model


def test_markdown_and_csv(tmp_path, potential, model):
    case = fake_case(tmp_path, reference=REFERENCE)
    t = np.arange(0.0, 3.0, 2e-3)
    write_run(tmp_path / "build", case.name, "fine", t, z=synthetic_decay(t, 0.0254, -0.001))
    write_run(tmp_path / "build", case.name, "coarse", t, z=synthetic_decay(t, 0.0254, -0.001))
    comparison = compare_case(case, build_dir=tmp_path / "build", theory=THEORY,
                              potential=potential, model=model)
    md_path, csv_path = write_comparison(comparison, tmp_path / "out")
    text = md_path.read_text()
    assert "| heave | CFD coarse | 0.63 |" in text
    assert text.index("CFD coarse") < text.index("CFD fine")  # coarse to fine
    with csv_path.open() as handle:
        table = list(csv.DictReader(handle))
    cfd = [r for r in table if r["source"] == "CFD fine"][0]
    assert float(cfd["period"]) == pytest.approx(PERIOD, rel=1e-6)
    assert float(cfd["period_lo"]) <= PERIOD <= float(cfd["period_hi"])
    assert float(cfd["damping_rel_diff"]) == pytest.approx(ZETA / MODEL_ZETA - 1, rel=1e-6)
    assert float(cfd["damping_rel_diff_measured"]) == pytest.approx(ZETA / 0.12 - 1, rel=1e-6)
    assert "| Δ period vs model |" in text and "| Δ ζ vs measured |" in text


def coarse_comparison(tmp_path, potential, model):
    """The comparison of a fake case with one coarse run of the synthetic decay."""
    case = fake_case(tmp_path)
    t = np.arange(0.0, 3.0, 2e-3)
    write_run(tmp_path / "build", case.name, "coarse", t, z=synthetic_decay(t, 0.0254, -0.001))
    return compare_case(case, build_dir=tmp_path / "build", theory=THEORY,
                        potential=potential, model=model)


def test_without_the_model_differences_are_to_theory(tmp_path, no_potential, model):
    """Potential flow not available: Cummins' model's row says why, and the period is set
    against the linear theory's, the basis saying so; without a reference there are no
    Δ-vs-measured columns."""
    comparison = coarse_comparison(tmp_path, no_potential, model)
    rows = rows_by_source(comparison)
    assert "potential flow" not in rows
    assert any(note.startswith("potential flow: not available") for note in comparison.notes)
    assert rows[MODEL]["period"] is None
    assert rows[MODEL]["note"].startswith("not computed: no potential flow")
    assert "reference" not in rows and not comparison.models
    cfd = rows["CFD coarse"]
    assert cfd["period_rel_diff"] == pytest.approx(PERIOD / THEORY_PERIOD - 1, rel=1e-6)
    assert cfd["damping_rel_diff"] is None  # the theory has no damping to compare with
    assert "Δ period vs linear theory (exact)" in cfd["basis"]
    header, _ = comparison_table(comparison.rows)
    assert "Δ period vs model" in header and "Δ period vs measured" not in header


def test_a_model_that_cannot_be_computed_says_why(tmp_path, potential):
    """A model that raises (here a capsizing release) gives its row with the reason and a note;
    the CFD's Δ falls back to the linear theory."""
    def capsizes(case, duration):
        raise InputError("--model cummins: roll capsizes (GM = -0.01 m)")

    comparison = coarse_comparison(tmp_path, potential, capsizes)
    rows = rows_by_source(comparison)
    assert rows[MODEL]["note"] == "not computed: --model cummins: roll capsizes (GM = -0.01 m)"
    assert any(n.startswith(f"{MODEL}: not computed") for n in comparison.notes)
    assert "vs linear theory (exact)" in rows["CFD coarse"]["basis"]


def test_roll_record_in_degrees(tmp_path, no_potential):
    case = fake_case(tmp_path, release={"heave": 0.0, "heel": 10.0, "trim": 0.0})
    theory = TheorySummary.from_dict(
        {**THEORY_DICT, "equilibrium": {"z_G": 0.0, "heel": 0.2, "trim": 0.0}})
    t = np.arange(0.0, 6.0, 5e-3)
    roll = synthetic_decay(t, 10.0, 0.5, period=1.3, zeta=0.05)  # degrees, as in the file
    write_run(tmp_path / "build", case.name, "coarse", t, roll=roll)
    comparison = compare_case(case, build_dir=tmp_path / "build", theory=theory,
                              potential=no_potential)
    assert excited_dofs(case) == ["roll"]
    cfd = rows_by_source(comparison, "roll")["CFD coarse"]
    assert cfd["period"] == pytest.approx(1.3, rel=1e-6)
    assert cfd["damping_ratio"] == pytest.approx(0.05, rel=1e-6)
    # The record settles at 0.5°, the theory at 0.2°: the offset is reported in degrees.
    assert "mean level +0.3 deg from the theory's equilibrium" in cfd["note"]


def test_bad_record_gives_a_failed_row_not_a_missing_one(tmp_path, no_potential):
    case = fake_case(tmp_path)
    t = np.arange(0.0, 3.0, 2e-3)
    z = synthetic_decay(t, 0.0254, -0.001)
    z[200] = np.nan
    write_run(tmp_path / "build", case.name, "coarse", t, z=z)
    short = t[t < 0.5]
    write_run(tmp_path / "build", case.name, "medium", short,
              z=synthetic_decay(short, 0.0254, -0.001))
    comparison = compare_case(case, build_dir=tmp_path / "build", theory=THEORY,
                              potential=no_potential)
    rows = rows_by_source(comparison)
    assert rows["CFD coarse"]["period"] is None
    assert "analysis failed: z: non-finite value nan at sample 200" in rows["CFD coarse"]["note"]
    assert "need at least 1.5" in rows["CFD medium"]["note"]
    assert "analysis failed" in comparison_markdown(comparison)


def test_no_run_yet_is_noted(tmp_path, no_potential):
    comparison = compare_case(fake_case(tmp_path), build_dir=tmp_path / "build", theory=THEORY,
                              potential=no_potential)
    assert [r["source"] for r in comparison.rows] == ["memoir (corrected)",
                                                      "linear theory (exact)", MODEL]
    assert any(note.startswith("CFD: no run yet") for note in comparison.notes)


def test_reference_entries():
    assert reference_entry({"heave_period": 0.63}, "heave_period") == (0.63, None, "")
    assert reference_entry({}, "heave_period") is None
    with pytest.raises(InputError, match="reference.heave_period has no 'value'"):
        reference_entry({"heave_period": {"uncertainty": 0.01}}, "heave_period")


def test_excited_dofs_from_release_and_reference(tmp_path):
    case = fake_case(tmp_path, release={"heave": 0.01, "heel": 0.0, "trim": 3.0},
                     reference={"roll_damping_ratio": 0.05})
    assert excited_dofs(case) == ["heave", "roll", "pitch"]


def test_only_finished_runs_are_compared(tmp_path):
    t = np.linspace(0.0, 3.0, 300)
    write_run(tmp_path, "cyl", "coarse", t, z=np.cos(t))
    write_motion(Path(tmp_path, "cyl", "medium", "motion.csv"), t, z=np.cos(t))  # unfinished
    write_run(tmp_path, "cyl", "coarse.old-20261122-040000", t, z=np.cos(t))  # moved aside
    assert [level for level, _ in cfd_runs("cyl", tmp_path)] == ["coarse"]
