"""Every body of the memoir in CFD: real coarse runs of the gmsh route (marker ``openfoam``) on
one MPI rank in make test and on 2 in make test-extended (cfdcases.RANKS, ALONE), each checked
against the theory and potential flow (Cummins' model).

Each test runs a shortened record of its case (make test stays within 20 minutes on 2 cores;
the records are given per test); the cases' whole records run under `make <case>`, and their
measured numbers are in the cases' READMEs. The tolerances come from the numbers measured on
this machine; the reason for each is written beside it.
"""

import math

import numpy as np
import pytest
from bodycases import IMPLICIT_SPHERE
from cfdcases import (
    ALONE,
    RANKS,
    SWAY_CHECKED,
    SWAY_TOLERANCE,
    analysed,
    cfd,
    cummins,
    early_period,
    extrema,
    first_sway,
    potential_period,
    refined_extrema,
    shared_run,
)

from floatfoam.analysis.decay import analyse_decay, find_crossings
from floatfoam.potential.models import decay_series

pytestmark = pytest.mark.openfoam


# make test's heave records: the first four extrema and the settled level are in by 2.0 s
# (the faster sections' fourth extremum comes by 1.56 s, and the mean of the last second is
# then within 0.04 mm of the equilibrium on the ellipse's coarse record and within 0.24 % of
# the draft on Cummins' parabola; the box's fourth comes at ~1.8 s: its coarse whole record of
# the 2D study cut at 2.0 s gives the same extrema period as cut at 2.5 s, +0.16 % from
# Cummins', and the last second's mean +0.23 % of the draft from the equilibrium, against
# +0.41 % at 2.5 s); the cases' own records run on until the swing is below 1 % of the
# release.
HEAVE_RECORDS = {"elliptic_cylinder": 2.0, "box_bilge_heave": 2.0, "parabolic_cylinder": 2.0}


@pytest.mark.parametrize("name", list(HEAVE_RECORDS))
def test_section_heave(tmp_path, name):
    """Heave decay of 2D sections released ≤ 10 % of their draft: the period within 3 % of
    Cummins' potential-flow model, the equilibrium draft within 1 %.

    Flat sections radiate strongly (Cummins: ζ = 0.22 for the ellipse): the record leaves the
    noise after ~1.5 cycles, too few for the decay fit, so both periods are timed by their
    first four extrema. Measured on make test's records at the default step: ellipse CFD
    0.773 s against Cummins' 0.763 s (+1.4 %), box +0.91 %, parabola +0.20 %. On the finer
    levels (`make validate`, relaxation 1.0) the decay fit's T_d moves by −0.8, −0.6 and −0.5 % from
    coarse to fine (ellipse, box, parabola) and halving the step by 0.3, 0.4 and 0.1 %;
    the fine T_d is 0.05 % (box) and 0.6 % (parabola) from Cummins' (the ellipse's 1.5 fitted
    cycles are not its whole-record fit; its whole record at the default step, T_d +0.8 % of
    Cummins': docs/studies/time-step-limits.md). 3 % is the issue's bound, held with room."""
    case, theory, motion, info = cfd(name, tmp_path,
                                     [f"run.end_time={HEAVE_RECORDS[name]}"])
    assert info.mesh == "2d"
    series = cummins(case)
    expected = early_period(series["time"], series["z"])
    assert early_period(motion["time"], motion["z"]) == pytest.approx(expected, rel=0.03)
    # The body settles in a finite tank whose level rises by A_wp·release/(2·half_length)
    # (0.25 mm for the ellipse) as it sinks back: the tail's mean within 1 % of the draft.
    tail = motion["time"] > motion["time"][-1] - 1.0
    assert np.mean(motion["z"][tail]) == pytest.approx(info.z_G_equilibrium,
                                                       abs=0.01 * theory.draft)


