"""A body given by triangles that is a body of revolution about z: found from its horizontal
cross-sections, its meridian through their equal-area radii, and the wedge it is meshed in
when upright and in heave (floatfoam.bodies.revolution, floatfoam.plan.kind.default_kind)."""

import math
import shutil

import numpy as np
import pytest
from bodycases import IMPLICIT_SPHERE as SPHERE
from bodycases import torus

from floatfoam.bodies.geometry import extrude_polygon, icosphere, mesh_volume, open_edges
from floatfoam.bodies.revolution import REVOLUTION_TOLERANCE, cross_section, meridian
from floatfoam.bodies.shapes import VerticalCylinder
from floatfoam.case import load_case, with_overrides
from floatfoam.hydrostatics.theory import equilibrium
from floatfoam.meshing.domains import build_domain
from floatfoam.meshing.volume_report import discrete_volume_report


def rings_sphere(radius: float, rings: int, sides: int):
    """A sphere as an STL of revolution is usually written: poles, and rings of ``sides``
    vertices at ``rings`` − 1 latitudes, outward."""
    lat = np.linspace(0.0, math.pi, rings + 1)[1:-1]
    lon = np.linspace(0.0, 2.0 * math.pi, sides, endpoint=False)
    ring = np.array([[math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), -math.cos(t)]
                     for t in lat for p in lon])
    vertices = radius * np.vstack([[0.0, 0.0, -1.0], ring, [0.0, 0.0, 1.0]])
    top, faces = len(vertices) - 1, []
    for j in range(sides):
        k = (j + 1) % sides
        faces.append((0, 1 + k, 1 + j))
        last = 1 + (rings - 2) * sides
        faces.append((last + j, last + k, top))
        for i in range(rings - 2):
            a, b = 1 + i * sides + j, 1 + i * sides + k
            faces += [(a, b, b + sides), (a, b + sides, a + sides)]
    faces = np.array(faces)
    return (vertices, faces) if mesh_volume(vertices, faces) > 0 else (vertices, faces[:, ::-1])


def revolved_volume(profile: np.ndarray) -> float:
    """The volume of the body of revolution of a polyline meridian (frustums)."""
    r, z = profile[:, 0], profile[:, 1]
    return float(np.sum(math.pi * np.diff(z) * (r[1:] ** 2 + r[1:] * r[:-1] + r[:-1] ** 2)
                        / 3.0))


def test_a_sphere_in_rings_has_its_triangles_volume_and_its_ends_on_the_axis():
    """Through the equal-area radii of its rings, the meridian's body of revolution holds the
    STL's volume (its polygons' areas) to the frustums' error between rings, not the exact
    sphere's: 64 sides are 0.16 % short of their circles."""
    vertices, faces = rings_sphere(0.1, 32, 64)
    profile = meridian(vertices, faces)
    assert profile is not None
    assert tuple(profile[0]) == (0.0, pytest.approx(-0.1)) and tuple(profile[-1]) == (
        0.0, pytest.approx(0.1))
    assert np.all(np.diff(profile[:, 1]) >= 0.0)
    # the rings' cross-sections are the polygons themselves, so the frustums through their
    # equal-area radii are the STL's volume (measured: to round-off)
    assert revolved_volume(profile) / mesh_volume(vertices, faces) - 1 == pytest.approx(0,
                                                                                    abs=2e-5)
    assert mesh_volume(vertices, faces) / (4 / 3 * math.pi * 0.1**3) < 0.997


def test_rings_scattered_in_single_precision_and_a_flange():
    """An STL's ring heights scatter by ~1e-7 of its coordinates: the rings are still one point
    each (33 on a sphere of 32 rings). A cylinder on a wider one (a flange) steps: two points at
    the step's height, each side's radius from its own cross-sections."""
    vertices, faces = rings_sphere(0.1, 32, 64)
    clean = meridian(vertices, faces)
    noisy = vertices * (1.0 + 1e-7 * np.random.default_rng(1).standard_normal(vertices.shape))
    profile = meridian(noisy, faces)
    assert len(profile) == len(clean) == 33
    assert revolved_volume(profile) / mesh_volume(noisy, faces) - 1 == pytest.approx(0, abs=1e-5)
    vertices, faces = _stacked(_cylinder(0.1, -0.1, 0.0), _cylinder(0.05, 0.0, 0.1))
    assert open_edges(faces) == 0
    profile = meridian(vertices, faces)
    steps = profile[np.isclose(profile[:, 1], 0.0)]
    area = 0.5 * 96 * math.sin(2 * math.pi / 96)
    assert sorted(steps[:, 0]) == pytest.approx([0.05 * math.sqrt(area / math.pi),
                                                 0.1 * math.sqrt(area / math.pi)], rel=1e-6)


