"""Pictures of the flow (floatfoam.analysis.pictures, ``floatfoam pictures``).

Refusals and the choice of times run on a one-cell case written here by hand (no OpenFOAM
utility runs in the fast tests), the arrows on a synthetic grid; one test (marker
``openfoam``) renders a short real run.
"""

import os
import subprocess
import sys

import numpy as np
import pytest
from fakes import fake_run

from floatfoam.analysis.flowview import (
    View,
    arrows,
    default_times,
    nearest,
    offscreen_pyvista,
    open_run,
)
from floatfoam.analysis.pictures import scale_length
from floatfoam.errors import InputError


def files_under(folder):
    return sorted(p for p in folder.rglob("*"))


def pictures(build, *argv):
    env = {**os.environ, "FLOATFOAM_BUILD": str(build)}
    env.pop("DISPLAY", None)
    return subprocess.run([sys.executable, "-m", "floatfoam.cli", "pictures", *argv], env=env,
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("argv, says", [
    (["sphere", "--level", "huge"], "--level 'huge'"),
    (["sphere", "--level", "medium"], "no run in"),
    (["sphere", "--times", "0.1", "5"], "--times 5 s"),
    (["sphere", "--times", "-0.1"], "--times -0.1 s"),
    (["sphere", "--colour", "red"], "--colour 'red'"),
    (["sphere", "--set", "mass.density=300"], "--set"),
])
def test_bad_input_is_refused_in_one_line_and_nothing_written(tmp_path, argv, says):
    fake_run(tmp_path)
    before = files_under(tmp_path)
    proc = pictures(tmp_path, *argv)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and says in lines[0] and "Traceback" not in proc.stderr
    assert files_under(tmp_path) == before


@pytest.mark.parametrize("kind", ["only the release written", "no alpha field", "unfinished"])
def test_run_without_pictures_is_refused(tmp_path, kind):
    if kind == "only the release written":
        fake_run(tmp_path, times=(0.0,))
    elif kind == "no alpha field":
        fake_run(tmp_path, fields=("U", "p_rgh"))
    else:
        fake_run(tmp_path, finished=False)
    before = files_under(tmp_path)
    proc = pictures(tmp_path, "sphere")
    expected = {"only the release written": "no written time beyond 0",
                "no alpha field": "no field alpha.water", "unfinished": "no finished run"}[kind]
    assert proc.returncode == 2 and expected in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
    assert files_under(tmp_path) == before


def test_default_times_are_after_the_release_first_trough_and_last(tmp_path):
    """The record z = 0.01 cos(πt/0.2) has its first trough at 0.2 s; the first written time
    after the release is 0.1 s (at t = 0 the water is at rest: its speed, one colour)."""
    run = open_run(fake_run(tmp_path))
    assert run.dof == "heave" and list(run.times) == pytest.approx([0.0, 0.1, 0.2, 0.3])
    assert default_times(run) == pytest.approx([0.1, 0.2, 0.3])
    assert nearest(run, 0.26) == pytest.approx(0.3)
    with pytest.raises(InputError, match="0 … 0.3 s"):
        nearest(run, 0.31)


@pytest.mark.parametrize("width, length", [(1.5, 0.2), (0.45, 0.05), (3.0, 0.5), (1.0, 0.2),
                                           (0.1, 0.02)])
def test_the_scale_bar_is_a_round_length_near_a_fifth_of_the_view(width, length):
    assert scale_length(width) == pytest.approx(length)


def test_arrows_stay_inside_the_view_box():
    """A jet three times faster than the rest (the 95th percentile sets an arrow's length) near
    the box's bottom: its arrows, several grid steps long, are cut at the box and do not reach
    the colour bar's margin below it."""
    pv = offscreen_pyvista()
    box = (0.0, 1.0, -0.75, 0.75, -0.41, 0.26)
    view = View("slab", (1.0, 0.0, 0.0), (0.5, 0.0, 0.0), box, 0.3, 0.1)
    grid = pv.ImageData(dimensions=(3, 80, 60), spacing=(0.5, 0.023, 0.015),
                        origin=(0.0, -0.9, -0.5)).cast_to_unstructured_grid()
    y, z = grid.points[:, 1], grid.points[:, 2]
    grid["alpha.water"] = (z < 0.0).astype(float)
    jet = np.exp(-((y - 0.5) ** 2 + (z + 0.36) ** 2) / 0.01)
    grid["U"] = np.column_stack([0 * y, np.sin(10 * z), -3.0 * jet])
    glyphs, speed = arrows(grid, view)
    assert glyphs.n_points and 0.0 < speed < 3.0
    bounds = np.reshape(glyphs.bounds, (3, 2))
    assert np.all(bounds[1:, 0] >= np.reshape(box, (3, 2))[1:, 0] - 1e-6)
    assert np.all(bounds[1:, 1] <= np.reshape(box, (3, 2))[1:, 1] + 1e-6)


@pytest.mark.openfoam
def test_pictures_of_a_short_sphere_run(tmp_path):
    """0.12 s of the sphere's heave (wedge), fields every 0.04 s, rendered: the PNGs are images
    of the window's size with the colours of the water, the body and the colour bar; the GIF
    has one frame per written time."""
    import imageio.v3 as iio

    from floatfoam.analysis.pictures import GIF_WINDOW, WINDOW, case_pictures
    from floatfoam.case import load_case
    from floatfoam.foam.driver import run_case

    case = load_case("sphere", ["run.end_time=0.12", "run.write_interval=0.04"])
    result = run_case(case, "coarse", 2, build_dir=tmp_path)
    run = open_run(result.run_dir)
    written = run.times
    assert written == pytest.approx([0.0, 0.04, 0.08, 0.12], abs=1e-6)
    flows = len(default_times(run))  # 2: 0.04 s and the last (no trough yet: at ~0.31 s)
    pairs = case_pictures("sphere", "coarse", tmp_path)  # ~3 s (its cost: the note, not here)
    pngs = [p for p, _ in pairs if p.suffix == ".png"]
    assert len(pngs) == flows + 1 and all(alt for _, alt in pairs)  # + the near-body one
    viridis_low = np.array([68, 1, 84])  # water at rest: the bottom of the colour map
    for png in pngs:
        image = iio.imread(png)[..., :3]
        assert image.shape == (WINDOW[1], WINDOW[0], 3)
        colours = np.unique(image.reshape(-1, 3), axis=0)
        assert len(colours) > 200  # not blank: a colour map, shading, text
    flow = iio.imread(pngs[0])[..., :3].reshape(-1, 3)
    water = np.all(np.abs(flow.astype(int) - viridis_low) <= 3, axis=1)
    assert water.mean() > 0.05  # the still water far from the body
    gif = next(p for p, _ in pairs if p.suffix == ".gif")
    frames = iio.imread(gif, index=None)
    assert frames.shape[:3] == (written.size, GIF_WINDOW[1], GIF_WINDOW[0])