# The records of make test: 2.1–2.3 roll periods (the cases' own end times, 5 periods, run
# under `make <case>` and `make bench-cfd FULL=1`: measured stable and within the same
# tolerances, their READMEs give the numbers). make test must stay within 20 minutes on 2
# cores. The fitted period hardly depends on the record's length: the coarse whole records of
# the 2D study (relaxation 1.0) cut at these ends give 2.33, 2.11 and 2.21 cycles and periods
# +1.21 %, −1.84 % and −0.21 % from Cummins' (ellipse, box, hyperbola), against +1.17 %,
# −1.74 % and −0.04 % cut at 2.7, 4.0 and 2.8 s and +1.12 %, −1.74 % and +0.05 % at 4.0 s;
# the last second's mean height moves by ≤ 0.17 % of the draft.
ROLL_RECORDS = {"elliptic_cylinder_roll": 2.0, "box_bilge": 3.0, "hyperbolic_cylinder": 2.0}


@pytest.mark.parametrize("name", list(ROLL_RECORDS))
def test_section_roll(shared_runs, name):
    """Roll decay of 2D sections released heeled, free in sway and heave: the roll period
    within 5 % of Cummins' model free in the same DoFs (the potential-flow added inertia and
    its sway–roll coupling), G's sway with it, the motion stable over the record, the body
    back at its equilibrium draft within 1 %. Measured on make test's records and step, at the
    default mesh motion (the Laplacian; 2.34, 2.11 and 2.23 cycles fitted): ellipse +1.11 %,
    box −1.83 %, hyperbola −1.12 % (docs/morphing.md, where the six-DoF distances gave +1.2 /
    −1.8 / −0.5 % at 0.3 and 1.6 × the section's smallest dimension, +1.4 / −2.6 / −0.5 % out
    to 0.9 × the room in the tank). The roll-only model about G gave 0.8683, 1.4458 and 0.9473 s
    (−1.4, −1.6, −4.1 % from the CFD on the distances' whole records) and twice the CFD's
    damping ratio on the ellipse and hyperbola. The 5 % is the issue's bound: the fine levels
    on the distances were within U_num ≤ 0.45 % and 0.3 % of their coarse whole records
    (+0.9 %, −1.4 %, +0.4 %: the cases' READMEs)."""
    overrides = [f"run.end_time={ROLL_RECORDS[name]}"]
    # the ellipse's run is tests/foam/test_paraview.py's too (a parallel run): made once
    ranks = 2 if name == "elliptic_cylinder_roll" else RANKS
    case, theory, motion, info = cfd(name, shared_run(name, overrides, shared_runs, ranks),
                                     overrides, ranks)
    assert motion["roll"][0] == pytest.approx(case.release["heel"], abs=1e-3)  # from equilibrium
    decay = analysed(motion, "roll")
    assert decay["n_cycles"] >= 2.0
    expected = potential_period(case, "roll")
    assert decay["period_mean"] == pytest.approx(expected, rel=0.05)
    series = cummins(case)
    swing = first_sway(series["time"], series["y"], expected)
    if abs(swing) > SWAY_CHECKED:
        assert first_sway(motion["time"], motion["y"], expected) == pytest.approx(
            swing, rel=SWAY_TOLERANCE)
    tail = motion["time"] > motion["time"][-1] - 1.0
    assert np.mean(motion["z"][tail]) == pytest.approx(info.z_G_equilibrium,
                                                       abs=0.01 * theory.draft)