def test_a_rounded_keel_under_a_long_wall_is_a_spline_and_a_line():
    """A hemisphere's 12 rings and then a wall 5 × its radius high with no ring between: the
    wall is a line (a chord 3 × longer than its neighbour), so the keel's spline does not swing
    across the axis, as one spline through both would (to r = −0.035 m)."""
    from floatfoam import gmshio
    from floatfoam.meshing.sections import _profile_curves

    lat = np.linspace(0, math.pi / 2, 13)[1:]
    profile = np.array([(0.0, -0.05), *[(0.05 * math.sin(t), -0.05 * math.cos(t)) for t in lat],
                        (0.05, 0.25), (0.0, 0.25)])
    with gmshio.session("meridian") as gmsh:
        curves = _profile_curves(gmsh.model.occ, profile)
        gmsh.model.occ.synchronize()
        radii = []
        for curve in curves:
            lo, hi = gmsh.model.getParametrizationBounds(1, curve)
            values = gmsh.model.getValue(1, curve, list(np.linspace(lo[0], hi[0], 100)))
            radii.append(min(values[0::3]))
    assert len(curves) == 3 and min(radii) > -1e-12


def test_a_sphere_not_in_rings_and_a_vertical_cylinder():
    """An icosphere's vertices lie in no rings: cross-sections at levels closer together near
    the poles, whose frustums hold its volume to 1e-4 (the chords of the meridian between
    161 levels: measured −9.6e-5). A vertical cylinder of 512 sides: four points, its flat
    bottom and top exact."""
    vertices, faces = icosphere(4)
    profile = meridian(0.1 * vertices, faces)
    assert profile is not None
    assert revolved_volume(profile) / mesh_volume(0.1 * vertices, faces) - 1 == pytest.approx(
        0, abs=2e-4)
    body = VerticalCylinder(0.1, 0.2)
    profile = meridian(*body.surface_mesh())
    area = 0.5 * 512 * 0.1**2 * math.sin(2 * math.pi / 512)
    assert profile == pytest.approx(np.array([[0.0, -0.1], [math.sqrt(area / math.pi), -0.1],
                                              [math.sqrt(area / math.pi), 0.1], [0.0, 0.1]]))
    assert body.is_axisymmetric


@pytest.mark.parametrize("change", ["off the axis", "out of round", "a box", "a ring",
                                    "a pipe"])
def test_bodies_that_are_not_of_revolution_about_z(change):
    """Off the axis by 2 % of the radius, 3 % out of round, a square section, a torus and a
    hollow cylinder (two loops at every cut) are not; 0.5 % out of round is (within
    REVOLUTION_TOLERANCE)."""
    vertices, faces = rings_sphere(0.1, 24, 48)
    if change == "off the axis":
        vertices = vertices + [0.002, 0.0, 0.0]
    elif change == "out of round":
        assert meridian(vertices * [1.0, 1.005, 1.0], faces) is not None
        vertices = vertices * [1.0, 1.03, 1.0]
    elif change == "a box":
        vertices, faces = extrude_polygon(np.array([[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1],
                                                    [-0.1, 0.1]]), 0.2)
        vertices = vertices[:, [1, 2, 0]]  # the extrusion along z
    elif change == "a ring":
        vertices, faces = torus(0.1, 0.03)
    else:
        vertices, faces = _pipe(0.1, 0.05, 0.2)
    assert meridian(vertices, faces) is None


def test_a_cross_section_is_its_loops():
    """The plane through a torus's middle cuts two loops of its tube's radii; above its top,
    none."""
    vertices, faces = torus(0.1, 0.03)
    loops = cross_section(vertices, faces, 0.001)
    assert len(loops) == 2
    radii = sorted(float(np.hypot(*loop.T).mean()) for loop in loops)
    assert radii == pytest.approx([0.07, 0.13], rel=0.01)
    assert cross_section(vertices, faces, 0.04) == []




