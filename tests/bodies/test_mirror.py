"""A body given by triangles meshed in half the tank: its mirror symmetry found from its
triangles (or its implicit expression), its half cut along the plane, and the normals of its
half's prism layers (floatfoam.bodies.mirror, floatfoam.plan.kind.half_plane)."""

import math

import numpy as np
import pytest

from floatfoam.bodies.geometry import extrude_polygon, icosphere, mesh_volume, open_edges
from floatfoam.bodies.mirror import clip_half, corner_normals, mirror_planes
from floatfoam.case import load_case, with_overrides
from floatfoam.hydrostatics.theory import equilibrium
from floatfoam.layout import CASES_DIR
from floatfoam.plan.kind import half_plane
from floatfoam.tank import pose


def octagon_prism():
    """The pontoon's shape: a flattened octagon (0.5 × 0.24 m) extruded 1.2 m along x."""
    w, h, c = 0.25, 0.12, 0.06
    section = np.array([[-w + c, -h], [w - c, -h], [w, -h + c], [w, h - c], [w - c, h],
                        [-w + c, h], [-w, h - c], [-w, -h + c]])
    return extrude_polygon(section, 1.2)


def box_with_an_off_centre_vertex():
    """A 2 × 1 × 1 box whose top face is a fan about a vertex at x = 0.3: its triangles are not
    mirrored about x = 0, its surface is."""
    v = np.array([[-1, -0.5, -0.5], [1, -0.5, -0.5], [1, 0.5, -0.5], [-1, 0.5, -0.5],
                  [-1, -0.5, 0.5], [1, -0.5, 0.5], [1, 0.5, 0.5], [-1, 0.5, 0.5],
                  [0.3, 0.0, 0.5]], dtype=float)
    f = np.array([[0, 2, 1], [0, 3, 2],  # bottom (outward: −z)
                  [4, 5, 8], [5, 6, 8], [6, 7, 8], [7, 4, 8],  # top fan
                  [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5],
                  [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    return v, f


def test_the_planes_a_body_is_symmetric_about_are_found_from_its_surface():
    v, f = octagon_prism()
    assert mesh_volume(v, f) > 0
    assert mirror_planes(v, f) == ("x", "y")
    # the same surface with triangles that do not mirror: each mirrored vertex on a face
    v, f = box_with_an_off_centre_vertex()
    assert mesh_volume(v, f) == pytest.approx(2.0)
    assert mirror_planes(v, f) == ("x", "y")
    # the top face's vertex raised 10 mm: its mirror image is 4.6 mm off the fan there (4.6
    # times the tolerance, 1e-3 of the box's smallest extent): no longer symmetric about
    # x = 0; still about y = 0
    v[8, 2] += 0.01
    assert mirror_planes(v, f) == ("y",)
    # a sphere shifted along x by a thousandth of its radius more than the tolerance
    sv, sf = icosphere(3)
    assert mirror_planes(sv, sf) == ("x", "y")
    assert mirror_planes(sv + [0.0025, 0.0, 0.0], sf) == ("y",)
    # the sphere's triangles turned 17° about z: no vertex mirrors onto another, each lies on
    # the facets within their sagitta (h²/8R: 0.07 % of the radius at icosphere(4), under the
    # tolerance's 0.2 %: 1e-3 of the diameter); one vertex pushed out 5 % breaks both planes
    c, s = np.cos(0.3), np.sin(0.3)
    turned = icosphere(4)[0] @ np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]).T
    faces = icosphere(4)[1]
    assert mirror_planes(turned, faces) == ("x", "y")
    bumped = turned.copy()
    k = int(np.argmax(bumped[:, 0] + 0.5 * bumped[:, 1]))
    bumped[k] *= 1.05
    assert mirror_planes(bumped, faces) == ()


def test_an_implicit_body_is_symmetric_where_its_expression_is():
    sv, sf = icosphere(2)
    assert mirror_planes(sv, sf, "x**2 + y**2 + z**2 - 1") == ("x", "y")
    # an egg along x: symmetric about y = 0 only (its points are the sphere's, off its
    # surface: the expression's values at a point and at its mirror image decide)
    assert mirror_planes(sv, sf, "x**2 + y**2 + z**2 + 0.3*x**3 - 1") == ("y",)


@pytest.mark.parametrize("axis", [0, 1])
def test_the_half_of_a_closed_surface_closes_by_its_mirror_image(axis):
    for v, f in (octagon_prism(), box_with_an_off_centre_vertex(), icosphere(3)):
        half_v, half_f = clip_half(v, f, axis)
        assert (half_v[:, axis] >= 0.0).all()
        mirror = half_v * np.where(np.arange(3) == axis, -1.0, 1.0)
        whole_v = np.vstack([half_v, mirror])
        whole_f = np.vstack([half_f, half_f[:, ::-1] + len(half_v)])
        # the two halves enclose the body's volume to round-off: the cut is exact and keeps
        # the faces' orientation
        assert mesh_volume(whole_v, whole_f) == pytest.approx(mesh_volume(v, f), rel=1e-12)
        # the only open edges are the cut's, in the plane
        edges = np.sort(np.concatenate([half_f[:, [0, 1]], half_f[:, [1, 2]],
                                        half_f[:, [2, 0]]]), axis=1)
        unique, count = np.unique(edges, axis=0, return_counts=True)
        rim = unique[count == 1]
        assert len(rim) == open_edges(half_f) > 0
        assert (half_v[rim][..., axis] == 0.0).all()


def test_the_half_s_layer_normals_keep_sharp_edges_and_lie_in_the_plane_at_the_cut():
    v, f = clip_half(*icosphere(3), 0)
    n = corner_normals(v, f, math.radians(20.0), plane=0)
    assert np.allclose(np.linalg.norm(n, axis=2), 1.0)
    at_cut = v[f][..., 0] == 0.0
    assert at_cut.any() and (n[..., 0][at_cut] == 0.0).all()
    # away from the cut, a sphere's mean normals point along the radius within the facets'
    # turning (icosphere(3): ~8° between neighbouring facets)
    radial = v[f] / np.linalg.norm(v[f], axis=2)[..., None]
    assert np.degrees(np.arccos(np.clip((n * radial).sum(axis=2), -1, 1)))[~at_cut].max() < 4
    # the octagonal prism's flat faces keep their own normal up to their sharp edges
    v, f = clip_half(*octagon_prism(), 0)
    n = corner_normals(v, f, math.radians(20.0), plane=0)
    corners = v[f]
    face = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    face /= np.linalg.norm(face, axis=1)[:, None]
    assert np.allclose(n, face[:, None, :], atol=1e-12)


def test_the_pontoon_is_meshed_in_half_the_tank_unless_the_case_says_otherwise():
    case = load_case(str(CASES_DIR / "stl_pontoon"))
    where = pose(case, "release", equilibrium(case))
    assert case.body.mirror_planes == ("x", "y")
    assert half_plane(case, where) == "x"  # heeled: roll about x keeps x = 0
    assert half_plane(with_overrides(case, ["mesh.gmsh.half_3d=false"]), where) is None
    off = with_overrides(case, ["mass.cog=[0.01, 0.0, -0.03]"])  # G off the plane
    assert half_plane(off, pose(off, "release", equilibrium(off))) is None