@pytest.mark.parametrize("name, release, tolerance, step", [
    # 10 % of the draft: the linear range; measured CFD 0.6248 s, Cummins 0.6207 s (+0.65 %).
    # 3 %: the grid studies (cases/sphere/README.md) put the fine levels +0.20 % ± 0.13 %,
    # −0.41 % ± 2.7 % and −1.6 % ± 0.68 % (10, 25, 50 mm) from Cummins' model, the coarse
    # wedge within 0.8 % of them. The two smaller releases at the default step; the 50 mm
    # release at half its Courant limit and step (Courant 0.5, ≤ 5 ms): at the default step its
    # 1.4 s record's fitted level is −1.02 mm, past the 1 mm allowed, −0.87 mm at half of it
    # (the whole coarse records cut at 1.4 s; Cummins' model with the nonlinear restoring fits
    # −0.14 mm: the CFD's own offset, docs/studies/time-step-limits.md)
    ("sphere", 0.01, 0.03, []),
    ("sphere_25mm", 0.025, 0.03, []),
    ("sphere_50mm", 0.05, 0.03, ["run.max_courant=0.5", "run.max_delta_t=0.005"]),
])
def test_sphere_heave_from_three_heights(tmp_path, name, release, tolerance, step):
    """The half-immersed sphere (axisymmetric wedge) released 10, 25 and 50 mm (up to half its
    radius) above equilibrium: the heave period within 3 % of Cummins' model — with the
    sphere's nonlinear restoring (its waterplane shrinks as it rises) for releases over 10 % of
    the draft — and the equilibrium draft within 1 %."""
    # make test: 2.2 periods (1.4 s) of the case's 5 (3.2 s, `make sphere...`). The coarse
    # whole records of the study at relaxation 1.0 cut at 1.4 s (2.23 cycles fitted) against
    # cut at 1.7 s (2.72 cycles): periods +0.71 / +0.74 / −0.23 % from Cummins' against
    # +0.60 / +0.61 / −0.57 % (10 / 25 / 50 mm), fitted levels −0.28 / −0.45 / −0.71 mm against
    # −0.26 / −0.42 / −0.80 mm (the body's wall on movingWallVelocity); the whole coarse
    # records at these steps cut at 1.4 s: +0.65 / +0.98 / +1.55 %, −0.30 / −0.56 / −0.87 mm
    case, theory, motion, info = cfd(name, tmp_path, ["run.end_time=1.4", *step])
    assert info.mesh == "wedge"
    assert motion["z"][0] - info.z_G_equilibrium == pytest.approx(release, abs=1e-6)
    decay = analysed(motion, "heave")
    assert decay["n_cycles"] >= 2.0
    series = cummins(case, nonlinear_restoring=release > 0.1 * theory.draft)
    expected = analyse_decay(series["time"], series["z"]).summary()["period_mean"]
    assert decay["period_mean"] == pytest.approx(expected, rel=tolerance)
    assert decay["equilibrium"] == pytest.approx(info.z_G_equilibrium,
                                                 abs=0.01 * theory.draft)


VERTICAL_CYLINDER = """[body]
shape = "vertical_cylinder"
radius = 0.1
height = 0.2
[mass]
density = 500.0
cog = [0.0, 0.0, -0.03]
gyradius = [0.06, 0.06, 0.07]
[release]
heave = 0.01
"""


def test_a_vertical_cylinder_heaves_in_a_wedge(tmp_path):
    """A buoy the project has no case for, written as a user would: a vertical cylinder of
    radius 0.1 m and height 0.2 m, half immersed, released 10 mm (10 % of the draft) at the
    defaults. A body of revolution in heave: the wedge (4,680 cells). Over 1.7 s (2.1 periods;
    the default step), the damped period within 3 % of Cummins' model, as the sphere's
    (measured on 1.6 s 0.7906 s against 0.7854 s, +0.67 %; `floatfoam run` of 3.2 s at the
    defaults 0.7883 s, +0.37 %, ζ 0.047 against potential flow's 0.034: the flat bottom's
    rim sheds eddies), where the memoir's model without the flat bottom's added mass gives
    0.6344 s; the equilibrium draft within 1 %."""
    folder = tmp_path / "buoy"
    folder.mkdir()
    (folder / "case.toml").write_text(VERTICAL_CYLINDER)
    case, theory, motion, info = cfd(str(folder), tmp_path, ["run.end_time=1.7"])
    assert info.mesh == "wedge"
    decay = analysed(motion, "heave")
    assert decay["n_cycles"] >= 2.0
    series = cummins(case)
    expected = analyse_decay(series["time"], series["z"]).summary()["period_mean"]
    assert decay["period_mean"] == pytest.approx(expected, rel=0.03)
    assert decay["period_mean"] > 1.1 * theory.period("heave")
    assert decay["equilibrium"] == pytest.approx(info.z_G_equilibrium, abs=0.01 * theory.draft)