def test_a_body_of_revolution_given_by_triangles_heaves_in_a_wedge(tmp_path):
    """An implicit sphere released in heave is meshed as the sphere shape is, in a wedge: its
    meridian's body of revolution within 2e-4 of its triangles' volume (the chords between
    161 levels), the mesh's body within the wedge's own chords of it, as the sphere's
    (coarse: −1.8e-3 immersed; 5e-3 the meshing tests' bound at coarse); with
    mesh.gmsh.wedge = false, or heeled, in the half tank."""
    (tmp_path / "case.toml").write_text(SPHERE)
    case = load_case(str(tmp_path))
    assert case.body.is_axisymmetric
    assert revolved_volume(case.body.meridian) / case.body.volume() - 1 == pytest.approx(
        0, abs=2e-4)
    result = build_domain(case, "coarse", path=tmp_path / "w.msh")
    assert result["kind"] == "wedge"
    assert abs(result["body_patch"]["immersed_error"]) < 5e-3
    report = discrete_volume_report(case, "coarse")
    assert abs(report["meridian"]["volume_error"]) < 5e-3
    for setting in ("mesh.gmsh.wedge=false", "release.heel=2.0"):
        kind = build_domain(with_overrides(case, [setting, "mesh.gmsh.body_cells_3d=4"]),
                            "coarse", path=tmp_path / "h.msh")["kind"]
        assert kind == "3d-half"


def test_an_implicit_float_with_a_sharp_rim(tmp_path):
    """A hemisphere under a cylinder with a flat top, written as an implicit surface: marching
    cubes round its top rim by a chamfer aligned with its grid, 2 % out of round within a
    grid cell of the top, where a cross-section is not asked to be round. A body of
    revolution, its meridian's top a corner at the rim's radius."""
    (tmp_path / "case.toml").write_text(
        '[body]\nshape = "implicit"\nexpression = "minimum(maximum(sqrt(x**2 + y**2 + z**2) '
        '- 0.15, z), maximum(sqrt(x**2 + y**2) - 0.15, abs(z - 0.05) - 0.05))"\n'
        'bounds = [[-0.16, -0.16, -0.16], [0.16, 0.16, 0.11]]\nresolution = 80\n'
        '[mass]\ndensity = 400.0\ncog = [0.0, 0.0, -0.04]\ngyradius = [0.08, 0.08, 0.08]\n')
    body = load_case(str(tmp_path)).body
    assert body.is_axisymmetric
    top = body.meridian[-2]
    assert top[1] == pytest.approx(0.1, abs=1e-6) and top[0] == pytest.approx(0.15, rel=0.02)
    # the chords between 161 levels, as the icosphere's (measured −2.8e-5)
    assert revolved_volume(body.meridian) / body.volume() - 1 == pytest.approx(0, abs=2e-4)
    if shutil.which("gmshToFoam") is None:  # OpenFOAM not installed
        return
    from floatfoam.foam.meshcheck import convert_and_check

    # its wedge converts and checks clean: no curve of the meridian a hair long at the rim
    # (a curve 0.8 mm long there makes a cell folded by 173°)
    result = build_domain(load_case(str(tmp_path)), "coarse", path=tmp_path / "f.msh")
    quality = convert_and_check(tmp_path / "f.msh", tmp_path / "foam")
    assert result["kind"] == "wedge" and quality["mesh_ok"]


def test_layers_are_refused_in_a_wedge_only_when_asked(tmp_path):
    """Left out, the prism layers of a body given by triangles are a 3D default and a wedge
    takes none; asked for, a wedge refuses them in one line naming the way to 3D."""
    (tmp_path / "case.toml").write_text(SPHERE + "[mesh.gmsh]\nlayers_3d = 3\n")
    with pytest.raises(Exception, match=r"layers_3d = 3: .* valid is 0, or mesh.gmsh.wedge "
                                        r"= false"):
        build_domain(load_case(str(tmp_path)), "coarse", path=tmp_path / "w.msh")


def _cylinder(radius: float, bottom: float, top: float, n: int = 96):
    """A vertical cylinder of ``n`` sides between two heights: vertices, faces, outward."""
    a = np.linspace(0, 2 * math.pi, n, endpoint=False)
    ring = radius * np.column_stack([np.cos(a), np.sin(a)])
    vertices = np.vstack([np.column_stack([ring, np.full(n, bottom)]),
                          np.column_stack([ring, np.full(n, top)]),
                          [[0.0, 0.0, bottom], [0.0, 0.0, top]]])
    faces = []
    for j in range(n):
        k = (j + 1) % n
        faces += [(j, k, n + k), (j, n + k, n + j), (2 * n, k, j), (2 * n + 1, n + j, n + k)]
    faces = np.array(faces)
    return (vertices, faces) if mesh_volume(vertices, faces) > 0 else (vertices, faces[:, ::-1])


