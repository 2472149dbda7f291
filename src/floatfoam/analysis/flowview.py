"""A run directory's fields as the pictures see them: reader, written times, section, view box.

pyvista reads a run directory with its own OpenFOAM reader (``vtkPOpenFOAMReader``: a
decomposed case, the points of the moving mesh at every written time). The section and the
view box follow the mesh kind of ``.floatfoam/info.json``:

* slabs (``2d``, ``ogrid``), one cell thick along x: the mid-plane x = const;
* ``wedge``, 5° about the z axis: its mid-plane y = 0, reflected about the axis x = 0 to show
  the whole meridian section;
* ``3d``, ``3d-half``: the section x = x_G (just inside the symmetry plane of a half domain).

The view box spans a few body sizes around the body at the release: the tank is far larger,
and cropping to it keeps a frame cheap. Colour limits are fixed over a run from the body's
peak speed in motion.csv, so that frames compare.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from floatfoam.errors import InputError
from floatfoam.layout import mesh_parts, time_folders
from floatfoam.plan.record import has_record, read_record, record_path

SLABS, WEDGES, SOLIDS = ("2d", "ogrid"), ("wedge",), ("3d", "3d-half")
WATER = "alpha.water"
HALF_WIDTH = 2.5  # half width of the view box, in body sizes (its height is 0.9 of it)
SPEED_FRACTION = 0.5  # colour limit of |U| in the body's peak speed: the water moves slower
VORTICITY_SCALE = 10.0  # colour limit of ω in U_body / size: the shed vortices, not the wall


def offscreen_pyvista():
    """pyvista set to render off-screen through EGL (libegl1 + Mesa), with no X display.

    VTK ≥ 9.4 picks its window class from ``VTK_DEFAULT_OPENGL_WINDOW`` when it loads; without
    it, it tries X first and warns (then falls back to EGL)."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    pv.OFF_SCREEN = True
    return pv


@dataclass
class Run:
    """A run directory opened for pictures: its reader, written times (s), mesh kind and the
    DoF its release displaces (roll after a heel, pitch after a trim, else heave)."""

    path: Path
    reader: object
    times: np.ndarray
    mesh: str
    dof: str
    parts: tuple = ()  # (reader, its times) of each mesh of a remeshed run, in time order

    def read(self, time: float):
        """The internal mesh (point data only) and the body patch at a written time (on the
        mesh of that time, for a remeshed run)."""
        reader = self.reader
        for part, times in self.parts:
            reader = part
            if times.size and time <= times[-1] + 1e-9:
                break
        reader.set_active_time_value(time)
        blocks = reader.read()
        internal = blocks["internalMesh"]
        internal.clear_cell_data()  # the reader interpolates every field to the points
        return internal, blocks["boundary"]["body"]


def open_run(run_dir) -> Run:
    """Open a run directory written by ``floatfoam run``.

    Parameters
    ----------
    run_dir : path
        ``<build>/<case>/<level>``: an OpenFOAM case (decomposed or not) with
        ``.floatfoam/info.json``.

    Returns
    -------
    Run

    Raises
    ------
    InputError
        One line when it is no such case, has no written time beyond 0, no ``alpha.water``
        field or no patch ``body``.
    """
    run = Path(run_dir)
    if not (run / "system" / "controlDict").is_file() or not has_record(run):
        raise InputError(f"run directory {run}: no OpenFOAM case with {record_path(run).name}; "
                         "valid is a run directory written by floatfoam run")
    info = read_record(run)
    mesh = info.mesh
    if mesh not in SLABS + WEDGES + SOLIDS:
        raise InputError(f"{record_path(run)}: mesh = {mesh!r}; valid are "
                         f"{', '.join(SLABS + WEDGES + SOLIDS)}")
    parts = []
    for folder in mesh_parts(run):  # a remeshed run's meshes, each its own case
        reader = offscreen_pyvista().POpenFOAMReader(str(folder / "system" / "controlDict"))
        if decomposed(folder):
            reader.case_type = "decomposed"
        reader.disable_all_patch_arrays()
        reader.enable_patch_array("internalMesh")
        if "patch/body" not in reader.patch_array_names:
            raise InputError(f"run directory {run}: no patch 'body'; valid is a floating-body "
                             "run")
        reader.enable_patch_array("patch/body")
        times = np.asarray(reader.time_values, dtype=float)
        if parts:  # a remeshing's time is the earlier mesh's
            times = times[times > parts[-1][1][-1] + 1e-9]
        parts.append((reader, times))
    reader = parts[0][0]
    times = np.concatenate([t for _, t in parts])
    if times.size < 2 or times.max() <= 0.0:
        raise InputError(f"run directory {run}: no written time beyond 0; valid is a run that "
                         "wrote fields (run.write_interval below run.end_time)")
    if WATER not in reader.cell_array_names:
        raise InputError(f"run directory {run}: no field {WATER}; valid is an interFoam run")
    dof = "roll" if info.heel else "pitch" if info.trim else "heave"
    return Run(run, reader, times, mesh, dof, tuple(parts) if len(parts) > 1 else ())