def test_a_body_of_revolution_given_by_triangles_heaves_in_a_wedge(tmp_path):
    """The `sphere` case's body written as a user's implicit surface (triangles): found to be a
    body of revolution, it heaves in the wedge, not in the 3D tank (whose coarse record's T_d
    over 1.9 s is 0.55 % short of Cummins' model: docs/morphing.md). Its first trough and crest
    (0.7 s, make test's step) within 0.6 % of Cummins' model's: at this step the `sphere`
    case's own wedge puts them +0.34 % and +0.12 % from it, these triangles +0.40 % and
    +0.08 % (measured)."""
    folder = tmp_path / "buoy"
    folder.mkdir()
    (folder / "case.toml").write_text(IMPLICIT_SPHERE)
    case, _, motion, info = cfd(str(folder), tmp_path, ["run.end_time=0.7"])
    assert info.mesh == "wedge"
    series = cummins(case)
    assert refined_extrema(motion["time"], motion["z"], 2) == pytest.approx(
        refined_extrema(series["time"], series["z"], 2), rel=0.006)


def test_lab_sphere_first_cycle_against_the_basin(tmp_path):
    """Kramer et al.'s (2021) sphere dropped from 0.1 D: the first period and first trough of
    the coarse wedge, reduced as the basin reduces its records about the level the body
    settles at (analysis.settled.settled_level: known here, so the record's first 1.1 s is
    enough), against the four drops' reference.

    The case's grid study (`floatfoam validate lab_sphere`, its README; the body's wall on
    movingWallVelocity) puts the coarse, medium and fine levels +0.24, −0.12 and +0.01 % from
    the basin's first period and their troughs 0.55 % and 0.18 % shallower than its and 0.02 %
    deeper; the coarse level's whole record at the default step +0.17 % and +1.53 % (+0.22 %
    and +1.42 % at Courant 0.5 and 5 ms: docs/studies/time-step-limits.md).
    First period within 0.5 %: the levels' spread 0.36 %, the halved step's 0.02 %, the
    basin's ± 0.07 %, rounded up. Trough within 2 %: the coarse level's +1.5 % (the medium
    level's +1.1 %: the case's README), the basin's ± 0.4 %, their sum 1.9 % rounded up."""
    from floatfoam import layout
    from floatfoam.analysis.extrema import crossing_reduction
    from floatfoam.analysis.measured import reference_entry
    from floatfoam.analysis.settled import settled_level

    case, theory, motion, info = cfd("lab_sphere", tmp_path, ["run.end_time=1.1"])
    assert info.mesh == "wedge"
    level = settled_level(case, "heave", layout.run_dir(case.name, "coarse", tmp_path), theory)
    assert level is not None
    first = crossing_reduction(motion["time"], motion["z"], level=level, n_extrema=2)
    period = reference_entry(case.reference, "heave_first_period")[0]
    trough = reference_entry(case.reference, "heave_first_trough")[0]
    assert first.first_period == pytest.approx(period, rel=0.005)
    assert first.first_trough == pytest.approx(trough, rel=0.02)


#: a flat, light box: 0.4 m wide, 0.08 m high, 250 kg/m³ (draft 20 mm), released 4 mm in
#: heave; its added mass at infinite frequency is 8.8 × its mass (docs/coupling.md: g = 4.4)
LIGHT_FLAT_BOX = """
[case]
title = "flat light box"
description = "a body whose added mass is many times its own"
[body]
shape = "box"
beam = 0.4
height = 0.08
bilge_radius = 0.01
length = 1.0
[mass]
density = 250.0
cog = [0.0, 0.0, 0.0]
gyradius = [0.1166, 0.2887, 0.2887]
[release]
heave = 0.004
"""