def _stacked(wide, narrow):
    """A narrow cylinder standing on a wide one (their shared face's disc left out of both):
    one closed surface, the wide top an annulus joined to the narrow bottom's ring."""
    (wv, wf), (nv, nf) = wide, narrow
    n = (len(wv) - 2) // 2
    top_centre, bottom_centre = 2 * n + 1, 2 * n
    wf = wf[~np.isin(wf, [top_centre]).any(axis=1)]  # the wide top's fan, replaced below
    nf = nf[~np.isin(nf, [bottom_centre]).any(axis=1)] + len(wv)
    annulus = []
    for j in range(n):
        k = (j + 1) % n
        a, b = n + j, n + k  # the wide top ring
        c, d = len(wv) + j, len(wv) + k  # the narrow bottom ring
        annulus += [(a, b, d), (a, d, c)]
    faces = np.vstack([wf, nf, annulus])
    vertices = np.vstack([wv, nv])
    return (vertices, faces) if mesh_volume(vertices, faces) > 0 else (vertices, faces[:, ::-1])


def _pipe(outer: float, inner: float, height: float, n: int = 48):
    """A hollow vertical cylinder: an annulus extruded along z."""
    a = np.linspace(0, 2 * math.pi, n, endpoint=False)
    ring = np.column_stack([np.cos(a), np.sin(a)])
    rows = [np.column_stack([r * ring, np.full(n, z)]) for r, z in
            ((outer, -height / 2), (outer, height / 2), (inner, height / 2),
             (inner, -height / 2))]
    vertices, faces = np.vstack(rows), []
    for row in range(4):  # the four walls of the annulus's section swept round
        for j in range(n):
            k = (j + 1) % n
            a0, a1 = row * n + j, row * n + k
            b0, b1 = ((row + 1) % 4) * n + j, ((row + 1) % 4) * n + k
            faces += [(a0, a1, b1), (a0, b1, b0)]
    faces = np.array(faces)
    return (vertices, faces) if mesh_volume(vertices, faces) > 0 else (vertices, faces[:, ::-1])


def test_the_tolerance_admits_a_polygon_of_24_sides():
    """REVOLUTION_TOLERANCE's reason: a regular polygon of N sides lies between its apothem and
    its circumradius, from 0.57 % (24) to 1.3 % (16) of its equal-area circle's radius."""
    def spread(n):
        equal_area = math.sqrt(n * math.sin(2 * math.pi / n) / (2 * math.pi))
        return max(1 - equal_area, equal_area - math.cos(math.pi / n))
    assert spread(24) < REVOLUTION_TOLERANCE < spread(16)


def test_a_run_in_a_wedge_of_triangles_is_not_the_3d_run_of_the_same_file(tmp_path):
    """The run's digest takes the wedge of a body given by triangles in, so that a 3D run of the
    same case file is another run; a shape's wedge and a heeled release (3D) have none."""
    from floatfoam.plan.stamps import _resolved_motion

    (tmp_path / "case.toml").write_text(SPHERE)
    assert _resolved_motion(load_case(str(tmp_path)), None) == ["layered", "wedge"]
    assert _resolved_motion(load_case("sphere"), None) == ["layered"]
    heeled = with_overrides(load_case(str(tmp_path)), ["release.heel=2.0"])
    assert "wedge" not in _resolved_motion(heeled, None)


@pytest.mark.parametrize("axis", [(0.0, 0.0), (0.7, 0.4)])
def test_a_body_of_revolution_drawn_off_its_files_axis_heaves_in_a_wedge(tmp_path, axis):
    """A sphere's STL in rings of 25 sides (its bounding box off its axis by 0.4 mm, the odd
    side's) on its file's z axis and with that axis at (0.7, 0.4) m, G given on it: the body
    frame's origin is on the volume's centroid (floatfoam.bodies.surfaces.centred), which lies
    on the axis whatever the facets' parity, so either file is a body of revolution about z
    and heaves in a wedge; the one on its axis is not moved."""
    from floatfoam.gmshio import write_stl
    from floatfoam.plan.kind import default_kind
    from floatfoam.tank import pose

    vertices, faces = rings_sphere(0.1, 24, 25)
    write_stl(tmp_path / "ball.stl", vertices + [*axis, 0.0], faces)
    (tmp_path / "case.toml").write_text(
        '[body]\nshape = "stl"\npath = "ball.stl"\n[mass]\ndensity = 500.0\n'
        f'cog = [{axis[0]}, {axis[1]}, -0.03]\ngyradius = [0.06, 0.06, 0.06]\n'
        '[release]\nheave = 0.01\n')
    case = load_case(str(tmp_path))
    assert (case.body.file_origin is None) == (axis == (0.0, 0.0))
    assert case.body.is_axisymmetric
    assert case.cog[:2].tolist() == [0.0, 0.0]
    assert default_kind(case, pose(case, "release", equilibrium(case))) == "wedge"