def decomposed(run: Path) -> bool:
    """Whether the fields are in processor* folders only (no reconstructed time beyond 0)."""
    return any(run.glob("processor*")) and not time_folders(run)


def first_trough(run: Run) -> float:
    """The written time nearest the first extremum of the released DoF in motion.csv.

    Half a damped period after the release (:func:`floatfoam.analysis.extrema.first_extrema`):
    the body at rest, the flow it set going still there. The middle written time when the body
    is held still (no motion.csv)."""
    from floatfoam.analysis.extrema import first_extrema
    from floatfoam.motion import dof_series, read_motion

    if not (run.path / "motion.csv").is_file():
        return float(run.times[run.times.size // 2])
    t, x = dof_series(read_motion(run.path / "motion.csv"), run.dof)
    turns = first_extrema(x, 1)
    return nearest(run, float(t[turns[0]]) if turns.size else float(t[-1]))


def nearest(run: Run, time: float, *, name: str = "time") -> float:
    """The written time nearest ``time`` (s); an InputError naming ``name`` outside the record
    [0, last written time]."""
    last = float(run.times[-1])
    if not -1e-9 <= time <= last + 1e-9:
        raise InputError(f"{name} {time:g} s: valid is within the written record 0 … {last:g} s "
                         f"of {run.path}")
    return float(run.times[np.argmin(np.abs(run.times - time))])


def default_times(run: Run) -> list[float]:
    """The first written time after the release, the first trough of the released DoF and the
    last written time. Not t = 0: the water is at rest there, and a picture of its speed is
    one colour (:func:`open_run` ensures a written time beyond 0)."""
    after = float(run.times[run.times > 0.0][0])
    return sorted({after, first_trough(run), float(run.times[-1])})


@dataclass(frozen=True)
class View:
    """The section and view box of a run (see the module docstring)."""

    kind: str  # slab, wedge or solid
    normal: tuple  # of the section
    origin: tuple  # a point of the section: the body's centre at the release
    box: tuple  # (xmin, xmax, ymin, ymax, zmin, zmax) in view, before the wedge's reflection
    size: float  # body size (m): its largest width
    speed: float  # the body's peak speed (m/s)


def make_view(run: Run, *, half_width: float = HALF_WIDTH) -> View:
    """The view of ``run``: its section through the body at the release and a box
    ``half_width`` body sizes either side of it, 0.55 of that below and 0.35 above."""
    internal, body = run.read(float(run.times[0]))
    d, b = internal.bounds, body.bounds
    c = [(b[2 * i] + b[2 * i + 1]) / 2 for i in range(3)]
    if run.mesh in SLABS:
        kind, normal, size = "slab", (1.0, 0.0, 0.0), max(b[3] - b[2], b[5] - b[4])
        c[0] = (d[0] + d[1]) / 2
    elif run.mesh in WEDGES:
        kind, normal, size = "wedge", (0.0, 1.0, 0.0), max(2 * b[1], b[5] - b[4])
        c[:2] = 0.0, 0.0
    else:
        kind, normal = "solid", (1.0, 0.0, 0.0)
        half = run.mesh == "3d-half"
        size = max((2 if half else 1) * (b[1] - b[0]), b[3] - b[2], b[5] - b[4])
        c[0] = d[0] + 1e-3 * size if half else c[0]  # just inside the symmetry plane
    w = half_width * size
    box = (d[0], d[1], c[1] - w, c[1] + w, c[2] - 0.55 * w, c[2] + 0.35 * w)
    if kind == "wedge":
        box = (0.0, w, d[2], d[3], box[4], box[5])
    elif kind == "solid":
        box = (d[0], c[0] + w, box[2], box[3], box[4], box[5])
    return View(kind, normal, tuple(c), box, size, speed_scale(run, size))


def speed_scale(run: Run, size: float) -> float:
    """The body's peak speed (m/s): max |(u, v, w)| + max |(p, q, r)|·size/2 over motion.csv
    (rates in deg/s, docs/conventions.md); a tenth of √(g·size) for a body held still."""
    from floatfoam.motion import read_motion

    if not (run.path / "motion.csv").is_file():
        return 0.1 * float(np.sqrt(9.81 * size))
    m = read_motion(run.path / "motion.csv")
    linear = np.sqrt(m["u"] ** 2 + m["v"] ** 2 + m["w"] ** 2).max()
    angular = np.deg2rad(np.abs(np.stack([m["p"], m["q"], m["r"]])).max()) * size / 2
    return float(linear + angular) or 1e-3


def colour_field(grid, colour: str, view: View):
    """The colour array 'c' of ``grid``, its bar title, colour map and limits.

    ``velocity``: the speed |U|, 0 … ``SPEED_FRACTION`` × the body's peak speed;
    ``vorticity``: ω·n, the component of ω = ∇×U along the section's normal (the one a 2D or
    axisymmetric flow has), ± ``VORTICITY_SCALE`` × peak speed / size."""
    if colour == "velocity":
        grid["c"] = np.linalg.norm(grid.point_data["U"], axis=1)
        return grid, "speed (m/s)", "viridis", (0.0, SPEED_FRACTION * view.speed)
    axis = int(np.argmax(view.normal))
    grid = grid.compute_derivative(scalars="U", gradient=False, vorticity=True)
    grid["c"] = grid.point_data["vorticity"][:, axis]
    limit = VORTICITY_SCALE * view.speed / view.size
    return grid, f"{'xyz'[axis]}-vorticity (1/s)", "coolwarm", (-limit, limit)


def mirrored(pieces, view: View, flip: bool = False) -> list:
    """The pieces and, for a wedge, their reflection about x = 0 (the whole meridian section),
    vectors reflected too; ``flip`` negates 'c' in the reflection (ω_y changes sign there)."""
    if view.kind != "wedge":
        return list(pieces)
    out = list(pieces)
    for piece in pieces:
        other = piece.reflect((1.0, 0.0, 0.0), point=(0.0, 0.0, 0.0),
                              transform_all_input_vectors=True)
        if flip and "c" in other.point_data:
            other["c"] = -other["c"]
        out.append(other)
    return out


def crop(run: Run, view: View, time: float):
    """The body patch and the internal mesh's whole cells in a box 20 % beyond the view box
    (a crinkle clip: cheap) at ``time``."""
    internal, body = run.read(time)
    b = np.reshape(view.box, (3, 2))
    margin = 0.2 * (b[:, 1] - b[:, 0])[:, None] * np.array([-1.0, 1.0])
    grid = internal.clip_box(tuple((b + margin).ravel()), invert=False, crinkle=True)
    return body, grid


def section_of(grid, view: View):
    """The section of ``grid`` (module docstring), clipped to the view box (clean edges)."""
    section = grid.slice(normal=view.normal, origin=view.origin)
    return section.clip_box(view.box, invert=False)


def filled(outline):
    """A closed outline triangulated into a face (vtkContourTriangulator: pyvista has no verb)."""
    from vtkmodules.vtkFiltersGeneral import vtkContourTriangulator

    pv = offscreen_pyvista()
    merged = pv.merge(outline).clean(tolerance=1e-6) if len(outline) > 1 else outline[0]
    tri = vtkContourTriangulator()
    tri.SetInputData(merged)
    tri.Update()
    return pv.wrap(tri.GetOutput())


def arrows(grid, view: View, count: int = 36):
    """Arrows of the water's in-plane velocity on a regular grid of the section (``count``
    across), cut at the view box, and the speed of an arrow one grid step long: the 95th
    percentile of the sampled speeds (the air's faster currents at the interface are left
    out)."""
    pv = offscreen_pyvista()
    x0, x1, y0, y1, z0, z1 = view.box
    axis = int(np.argmax(view.normal))
    u = np.linspace(*((x0, x1) if axis == 1 else (y0, y1)), count)
    z = np.linspace(z0, z1, count // 2)
    U, Z = np.meshgrid(u, z)
    points = np.zeros((U.size, 3))
    points[:, 2] = Z.ravel()
    points[:, 0 if axis == 1 else 1] = U.ravel()
    points[:, axis] = view.origin[axis]
    probes = pv.PolyData(points).sample(grid)
    velocity = probes["U"].copy()
    velocity[:, axis] = 0.0  # in the section
    water = (probes["vtkValidPointMask"] > 0) & (probes[WATER] >= 0.9)  # off the interface
    probes["V"] = velocity * water[:, None]
    speeds = np.linalg.norm(probes["V"][water], axis=1)
    speed = float(np.percentile(speeds, 95)) if speeds.size else 0.0
    speed = speed if speed > 0.0 else 1.0  # water at rest: no arrow has a length
    arrow = pv.Arrow(tip_length=0.35, shaft_radius=0.04, tip_radius=0.12)
    factor = (u[1] - u[0]) / speed
    glyphs = probes.glyph(orient="V", scale="V", factor=factor, geom=arrow)
    # cut at the view box: a jet's arrows, several steps long, reached into the colour bar's
    # margin below it and covered its title
    return glyphs.clip_box(view.box, invert=False), speed