def test_a_light_flat_body_is_coupled_without_diverging(tmp_path):
    """A body light beside the water it moves: without the coupling's added-mass compensation
    (src/solver/addedMassCompensation.C) its PIMPLE correctors multiply the error of its
    acceleration by −4.4 and the run diverges within its first millisecond. Compensated, it
    runs at the defaults and falls as Cummins' model with nonlinear restoring does: over
    0.1 s within 3 % (measured −0.6 %; over 0.4 s −1…−3 %: the fluid's viscosity and the
    coarse cells, which the model leaves out, as the laboratory sphere's +1.6 % over 0.2 s)."""
    folder = tmp_path / "flat"
    folder.mkdir()
    (folder / "case.toml").write_text(LIGHT_FLAT_BOX)
    case, theory, motion, info = cfd(str(folder), tmp_path, ["run.end_time=0.1"])
    assert info.mesh == "2d"
    fall = motion["z"][0] - motion["z"][-1]
    series = cummins(case, duration=0.5, nonlinear_restoring=True)
    expected = series["z"][0] - float(np.interp(0.1, series["time"], series["z"]))
    assert fall == pytest.approx(expected, rel=0.03)


@pytest.mark.extended  # make test-extended: a setting's own route (36 s alone, 60–110 s in
# make test), beyond make test's 20 minutes
def test_a_mesh_made_at_equilibrium_starts_from_the_release(tmp_path):
    """lab_sphere's wedge made with the body at equilibrium (run.mesh_pose, floatfoam.foam.
    meshpose) and moved to the 29 mm release before the first step: G starts at the release,
    the mesh as made is the solver's points0, and the body falls as it does from a mesh made at
    the release — over 0.2 s within 3 % of Cummins' model with nonlinear restoring (measured
    30.08 mm against 29.62 mm, +1.6 %; without added mass the model falls 40.8 mm)."""
    case, theory, motion, info = cfd("lab_sphere", tmp_path,  # the ranks' meshes are checked
                                     ["run.end_time=0.2", 'run.mesh_pose="equilibrium"'], ALONE)
    release = case.release["heave"]
    assert info.mesh_offset == pytest.approx([0.0, 0.0, release], abs=1e-9)
    assert motion["z"][0] - info.z_G_equilibrium == pytest.approx(release, abs=1e-6)
    from foamlib import FoamFieldFile

    from floatfoam.foam.meshpose import _patch_points

    run_dir = tmp_path / "lab_sphere" / "coarse"
    meshes = [p / "constant" / "polyMesh" for p in sorted(run_dir.glob("processor*"))]
    assert len(meshes) == ALONE
    for mesh in [*meshes, run_dir / "constant" / "polyMesh"]:  # the ranks' and the whole's
        made, moved = (np.asarray(FoamFieldFile(mesh / n)[None]) for n in ("points0", "points"))
        lift = moved - made
        assert np.all(lift[:, :2] == 0.0) and np.all((lift[:, 2] >= 0.0)
                                                     & (lift[:, 2] <= release + 1e-12))
        body = _patch_points(mesh, ["body"])  # a rank may hold none of it
        assert np.allclose(lift[body, 2], release, rtol=0, atol=1e-12)
        walls = _patch_points(mesh, ["bottom", "sides", "atmosphere"])
        assert np.all(lift[walls, 2] == 0.0)
    assert len(body) and len(walls)  # the whole mesh's
    fall = motion["z"][0] - float(np.interp(0.2, motion["time"], motion["z"]))
    series = cummins(case, duration=0.5, nonlinear_restoring=True)
    expected = series["z"][0] - float(np.interp(0.2, series["time"], series["z"]))
    assert fall == pytest.approx(expected, rel=0.03)


