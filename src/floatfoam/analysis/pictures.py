"""Pictures of the flow around a floating body: free surface, body and water, off-screen.

The free surface is the contour α = 0.5 of the volume fraction (the VOF interface, Hirt &
Nichols 1981), a line in a section and a surface in 3D; the body is its patch (its section,
filled, in a slab or wedge). The water is coloured by its speed |U| or by the vorticity
ω = ∇×U normal to the section (pyvista's ``compute_derivative``). The sections, view boxes and
colour limits are :mod:`floatfoam.analysis.flowview`'s; here they are drawn, through EGL
without an X display: square on (parallel projection) for a slab or a wedge, obliquely from
x < 0 for a 3D body (a cutaway: the section in front, the free surface behind it). Every
picture has a length scale: a bar of a round length in the section's plane, in the air at the
view's upper right.

Cost, measured on the coarse example runs (2 cores, one busy with a solver): 0.3–0.7 s per PNG
and 0.2–0.3 s per GIF frame (one per written time, at most MAX_FRAMES), 8–13 s per GIF of
33–52 frames, whatever the mesh kind: every frame is cropped to the view box before it is cut
and drawn.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from floatfoam import layout
from floatfoam.analysis.flowview import (
    WATER,
    Run,
    View,
    arrows,
    colour_field,
    crop,
    default_times,
    filled,
    first_trough,
    make_view,
    mirrored,
    nearest,
    offscreen_pyvista,
    open_run,
    section_of,
)
from floatfoam.errors import InputError

COLOURS = ("velocity", "vorticity")
WINDOW = (1000, 560)  # PNG pixels
GIF_WINDOW = (640, 358)  # GIF pixels
MAX_FRAMES = 240  # a GIF's frames at most: a longer record is sampled evenly
NEAR_HALF_WIDTH = 1.5  # half width of the near-body view, in body sizes
BODY, SURFACE = "#8c8c8c", "#9ec5e6"
BAR = {"vertical": False, "position_x": 0.3, "position_y": 0.01, "width": 0.4, "height": 0.11,
       "n_labels": 2, "fmt": "%.3g", "color": "black"}
FONT = 10  # points, in a PNG; scaled with the window's height
SCALE_FRACTION = 0.2  # the length scale's bar: the round length nearest this much of the view
#: how the pictures are drawn: pictures drawn in another style are drawn again by the report
#: (2: a length scale, arrows cut at the view box, no picture at t = 0 by default)
STYLE = 2


def scale_length(width: float) -> float:
    """The length of the scale bar of a view ``width`` m wide: the largest of 1, 2 and 5 ×
    10^k m not above :data:`SCALE_FRACTION` of it."""
    target = SCALE_FRACTION * width
    decade = 10.0 ** np.floor(np.log10(target))
    return float(max(m * decade for m in (1.0, 2.0, 5.0) if m * decade <= target * (1 + 1e-9)))


def _body(pl, body, view: View) -> None:
    """The body: its surface in 3D, else its section, filled."""
    if view.kind == "solid":
        _add(pl, body, color=BODY, smooth_shading=True)
    else:
        outline = mirrored([body.slice(normal=view.normal, origin=view.origin)], view)
        _add(pl, filled(outline), color=BODY, lighting=False)


def _flow_scene(pl, run: Run, view: View, time: float, colour: str, label: str) -> None:
    """The water coloured by ``colour``, the free surface and the body at ``time``."""
    body, grid = crop(run, view, time)
    grid, bar, cmap, clim = colour_field(grid, colour, view)
    section = section_of(grid, view)
    flip = colour == "vorticity"
    water = section.clip_scalar(scalars=WATER, value=0.5, invert=False)
    for piece in mirrored([water], view, flip):
        _add(pl, piece, scalars="c", cmap=cmap, clim=clim, lighting=False,
             scalar_bar_args=_bar(pl, bar))
    for line in mirrored([section.contour([0.5], scalars=WATER)], view):
        _add(pl, line, color="black", line_width=2, lighting=False)
    if view.kind == "solid":  # the free surface behind the section (no air drawn in front)
        # shaded, not coloured: its points mix the air's faster spurious currents (VOF)
        surface = grid.contour([0.5], scalars=WATER).clip_box(view.box, invert=False)
        _add(pl, surface, color=SURFACE, smooth_shading=True, specular=0.3)
    _body(pl, body, view)
    _scale_bar(pl, view)
    _label(pl, f"{label}   t = {time:.3f} s")
    _camera(pl, view)


def _add(pl, mesh, **kwargs) -> None:
    """Add a mesh without rendering: the screenshot or frame renders the scene once."""
    pl.add_mesh(mesh, render=False, **kwargs)


def _font(pl, points: float) -> int:
    return max(6, round(points * pl.window_size[1] / WINDOW[1]))


def _bar(pl, title: str) -> dict:
    """The colour bar below the view, titled with the quantity and its unit."""
    return {**BAR, "title": title, "title_font_size": _font(pl, 1.4 * FONT),
            "label_font_size": _font(pl, 1.2 * FONT)}


def _scale_bar(pl, view: View) -> None:
    """A bar of :func:`scale_length` in the section's plane, 4 % of the view's width from the
    view box's right side as seen (its y minimum for a 3D body, seen from x < 0) and 8 % of
    its height below its top (in the air), with end ticks and its length written above it."""
    pv = offscreen_pyvista()
    x0, x1, y0, y1, z0, z1 = view.box
    axis = 0 if view.kind == "wedge" else 1  # the section's horizontal axis
    u0, u1 = (-x1, x1) if view.kind == "wedge" else (y0, y1)  # a wedge shown mirrored
    length = scale_length(u1 - u0)
    right, z = u1 - 0.04 * (u1 - u0), z1 - 0.08 * (z1 - z0)
    if view.kind == "solid":  # seen from x < 0, y grows to the left
        right = u0 + 0.04 * (u1 - u0) + length
    tick = 0.015 * (z1 - z0)

    def point(u, height):
        p = np.array(view.origin, dtype=float)
        p[axis], p[2] = u, height
        return p

    ends = (right - length, right)
    lines = [pv.Line(point(ends[0], z), point(ends[1], z))]
    lines += [pv.Line(point(u, z - tick), point(u, z + tick)) for u in ends]
    _add(pl, pv.merge(lines), color="black", line_width=3, lighting=False)
    pl.add_point_labels([point(right - length / 2, z + 2 * tick)], [f"{length:g} m"],
                        show_points=False, shape=None, always_visible=True,
                        font_size=_font(pl, 1.6 * FONT), text_color="black", render=False)


def _label(pl, text: str) -> None:
    pl.add_text(text.strip(), position="upper_left", font_size=_font(pl, FONT), color="black",
                render=False)


def _camera(pl, view: View) -> None:
    """Parallel projection along the section normal for a slab or wedge, the view box between
    a top margin (the label) and a bottom one (the colour bar); an oblique perspective from
    x < 0 for a 3D body."""
    x0, x1, y0, y1, z0, z1 = view.box
    if view.kind == "solid":
        focus = np.array([view.origin[0], (y0 + y1) / 2, z0 + 0.35 * (z1 - z0)])  # bar below
        eye = np.array([-1.0, -0.3, 0.4]) / np.linalg.norm([-1.0, -0.3, 0.4])
        pl.camera.view_angle = 30.0
        distance = 0.72 * (y1 - y0) / 2 / np.tan(np.radians(15.0))  # the box fills the width
        pl.camera_position = [focus + distance * eye, focus, (0, 0, 1)]
        pl.reset_camera_clipping_range()
        return
    width, height = pl.window_size
    top, bottom = 0.07 * height, 0.16 * height  # pixels
    u0, u1 = (-x1, x1) if view.kind == "wedge" else (y0, y1)
    k = min((height - top - bottom) / (z1 - z0), width / (u1 - u0))  # pixels per metre
    focus = np.zeros(3)
    focus[2] = z0 - bottom / k + height / (2 * k)
    axis = 0 if view.kind == "wedge" else 1
    focus[axis] = (u0 + u1) / 2
    eye = np.zeros(3)
    eye[1 - axis] = -1.0 if view.kind == "wedge" else 1.0
    focus[1 - axis] = view.origin[1 - axis]
    pl.camera_position = [focus + 20 * view.size * eye, focus, (0, 0, 1)]
    pl.enable_parallel_projection()
    pl.camera.parallel_scale = height / (2 * k)
    pl.reset_camera_clipping_range()


def _plotter(window):
    return offscreen_pyvista().Plotter(off_screen=True, window_size=list(window))


def _opened(run_dir) -> Run:
    """``run_dir`` opened (:func:`~floatfoam.analysis.flowview.open_run`), or the Run given."""
    return run_dir if isinstance(run_dir, Run) else open_run(run_dir)


def _check_colour(colour: str) -> None:
    if colour not in COLOURS:
        raise InputError(f"colour = {colour!r}: valid are {', '.join(COLOURS)}")


def flow_pictures(run_dir, out_dir, *, times=None, colour="velocity", title="") -> list[Path]:
    """PNGs of the free surface, the body and the water coloured by ``colour``.

    Parameters
    ----------
    run_dir : path or Run
        A run directory (:func:`~floatfoam.analysis.flowview.open_run`).
    out_dir : path
        Where ``flow_<colour>_t<time>.png`` go (made when missing).
    times : sequence of float, optional
        Times (s), each taken as the nearest written time; by default the first written time
        after the release, the first trough of the released DoF and the last written time
        (:func:`~floatfoam.analysis.flowview.default_times`).
    colour : {"velocity", "vorticity"}
        The speed |U| or the vorticity normal to the section (module docstring).
    title : str
        Written before the time in the picture.

    Returns
    -------
    list of Path
        The PNGs, in time order.

    Raises
    ------
    InputError
        A colour or time outside the record (nothing is written) or a run without fields.
    """
    _check_colour(colour)
    run = _opened(run_dir)
    chosen = sorted({nearest(run, float(t)) for t in times}) if times else default_times(run)
    view = make_view(run)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    pl = _plotter(WINDOW)
    try:
        for t in chosen:
            pl.clear()
            _flow_scene(pl, run, view, t, colour, title)
            paths.append(out / f"flow_{colour}_t{t:.3f}.png")
            pl.render()  # a screenshot renders only the first time
            pl.screenshot(str(paths[-1]))
    finally:
        pl.close()
    return paths


def decay_animation(run_dir, out_path, *, colour="velocity", title="", fps=8.0,
                    max_frames=MAX_FRAMES) -> Path:
    """A GIF of the free decay in the view of :func:`flow_pictures`: one frame per written time,
    evenly sampled down to ``max_frames`` (a bound on its cost), ``fps`` frames a second.

    Returns the GIF's path; raises InputError as :func:`flow_pictures`.
    """
    _check_colour(colour)
    run = _opened(run_dir)
    view = make_view(run)
    step = int(np.ceil(run.times.size / max_frames))
    out = Path(out_path)
    out.parent.mkdir(parents=True, exist_ok=True)
    pl = _plotter(GIF_WINDOW)
    try:
        pl.open_gif(str(out), fps=fps, palettesize=128)
        for t in run.times[::step]:
            pl.clear()
            _flow_scene(pl, run, view, float(t), colour, title)
            pl.write_frame()
    finally:
        pl.close()
    return out


def near_body_snapshot(run_dir, out_path, time=None, *, title="") -> Path:
    """A PNG of the pressure p_rgh − p_atm and the water's velocity arrows in the section,
    1.5 body sizes around the body, at ``time`` (s; default: the first trough).

    interFoam's p_rgh = p − ρ g·x (OpenFOAM v1912, ``interFoam/createFields.H``) is uniform in
    water at rest, so its departure from p_atm (its median in the air of the section) is the
    dynamic pressure plus the hydrostatic pressure of the free surface's elevation.
    Returns the PNG's path; raises InputError as :func:`flow_pictures`.
    """
    run = _opened(run_dir)
    time = first_trough(run) if time is None else nearest(run, float(time))
    view = make_view(run, half_width=NEAR_HALF_WIDTH)
    if view.kind == "solid":  # a section is flat: seen square on, as a slab's
        view = replace(view, kind="slab")
    body, grid = crop(run, view, time)
    section = section_of(grid, view)
    air = section[WATER] < 0.5
    section["c"] = section["p_rgh"] - (np.median(section["p_rgh"][air]) if air.any() else 0.0)
    limit = float(np.percentile(np.abs(section["c"]), 99)) or 1.0
    out = Path(out_path)
    out.parent.mkdir(parents=True, exist_ok=True)
    pl = _plotter(WINDOW)
    try:
        for piece in mirrored([section], view):
            _add(pl, piece, scalars="c", cmap="RdBu_r", clim=(-limit, limit), lighting=False,
                 scalar_bar_args=_bar(pl, "p_rgh - p_atm (Pa)"))
        for line in mirrored([section.contour([0.5], scalars=WATER)], view):
            _add(pl, line, color="black", line_width=2, lighting=False)
        glyphs, speed = arrows(grid, view)
        for piece in mirrored([glyphs], view):
            _add(pl, piece, color="black", lighting=False)
        _body(pl, body, view)
        _scale_bar(pl, view)
        _label(pl, f"{title}   t = {time:.3f} s   arrows: water velocity, one grid step "
                   f"= {speed:.2g} m/s")
        _camera(pl, view)
        pl.render()  # a screenshot renders only the first time
        pl.screenshot(str(out))
    finally:
        pl.close()
    return out


def case_pictures(case_name: str, level: str, build=None, *, colour="velocity",
                  times=None) -> list[tuple[Path, str]]:
    """The pictures of a finished run, for the report, in ``<build>/<case>/pictures/<level>/``:
    :func:`flow_pictures` at ``times``, :func:`near_body_snapshot` at the first trough and
    :func:`decay_animation`.

    Returns
    -------
    list of (Path, str)
        Each picture and its alt text.

    Raises
    ------
    InputError
        An unknown level, no finished run at that level, a run without fields, a colour or a
        time outside the record: one line, nothing written.
    """
    if level not in layout.LEVELS:
        raise InputError(f"--level {level!r}: valid levels are {', '.join(layout.LEVELS)}")
    return run_pictures(layout.run_dir(case_name, level, build), colour=colour, times=times)


def run_pictures(run_dir, *, colour="velocity", times=None) -> list[tuple[Path, str]]:
    """:func:`case_pictures` of the run in ``run_dir`` (``<build>/<case>/<run>``), in
    ``<build>/<case>/pictures/<run>/``."""
    run_dir = Path(run_dir)
    case_name, level = run_dir.parent.name, run_dir.name
    if not layout.is_finished(run_dir):
        raise InputError(f"RUN {run_dir}: no finished run there; valid is a finished run "
                         "(floatfoam run CASE with its level finishes it)")
    _check_colour(colour)
    run = open_run(run_dir)
    for t in times or ():  # every time checked before anything is written
        nearest(run, float(t), name="--times")
    out = run_dir.parent / "pictures" / level
    label = f"{case_name}/{level}"
    what = "speed" if colour == "velocity" else "vorticity normal to the section"
    pairs = [(p, f"{label}: free surface (black line), body (grey) and water coloured by its "
                 f"{what} at t = {p.stem.split('_t')[-1]} s")
             for p in flow_pictures(run, out, times=times, colour=colour, title=label)]
    snap = near_body_snapshot(run, out / "near_body.png", title=label)
    pairs.append((snap, f"{label}: pressure p_rgh − p_atm and water velocity arrows near the "
                        "body at its first trough"))
    gif = decay_animation(run, out / f"decay_{colour}.gif", colour=colour, title=label)
    pairs.append((gif, f"{label}: the free decay, one frame per written time, water coloured "
                       f"by its {what}"))
    return pairs