def test_capsizing_ellipse_turns_over_to_its_stable_attitude(tmp_path):
    """The ellipse on its major axis with G too high (GM = −0.0154 m): Le Barbier's verdict
    "capsizes" seen in the fluid. Released at 2°, it leaves the upright attitude, turns past the
    stable attitude of its GZ curve (65.4°) and swings about it, never back to upright; the run
    meshes it anew each 30° of turn (run.remesh_angle).

    Its heel history follows the nonlinear inviscid model (exact GZ, no added inertia, no
    damping) to within 10 % in time up to 80° (measured: 3.1 % at 5°, 4.9 % at 80°; the fluid's
    added inertia slows it; the medium level 2.8 % and 4.7 %, its README). Damping is light: on
    a 4 s record it still swung 27°–86° about the stable attitude, so the settled attitude is
    not reached in a test's time; the check is that the swing brackets it."""
    from floatfoam.hydrostatics.gz import righting_arm
    from floatfoam.hydrostatics.roots import brentq

    # make test: to 1.6 s, on the swing back (below the stable 65.4° by then), at the default
    # mesh motion (no distance set: the morphing zone reaches to the tank's top)
    case, theory, motion, info = cfd("elliptic_cylinder_capsize", tmp_path,
                                     ["run.end_time=1.6"])
    assert theory.dofs["roll"].verdict == "capsizes"
    stable = brentq(lambda a: righting_arm(case, math.radians(a)), 50.0, 80.0)
    assert stable == pytest.approx(65.4, abs=0.1)
    t, roll = motion["time"], motion["roll"]
    assert roll[0] == pytest.approx(2.0, abs=1e-3)
    model = decay_series(case, "nonlinear", duration=2.0)
    for angle in (10.0, 20.0, 40.0, 60.0, 80.0):
        cfd_time = t[np.argmax(roll >= angle)]
        model_time = model["time"][np.argmax(model["roll"] >= angle)]
        assert roll.max() >= angle and cfd_time == pytest.approx(model_time, rel=0.10)
    peak = int(np.argmax(roll))
    assert roll[peak] > 85.0  # past the stable attitude, the mesh following (measured 89.7°)
    after = roll[peak:]
    assert after.min() < stable < roll[peak]  # and swings back about it (53.7° by 1.6 s)
    assert after.min() > 20.0  # never back to upright
    # the mesh made anew on the way, each 30° of turn (measured: at 34.5° and 67.8°), and the
    # pictures read each time on its own mesh: the body patch upright at 0.5 s (taller than
    # wide: the ellipse stands on its major axis, 0.30 × 0.20 m) and lying over at the peak
    from floatfoam.analysis.flowview import open_run

    run = open_run(tmp_path / case.name / "coarse")
    assert len(run.parts) >= 2 and run.times[-1] == pytest.approx(1.6)
    for when, heel in ((0.5, float(np.interp(0.5, t, roll))), (t[peak], roll[peak])):
        _, body = run.read(float(run.times[np.argmin(np.abs(run.times - when))]))
        b = body.bounds
        wide, tall = b[3] - b[2], b[5] - b[4]
        assert (tall > wide) == (heel < 45.0), (when, heel, wide, tall)


@pytest.mark.extended  # make test-extended: make test's 20 minutes hold the STL body's 3D roll
def test_triaxial_ellipsoid_roll_3d(tmp_path):
    """The triaxial ellipsoid (0.20, 0.15, 0.10) m released heeled 10°, in 3D on the half
    domain x ≥ 0 (symmetry plane x = 0, which its roll keeps), on a record of 0.2 s, past its
    first zero crossing (a quarter period; the whole 3.6 s runs under `make ellipsoid_roll`, the
    first trough and G's sway below): stable, the first crossing within 5 %
    of Cummins' model free in sway, heave and roll as the CFD body (measured 0.1642 s against
    0.1633 s, +0.5 %), where the memoir's linear model without added inertia crosses 11 %
    earlier (0.1458 s); the draft within 1 %."""
    record = 0.2  # a crossing 5 % late (0.172 s) is still seen
    case, theory, motion, info = cfd("ellipsoid_roll", tmp_path, [f"run.end_time={record}"],
                                     ALONE)
    assert info.mesh == "3d-half"
    assert motion["roll"][0] == pytest.approx(10.0, abs=1e-3)
    series = cummins(case, duration=0.5)
    crossing = first_crossing(motion["time"], motion["roll"])
    assert crossing == pytest.approx(first_crossing(series["time"], series["roll"]), rel=0.05)
    linear = decay_series(case, "linear", duration=0.5)
    assert crossing > 1.05 * first_crossing(linear["time"], linear["roll"])
    assert np.mean(motion["z"]) == pytest.approx(info.z_G_equilibrium, abs=0.01 * theory.draft)


@pytest.mark.extended  # make test-extended, as the quarter period
def test_triaxial_ellipsoid_roll_3d_first_trough_and_sway(tmp_path):
    """ellipsoid_roll as above on a record of 0.35 s, through its first trough at 0.324 s: the
    time of the first trough (half the period) within 5 % of Cummins' model (measured 0.3268 s
    against 0.3237 s, +0.9 %, the samples nearest the troughs; the vertices of parabolas through
    them 0.3255 s and 0.3242 s, +0.4 %; the mesh following the body by the Laplacian, the
    3D default), G's sway by then within 10 % (−7.93 mm against −8.34 mm,
    −4.9 %), the draft within 1 %. On the whole record the fitted periods differ by −0.9 % (0.6642 s
    against 0.6705 s); the roll-only model about G (0.7095 s) is −6.4 % away."""
    record = 0.35  # a trough 5 % late (0.340 s) is still seen
    case, theory, motion, info = cfd("ellipsoid_roll", tmp_path, [f"run.end_time={record}"],
                                     ALONE)
    assert info.mesh == "3d-half"
    assert motion["roll"][0] == pytest.approx(10.0, abs=1e-3)
    series = cummins(case)
    expected = extrema(series["time"], series["roll"], 1)[0]
    assert extrema(motion["time"], motion["roll"], 1)[0] == pytest.approx(expected, rel=0.05)
    assert first_sway(motion["time"], motion["y"], record) == pytest.approx(
        first_sway(series["time"], series["y"], record), rel=SWAY_TOLERANCE)
    assert np.mean(motion["z"]) == pytest.approx(info.z_G_equilibrium, abs=0.01 * theory.draft)


def first_crossing(t, x) -> float:
    """The time ``x`` first crosses zero (analysis.decay.find_crossings, no noise band)."""
    times, _ = find_crossings(t, x, 0.0)
    assert len(times), "no zero crossing"
    return float(times[0])


@pytest.mark.extended  # make test-extended: make test's 20 minutes hold the 3D roll, not this
def test_triaxial_ellipsoid_pitch_3d(tmp_path):
    """The triaxial ellipsoid of ellipsoid_roll released trimmed 5° (cases/ellipsoid_pitch), in
    3D on the half domain y ≥ 0 (symmetry plane y = 0, which its pitch keeps), free in surge,
    heave and pitch. On a record of 0.18 s, past the first zero crossing (a quarter period; the
    whole 3.3 s runs under `make ellipsoid_pitch`): starting at 5° from the equilibrium, the time
    of the first crossing within 5 % of Cummins' model free in the same DoFs, as the roll's
    period (measured 0.1600 s against 0.1601 s, −0.03 %), where the memoir's linear model
    without added inertia crosses 15 % earlier (0.1355 s); the draft within 1 %. (With G
    misplaced on x = 0 instead of where the trim puts it, it crosses at 0.1877 s:
    tests/foam/test_cfd_setup.py checks G's place.)"""
    record = 0.18
    case, theory, motion, info = cfd("ellipsoid_pitch", tmp_path, [f"run.end_time={record}"],
                                     ALONE)
    assert info.mesh == "3d-half"
    assert motion["pitch"][0] == pytest.approx(5.0, abs=1e-3)
    assert np.all(np.abs(motion["roll"]) < 1e-6)  # the plane y = 0 keeps it from rolling
    series = cummins(case, duration=0.5)
    expected = first_crossing(series["time"], series["pitch"])
    crossing = first_crossing(motion["time"], motion["pitch"])
    assert crossing == pytest.approx(expected, rel=0.05)
    linear = decay_series(case, "linear", duration=0.5)
    assert crossing > 1.1 * first_crossing(linear["time"], linear["pitch"])
    assert np.mean(motion["z"]) == pytest.approx(info.z_G_equilibrium, abs=0.01 * theory.draft)


@pytest.mark.extended  # make test-extended: ~7 min on 2 ranks, past make test's budget
def test_the_ellipsoid_the_print_calls_stable_turns_over_in_the_fluid(tmp_path):
    """ellipsoid_printed_verdict: the oblate ellipsoid with G high, which the memoir's printed
    criterion says oscillates and the exact theory says capsizes (its GZ curve negative from 0°
    to 180°, stable upside down). Released at 5°, in 3D on the half tank, the mesh made anew
    each time the body has turned run.remesh_angle (30°) from its mesh's attitude: it turns
    over to 180° and past it, its heel history within 10 % in time of the nonlinear inviscid
    model's to 180° (measured: 2.1 % at 10°, 7.1 % at 90°, 6.3 % at 180°: the fluid's added
    inertia, which the model leaves out, slows it), and swings back from a peak beyond 200°
    (measured 246° at 0.787 s, the model's 245° at 0.725 s)."""
    record = 0.85  # past the peak beyond 180° (0.787 s), by 10° of the swing back
    case, theory, motion, info = cfd("ellipsoid_printed_verdict", tmp_path,
                                     [f"run.end_time={record}"], ALONE)
    assert info.mesh == "3d-half" and theory.dofs["roll"].verdict == "capsizes"
    run_dir = tmp_path / "ellipsoid_printed_verdict" / "coarse"
    assert len(list((run_dir / "remeshed").iterdir())) >= 6  # 5° + 6 × 30° > 180°
    t, roll = motion["time"], motion["roll"]
    model = decay_series(case, "nonlinear", duration=1.0)
    for angle in (10.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0):
        cfd_time = t[np.argmax(roll >= angle)]
        model_time = model["time"][np.argmax(model["roll"] >= angle)]
        assert roll.max() >= angle and cfd_time == pytest.approx(model_time, rel=0.10)
    peak = int(np.argmax(roll))
    assert roll[peak] > 200.0 and roll[-1] < roll[peak]  # past upside down, and back


def test_a_users_stl_body_rolls_with_its_added_inertia(tmp_path):
    """A body a user brings as an STL file (cases/stl_pontoon: a 1.2 m pontoon of flattened-
    octagon section) heeled 8°: found symmetric about x = 0 from its triangles, meshed in the
    half tank x ≥ 0 (its STL's flat patches cut along the plane and remeshed by gmsh, three
    prism layers at the body by default, the tetrahedra optimised by Netgen: 79,423 cells at
    the coarse level). On a 0.1 s record (the first sixth of a roll period; its whole record,
    3.6 s, runs under `make stl_pontoon`): stable, starting at 8°, and falling back as the
    fluid's inertia allows — the roll's drop over 0.1 s within 10 % of Cummins' model
    (measured 2.48° against 2.39°, +3.9 %, in the half tank; at release the motion is set by
    the added inertia at infinite frequency), where the body without added inertia (the
    memoir's linear model) would fall 3.75°."""
    case, _, motion, info = cfd("stl_pontoon", tmp_path, ["run.end_time=0.1"])
    assert info.mesh == "3d-half"
    assert motion["roll"][0] == pytest.approx(8.0, abs=1e-3)
    # a 3D tank's coupling ends when the body has converged (run.coupling_tolerance 0.01): on
    # the Laplacian's body-patch motion most steps end after two of their three iterations
    # (measured 30 of 32)
    log = (tmp_path / "stl_pontoon" / "coarse" / "log.interFoam").read_text()
    steps = log.count("\nTime = ")
    converged = log.count("PIMPLE: converged in 2 iterations")
    assert f"Coupling: {converged} of {steps} steps converged" in log
    assert converged > steps / 2

    def drop(series):
        return 8.0 - float(np.interp(0.1, series["time"], series["roll"]))

    assert drop(motion) == pytest.approx(drop(cummins(case, duration=0.5)), rel=0.10)
    assert drop(motion) < 0.8 * drop(decay_series(case, "linear", duration=0.5))
