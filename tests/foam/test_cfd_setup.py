"""The set-up of a CFD run, without the solver: the mesh each case gets, the six-DoF
constraints a release excites, the angles of the motion series, defaults and refusals, and
cases that extend one another. (The runs themselves: tests/cfd/test_cfd_bodies.py.)"""

import math
import shutil

import numpy as np
import pytest
from foamlib import FoamFile

from floatfoam.bodies.geometry import rotation
from floatfoam.case import load_case
from floatfoam.errors import InputError
from floatfoam.foam import domain, render
from floatfoam.foam.logwatch import Step
from floatfoam.foam.runner import Limits, Stall
from floatfoam.hydrostatics.theory import equilibrium
from floatfoam.plan import release
from floatfoam.settings import MOTION_DIFFUSIVITIES


def planned(name, overrides=()):
    case = load_case(name, list(overrides))
    state = release.release_state(case, equilibrium(case))
    return case, state, domain.plan(case, "coarse", state["pose"])


@pytest.mark.parametrize("name, overrides, expected", [
    ("elliptic_cylinder", [], (3.0, 0.5, 0.01)),  # a 2D section's (time-step-limits.md)
    ("ellipsoid_roll", [], (1.0, 0.5, 0.01)),  # a 3D tank's bulk limit
    ("sphere", [], (1.0, 0.5, 0.01)),  # a wedge's
    ("elliptic_cylinder", ["run.max_courant=0.3"], (0.3, 0.3, 0.01)),  # below the interface's
    ("ellipsoid_roll", ["run.max_courant=2"], (2.0, 0.5, 0.01)),  # set, in 3D
    ("elliptic_cylinder", ["run.max_delta_t=0.004"], (3.0, 0.5, 0.004)),
])
def test_the_step_limits_reach_the_control_dictionary(tmp_path, name, overrides, expected):
    """controlDict's maxCo, maxAlphaCo and maxDeltaT from [run] at the coarse level: Courant 3
    in the bulk of a 2D section's mesh and 1 on a wedge and in a 3D tank, 0.5 at the interface
    and 10 ms by default; the bulk's limit, when smaller, is the interface's too."""
    from floatfoam.layout import COMMON_DIR

    case, _, mesh = planned(name, overrides)
    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    render._control(case, tmp_path, mesh, 1.0)
    control = FoamFile(tmp_path / "system" / "controlDict")
    limits = (control["maxCo"], control["maxAlphaCo"], control["maxDeltaT"])
    assert limits == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("name, kind, share", [
    ("cylinder_heave", "ogrid", 0.01),  # the O-grid slab is 10 mm of the 1 m section
    ("elliptic_cylinder", "2d", 1.0),
    ("sphere", "wedge", 5.0 / 360.0),
    ("ellipsoid_roll", "3d-half", 0.5),
    ("stl_pontoon", "3d-half", 0.5),  # symmetric about x = 0 (its triangles), heeled about x
])
def test_each_body_gets_its_mesh(name, kind, share):
    _, _, mesh = planned(name)
    assert mesh.kind == kind and mesh.share == pytest.approx(share)
    assert set(mesh.patches) >= {"body", "bottom", "sides", "atmosphere"}


def test_half_domain_follows_the_release():
    """A heel keeps x = 0 (the tank is cut there, its length halved); a trim keeps y = 0."""
    _, _, heel = planned("ellipsoid_roll")
    _, _, trim = planned("ellipsoid_roll", ["release.heel=0", "release.trim=5"])
    assert heel.kind == trim.kind == "3d-half"
    assert heel.extents[0] == pytest.approx(2.0) and heel.extents[1] == pytest.approx(4.0)
    assert trim.extents[0] == pytest.approx(4.0) and trim.extents[1] == pytest.approx(2.0)
    _, _, both = planned("ellipsoid_roll", ["release.trim=5"])
    assert both.kind == "3d"  # heel and trim: no plane is kept


@pytest.mark.parametrize("release, expected", [
    ({"heave": 0.01}, {"line": [0.0, 0.0, 1.0], "orientation": None}),
    ({"heel": 10.0}, {"plane": [1.0, 0.0, 0.0], "axis": [1.0, 0.0, 0.0]}),
    ({"trim": 5.0}, {"plane": [0.0, 1.0, 0.0], "axis": [0.0, 1.0, 0.0]}),
    ({"heel": 10.0, "trim": 5.0}, {}),
])
def test_constraints_follow_the_release(release, expected):
    overrides = [f"release.{k}={v}" for k, v in {"heave": 0.0, "heel": 0.0, "trim": 0.0,
                                                 **release}.items()]
    case, state, mesh = planned("ellipsoid_roll", overrides)
    found = {}
    for entry in render.constraints(case, mesh, [0.0, 0.0, 0.0]).values():
        kind = entry["sixDoFRigidBodyMotionConstraint"]
        found[kind] = entry.get("direction") or entry.get("normal") or entry.get("axis")
    assert found == expected


def test_a_wedge_moves_in_heave_alone():
    case, state, mesh = planned("sphere", ["release.heave=0.05"])
    kinds = {e["sixDoFRigidBodyMotionConstraint"]
             for e in render.constraints(case, mesh, [0.0, 0.0, 0.0]).values()}
    assert kinds == {"line", "orientation"}


def test_morphing_past_the_clamped_bottom_is_named():
    """The 0.5 D drop of the laboratory sphere starts with its lowest point at the still water,
    0.9 m above the basin's bottom (Kramer et al. 2021: depth 0.900 m): a morphing zone out to
    1.2 m reaches past the bottom (its medium level's bottom cell collapsed), 0.9 m does not."""
    def warning(name, overrides=(), distances=True):
        zone = ['run.mesh_motion="distances"', "run.inner_distance=0.2",
                "run.outer_distance=0.9"] if distances else []
        case, state, mesh = planned(name, [*zone, *overrides])
        return domain.clamped_bottom(mesh, case, state["pose"])

    text = warning("lab_sphere_05D", ["run.outer_distance=1.2"])
    assert "run.outer_distance = 1.2 m reaches past the tank's bottom, 0.9 m below" in text
    assert text.endswith("(an outer distance of at most 0.9 m keeps the bottom out of the zone)")
    assert warning("lab_sphere_05D") is None
    # drop 3's release, 0.26 mm lower: 0.2 mm past the bottom, 0.02 % of the band, lets pass
    assert warning("lab_sphere_05D", ["release.heave=0.1498"]) is None
    assert warning("lab_sphere_05D", ["run.outer_distance=0.92"]) is not None
    assert warning("sphere", ["run.outer_distance=0.32"]) is None  # 1.9 m of water below
    assert warning("lab_sphere_05D", distances=False) is None  # the Laplacian has no zone


def test_the_morphing_zone_reaches_as_far_as_the_tank_allows():
    """The six-DoF distances' defaults (floatfoam.plan.zone.distances): rigid within half
    the body's smallest dimension, fixed beyond 0.9 × the room between the body at its release
    and the nearest held wall: for the capsizing ellipse (half beam 0.1 m, half height 0.15 m,
    released at 2°) the default tank's 0.9 m of air above the still water. A body that turns
    over must have room for the circle it sweeps about G (radius 0.17 m, its top from G)."""
    case, state, mesh = planned("elliptic_cylinder_capsize")
    heel = math.radians(2.0)
    top = state["pose"].z_c + math.hypot(0.1 * math.sin(heel), 0.15 * math.cos(heel))
    assert mesh.inner == pytest.approx(0.1)
    assert mesh.outer == pytest.approx(0.9 * (0.9 - top), rel=1e-3)  # the surface mesh's
    assert domain.clamped_bottom(mesh, case, state["pose"]) is None
    # the ends 0.16 m from the middle: the section fits, the 0.17 m circle it sweeps does not
    with pytest.raises(InputError, match=r"body turning over reaches 0.01\d* m past its nearest "
                                         r"held wall; valid is a larger tank \(\[domain\]"):
        planned("elliptic_cylinder_capsize", ["domain.half_length=0.16"])
    # stable (G lowered): no circle; the section itself reaches 0.06 m from the ends
    case, state, mesh = planned("elliptic_cylinder_capsize",
                                ["mass.cog=[0,0,-0.06]", "domain.half_length=0.16"])
    assert mesh.outer == pytest.approx(0.9 * 0.06, rel=2e-2)


def test_release_about_the_equilibrium_attitude():
    """The body starts heeled by the release from its equilibrium attitude; the solver's
    orientation is that attitude, and the motion series' angles are measured from the
    equilibrium (box_bilge with G 10 mm off the centre line floats heeled)."""
    case = load_case("box_bilge", ["mass.cog=[0.0, 0.01, 0.0]"])
    eq = equilibrium(case)
    assert abs(math.degrees(eq.heel)) > 1.0
    state = release.release_state(case, eq)
    assert state["pose"].heel == pytest.approx(eq.heel + math.radians(10.0))
    assert np.allclose(state["orientation"], rotation(state["pose"].heel, 0.0))
    step = Step(time=0.0, centre_of_mass=np.zeros(3), orientation=state["orientation"])
    assert step.motion_row(state["equilibrium_orientation"])[4] == pytest.approx(10.0)
    assert step.motion_row()[4] == pytest.approx(math.degrees(state["pose"].heel))


def six_dof(name, run_dir, overrides=()):
    """The case, its release state and mesh plan, and the six-DoF coefficients the render
    writes for them into ``run_dir``."""
    from foamlib import FoamFile

    case, state, mesh = planned(name, overrides)
    body = render._motion(case, run_dir, mesh, state)  # the Laplacian's body condition
    coeffs = body if body is not None else \
        FoamFile(run_dir / "constant" / "dynamicMeshDict")["sixDoFRigidBodyMotionCoeffs"]
    return case, state, mesh, coeffs


@pytest.mark.parametrize("name, overrides, motion", [
    ("sphere", (), "layered"),  # heave alone, in a wedge
    ("cylinder_heave", (), "layered"),  # heave alone, on the O-grid
    ("box_bilge_heave", (), "layered"),  # heave alone, on a 2D section
    ("sphere", ("mesh.gmsh.wedge=false",), "laplacian"),  # heave alone in 3D: a zone 1.7 ×
    ("sphere", ("mesh.gmsh.wedge=false", "domain.air_height=1.0"), "laplacian"),  # 4.0 ×
    ("sphere", ("mesh.gmsh.wedge=false", 'run.mesh_motion="layered"'), "layered"),  # asked
    ("sphere", ('run.mesh_motion="laplacian"',), "laplacian"),  # asked
    ("cylinder_heave", ("run.layer_band=1.5",), "layered"),
    ("box_bilge", (), "laplacian"),  # heeled 10°: sway, heave and roll on a 2D section
    ("elliptic_cylinder_capsize", (), "distances"),  # released to turn over
    ("ellipsoid", (), "laplacian"),  # 3D: a zone 2.65 × the body's smallest dimension
    ("ellipsoid_roll", (), "laplacian"),  # 3D: a zone 1.29 × it
    ("superellipsoid_buoy", (), "laplacian"),  # 3D, the whole tank: 0.45 ×
    ("lab_sphere", ('run.mesh_pose="equilibrium"',), "distances"),  # moved by the six-DoF scale
    ("elliptic_cylinder_capsize", ('run.mesh_motion="laplacian"',), "laplacian"),  # asked
    ("cylinder_heave", ('run.mesh_motion="laplacian"', 'run.motion_diffusivity="linear"'),
     "laplacian"),  # 1/d
    ("elliptic_cylinder_capsize", ('run.motion_diffusivity="linear"',), "distances"),  # ignored
    ("cylinder_heave", ("run.inner_distance=0.045", "run.outer_distance=0.24"), "distances"),
    ("ellipsoid_roll", ("run.outer_distance=0.5",), "distances"),  # a distance set is used
])
def test_the_mesh_motion_by_default_and_on_request(tmp_path, name, overrides, motion):
    """run.mesh_motion "auto": the six-DoF solver's distances where the case sets a distance,
    for a release that turns the body over and a mesh made at equilibrium, else the layered
    motion for a body free in heave alone in 2D or a wedge, else the Laplacian, in 2D, a
    wedge and a 3D tank of any size (a zone for the distances of 0.45 to 4 × the body's
    smallest dimension). The layered
    motion's dictionary: floatfoam's solver on the six-DoF coefficients with run.layer_band,
    the tank's ends free to slide. The Laplacian's
    dictionaries: the displacement's diffusivity quadratic in the inverse distance from the
    body (linear with run.motion_diffusivity "linear"), the body's condition holding the six-DoF
    equations; no sixDoFRigidBodyState function object on either route."""
    from foamlib import FoamFile

    from floatfoam.layout import COMMON_DIR

    case, state, mesh = planned(name, overrides)
    assert mesh.motion == motion
    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    render._control(case, tmp_path, mesh, 1.0)
    body = render._motion(case, tmp_path, mesh, state)
    text = (tmp_path / "constant" / "dynamicMeshDict").read_text()
    functions = FoamFile(tmp_path / "system" / "controlDict")["functions"]
    if motion == "laplacian":
        diffusivity = {"quadratic": "diffusivity quadratic inverseDistance (body);",
                       "linear": "diffusivity inverseDistance (body);"}
        assert set(diffusivity) == set(MOTION_DIFFUSIVITIES)
        assert "displacementLaplacian" in text
        assert diffusivity[case.settings.run.motion_diffusivity] in \
            [line.strip() for line in text.splitlines()]
        assert body["type"] == "bodySixDoFRigidBodyDisplacement" and "innerDistance" not in body
        assert body["mass"] == pytest.approx(case.mass * mesh.share)
    else:
        assert body is None and "sixDoFRigidBodyMotionCoeffs" in text
        coeffs = FoamFile(tmp_path / "constant" / "dynamicMeshDict")
        layered = coeffs["motionSolver"] == "layeredSixDoFRigidBodyMotion"
        assert layered == (motion == "layered")
        if layered:
            assert coeffs["sixDoFRigidBodyMotionCoeffs"]["layerBandExpansion"] == \
                case.settings.run.layer_band
    assert "motion" not in functions  # one source of the motion: the log (foam.motionlog)


@pytest.mark.parametrize("solver, velocity, displacement", [
    (None, "bodyVelocity", "bodySixDoFRigidBodyDisplacement"),  # floatfoam's (make setup)
    ("/usr/bin/interFoam", "movingWallVelocity", "sixDoFRigidBodyDisplacement"),  # Debian's
])
def test_the_body_conditions_follow_the_solver(tmp_path, solver, velocity, displacement):
    """The body's velocity is floatfoam's bodyVelocity (the rigid body's at the step's end)
    and the Laplacian's body condition the copy of v1912's that lets it read the motion, where
    the interFoam to run has them; on another interFoam (run.solver) v1912's own."""
    from floatfoam.foam.patches import boundary_conditions
    from floatfoam.layout import COMMON_DIR
    from floatfoam.plan.stamps import has_body_velocity

    chosen = (f'run.solver="{solver}"',) if solver else ()
    case, state, mesh = planned("cylinder_heave", ('run.mesh_motion="laplacian"', *chosen))
    own = has_body_velocity(case)
    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    render._control(case, tmp_path, mesh, 1.0)
    assert render._motion(case, tmp_path, mesh, state, own)["type"] == displacement
    assert boundary_conditions("U", mesh.patches, own)["body"]["type"] == velocity


@pytest.mark.parametrize("name, free", [
    ("cylinder_heave", ["heave"]),
    ("flume_section_roll", ["heave", "roll", "sway"]),  # heeled: sway and roll with heave
])
def test_the_coupling_is_compensated_by_half_the_added_mass(tmp_path, name, free):
    """The six-DoF restraint addedMassCompensation (src/solver/) takes half the body's added
    mass at infinite frequency (Newmark passes half of a change of the acceleration on to the
    body's faces' velocity at the step's end), × the domain's share of the body, in the DoFs
    it is free in and no other, on either mesh motion; a body held still takes none."""
    from floatfoam.layout import COMMON_DIR
    from floatfoam.plan.zone import free_names
    from floatfoam.potential.coupling import infinite_frequency_added_mass

    case, state, mesh = planned(name)
    assert free_names(case, mesh.kind) == free
    eq = equilibrium(case)
    compensation = render._compensation(case, eq, mesh)
    matrix = np.block([[np.reshape(compensation[a], (3, 3)), np.reshape(compensation[b], (3, 3))]
                       for a, b in (("linear", "linearAngular"), ("angularLinear", "angular"))])
    axes = [{"surge": 0, "sway": 1, "heave": 2, "roll": 3, "pitch": 4}[n] for n in free]
    a_inf = infinite_frequency_added_mass(case, eq, free)
    assert matrix[np.ix_(axes, axes)] == pytest.approx(0.5 * mesh.share * a_inf, rel=1e-12)
    held = [i for i in range(6) if i not in axes]
    assert not matrix[held].any() and not matrix[:, held].any()
    assert matrix[2, 2] > 0.0
    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    render._control(case, tmp_path, mesh, 1.0)
    body = render._motion(case, tmp_path, mesh, state, True, compensation)
    coeffs = body if body is not None else \
        FoamFile(tmp_path / "constant" / "dynamicMeshDict")["sixDoFRigidBodyMotionCoeffs"]
    restraint = coeffs["restraints"]["addedMass"]
    assert restraint["sixDoFRigidBodyMotionRestraint"] == "addedMassCompensation"
    assert np.ravel(restraint["linear"]) == pytest.approx(compensation["linear"])
    held_still = load_case(name, ["run.static_body=true"])
    assert render._compensation(held_still, eq, mesh) is None


def test_the_layered_motion_is_refused_for_a_body_that_turns():
    """The layered motion moves whole rows with the body: a body free to roll (box_bilge,
    heeled) would turn rows across the tank, so it is refused in one line naming the setting
    and the DoFs."""
    with pytest.raises(InputError) as err:
        planned("box_bilge", ['run.mesh_motion="layered"'])
    message = str(err.value)
    assert "\n" not in message
    assert all(w in message for w in ("run.mesh_motion", "roll", "heave alone")), message


@pytest.mark.parametrize("name", ["ellipsoid_pitch", "superellipsoid_buoy"])
def test_a_trimmed_body_gets_its_own_centre_of_mass(tmp_path, name):
    """The six-DoF centre of mass of a body trimmed at release is G where the trimmed body
    puts it, off x = 0 by −z_G·sin θ from the body's axis (2.6 mm for the ellipsoid, 2.1 mm for
    the buoy): its righting arm at release is then the theory's GM_pitch·sin θ. Written at
    x = 0, G would take 21 % off the ellipsoid's arm and make it oscillate about a trim of
    1.05° in CFD."""
    from floatfoam.hydrostatics.immersion import mesh_immersed
    from floatfoam.hydrostatics.theory import theory_summary
    from floatfoam.meshing import body_surface
    from floatfoam.meshing.levels import mesh_spec

    case, state, _, coeffs = six_dof(name, tmp_path)
    cog = np.asarray(coeffs["centreOfMass"], dtype=float)
    assert np.allclose(cog, state["cog"], atol=1e-12)
    trim = math.radians(case.release["trim"])
    assert abs(cog[0]) > 0.9 * abs(case.cog[2]) * math.sin(trim)  # cos(heel) ≥ 0.99 here
    if name == "ellipsoid_pitch":  # the closed-form body: its arm against GM_pitch·sin θ
        pose = state["pose"]
        vertices, faces = body_surface.body_triangles(case.body, mesh_spec(case, "fine"))
        buoyancy = mesh_immersed(vertices, faces, pose.z_c, pose.heel, pose.trim).centroid
        arm = theory_summary(case).dofs["pitch"].metacentric_height * math.sin(trim)
        # measured 12.27 mm against 12.42 mm (−1.2 %: the arm at 5°, of the fine level's
        # triangles, against the linear theory's); with G at x = 0 it is 9.66 mm
        assert abs(buoyancy[0] - cog[0]) == pytest.approx(arm, rel=0.02)


@pytest.mark.parametrize("name", ["elliptic_cylinder_roll", "cylinder_heave"])
def test_a_section_centre_of_mass_is_mid_slab(tmp_path, name):
    """A 2D slab one cell thick holds G in its middle (the gmsh slab is centred on x = 0, the
    O-grid's starts there), whatever G's x along the section."""
    _, _, mesh, coeffs = six_dof(name, tmp_path, ["mass.cog=[0.05, 0.0, 0.0]"])
    assert coeffs["centreOfMass"][0] == pytest.approx(mesh.x_mid, abs=1e-12)


def rendered_solvers(tmp_path, name):
    """fvSolution's solvers as render._solution leaves them for case ``name`` (the shared
    system folder copied into ``tmp_path``)."""
    from foamlib import FoamFile

    from floatfoam.layout import COMMON_DIR

    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    case, _, mesh = planned(name)
    render._solution(case, tmp_path, mesh)
    return FoamFile(tmp_path / "system" / "fvSolution")["solvers"]


@pytest.mark.parametrize("name, solver", [("elliptic_cylinder", "GAMG"),
                                          ("superellipsoid_buoy", "GAMG"),  # heeled and trimmed
                                          ("cylinder_heave", "GAMG"), ("sphere", "PCG"),
                                          ("ellipsoid_roll", "GAMG"), ("stl_pontoon", "GAMG")])
def test_pcorr_solver_follows_the_mesh(tmp_path, name, solver):
    """pcorr by GAMG on every mesh but the wedge's, where it measured no slower, by the shared
    PCG on the wedge (render.PCORR_BY_GAMG); the same tolerance either way."""
    pcorr = rendered_solvers(tmp_path, name)['"pcorr.*"']
    assert pcorr["solver"] == solver and pcorr["tolerance"] == 1e-3 and pcorr["relTol"] == 0


@pytest.mark.parametrize("name, correctors", [("elliptic_cylinder", 1), ("cylinder_heave", 1),
                                              ("sphere", 2), ("ellipsoid_roll", 2),
                                              ("superellipsoid_buoy", 2)])
def test_alpha_correctors_follow_the_mesh(tmp_path, name, correctors):
    """One MULES corrector on the 2D sections, the shared fvSolution's two on the wedges and
    in 3D (render.ALPHA_ONE_CORRECTOR)."""
    alpha = rendered_solvers(tmp_path, name)['"alpha.water.*"']
    assert alpha["nAlphaCorr"] == correctors and alpha["nLimiterIter"] == 5


def test_laplacian_takes_the_distance_from_the_body_once():
    """The Laplacian's diffusivity (inverseDistance, v1912's wallDist under the name "patch")
    reads fvSchemes' patchDist: updateInterval 0 takes the distance when the solver starts and
    never again (wallDist::movePoints), not after each of a step's mesh motions."""
    from foamlib import FoamFile

    from floatfoam.layout import COMMON_DIR

    schemes = FoamFile(COMMON_DIR / "system" / "fvSchemes")
    assert schemes["patchDist"]["method"] == "meshWave"
    assert schemes["patchDist"]["updateInterval"] == 0


@pytest.mark.parametrize("overrides, outer", [([], 3), (["run.outer_correctors=2"], 2),
                                              (["run.static_body=true"], 1)])
def test_outer_correctors_reach_fvsolution(tmp_path, overrides, outer):
    """run.outer_correctors is PIMPLE's nOuterCorrectors (a static body needs one)."""
    import shutil

    from foamlib import FoamFile

    from floatfoam.layout import COMMON_DIR

    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    case, _, mesh = planned("box_bilge", overrides)
    render._control(case, tmp_path, mesh, 1.0)
    assert FoamFile(tmp_path / "system" / "fvSolution")["PIMPLE"]["nOuterCorrectors"] == outer


@pytest.mark.parametrize("name, overrides, tolerance", [
    ("box_bilge", [], 0.0),  # a 2D section's (release.COUPLING_TOLERANCE)
    ("sphere", [], 0.0),  # a wedge's
    ("stl_pontoon", [], 0.01),  # a 3D tank's
    ("box_bilge", ["run.coupling_tolerance=0.05"], 0.05),
    ("stl_pontoon", ["run.coupling_tolerance=0"], 0.0),  # set, in 3D
    ("stl_pontoon", ["run.static_body=true"], 0.0),
])
def test_coupling_tolerance_reaches_fvsolution(tmp_path, name, overrides, tolerance):
    """run.coupling_tolerance is PIMPLE's couplingTolerance (src/solver/couplingConvergence.H):
    by default 0 on a section's and a wedge's mesh, 0.01 in a 3D tank; 0 for a static body."""
    import shutil

    from foamlib import FoamFile

    from floatfoam.layout import COMMON_DIR

    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    case, _, mesh = planned(name, overrides)
    render._control(case, tmp_path, mesh, 1.0)
    pimple = FoamFile(tmp_path / "system" / "fvSolution")["PIMPLE"]
    assert pimple["couplingTolerance"] == pytest.approx(tolerance, abs=0)


def test_interface_gravity_smoothing_reaches_fvsolution(tmp_path):
    """run.interface_gravity_smoothing is PIMPLE's interfaceGravitySmoothing
    (src/solver/interfaceGravity.H), 0 by default; set without run.interface_gravity it is
    refused in one line naming both."""
    import shutil

    from foamlib import FoamFile

    from floatfoam.layout import COMMON_DIR

    for overrides, passes in (([], 0), (["run.interface_gravity=true",
                                        "run.interface_gravity_smoothing=2"], 2)):
        shutil.copytree(COMMON_DIR / "system", tmp_path / "system", dirs_exist_ok=True)
        case, _, mesh = planned("stl_pontoon", overrides)
        render._control(case, tmp_path, mesh, 1.0)
        pimple = FoamFile(tmp_path / "system" / "fvSolution")["PIMPLE"]
        assert pimple["interfaceGravitySmoothing"] == passes
    with pytest.raises(InputError, match=r"^run.interface_gravity_smoothing = 2: valid with "
                                         r"run.interface_gravity = true, or 0$"):
        load_case("stl_pontoon", ["run.interface_gravity_smoothing=2"])
    with pytest.raises(InputError, match="run.interface_gravity_smoothing"):
        load_case("stl_pontoon", ["run.interface_gravity=true",
                                  "run.interface_gravity_smoothing=-1"])


@pytest.mark.parametrize("name, key, scheme, entry, written", [
    ("box_bilge", "time_scheme", None, "default", "Euler"),
    ("box_bilge", "time_scheme", "Euler", "default", "Euler"),
    ("box_bilge", "time_scheme", "CrankNicolson 0.9", "default", ("CrankNicolson", 0.9)),
    ("box_bilge", "time_scheme", "CrankNicolson 1", "default", ("CrankNicolson", 1.0)),
    # "auto": Crank–Nicolson 0.9 for a body free in heave alone, Euler for one free to turn
    ("lab_sphere", "interface_time_scheme", None, "ddt(alpha)", ("CrankNicolson", 0.9)),
    ("box_bilge", "interface_time_scheme", None, "ddt(alpha)", "Euler"),
    ("lab_sphere", "interface_time_scheme", "Euler", "ddt(alpha)", "Euler"),
    ("box_bilge", "interface_time_scheme", "CrankNicolson 1", "ddt(alpha)",
     ("CrankNicolson", 1.0))])
def test_time_schemes_reach_fvschemes(tmp_path, name, key, scheme, entry, written):
    """run.time_scheme sets ddtSchemes' default (without it the shared Euler stays),
    run.interface_time_scheme its ddt(alpha), by default Crank–Nicolson 0.9 for a body free in
    heave alone and Euler for one free to turn; the file as interFoam reads it."""
    import shutil

    from foamlib import FoamFile

    from floatfoam.layout import COMMON_DIR

    shutil.copytree(COMMON_DIR / "system", tmp_path / "system")
    case, _, mesh = planned(name, [f'run.{key}="{scheme}"'] if scheme else [])
    render._solution(case, tmp_path, mesh)
    value = FoamFile(tmp_path / "system" / "fvSchemes")["ddtSchemes"][entry]
    assert (tuple(value) if not isinstance(value, str) else value) == written
    text = (tmp_path / "system" / "fvSchemes").read_text()
    words = written if isinstance(written, str) else " ".join(map(str, written))
    assert f"{entry} {words};" in " ".join(text.split())


def test_mesh_made_at_equilibrium(tmp_path):
    """run.mesh_pose = "equilibrium": G at equilibrium is the six-DoF initial centre of mass
    and the constraints' centre of rotation (the solver's initial one), G at release its
    centre of mass; refused for anything but the two poses, a heel or trim release, the
    O-grid and a body held still, in one line before anything is written."""
    from foamlib import FoamFile

    from floatfoam.plan.release import mesh_pose

    case, state, mesh = planned("lab_sphere", ['run.mesh_pose="equilibrium"'])
    eq = equilibrium(case)
    made = mesh_pose(case, state, eq)
    assert made.z_c == pytest.approx(eq.z_c) and state["mesh_offset"][2] == pytest.approx(
        case.release["heave"])
    render._motion(case, tmp_path, mesh, state)
    coeffs = FoamFile(tmp_path / "constant" / "dynamicMeshDict")["sixDoFRigidBodyMotionCoeffs"]
    assert coeffs["centreOfMass"][2] == pytest.approx(state["cog"][2])
    assert coeffs["initialCentreOfMass"][2] == pytest.approx(state["z_G_equilibrium"])
    assert coeffs["constraints"]["heaveOnly"]["centreOfRotation"][2] == pytest.approx(
        state["z_G_equilibrium"])
    with pytest.raises(InputError, match=r"^run.mesh_pose = 'upright': valid is one of "
                                         r"release, equilibrium$"):
        load_case("lab_sphere", ['run.mesh_pose="upright"'])
    for name, extra, says in (("elliptic_cylinder_roll", [], "heave only"),
                              ("cylinder_heave", [], "needs a gmsh mesh"),
                              ("lab_sphere", ["run.static_body=true"], "static_body = true")):
        case, state, _ = planned(name, ['run.mesh_pose="equilibrium"', *extra])
        with pytest.raises(InputError, match=says):
            mesh_pose(case, state, equilibrium(case))


def test_default_end_time_and_its_refusal():
    """No run.end_time: five periods of the released DoF with the added-mass allowance (roll
    × 1.15); a release whose DoF capsizes has no period to set it from."""
    from floatfoam.hydrostatics.theory import theory_summary

    case = load_case("ellipsoid")  # no [run]; released heeled 5°
    assert case.settings.run.end_time is None
    roll = theory_summary(case).period("roll")
    assert release.end_time_of(case) == pytest.approx(round(5 * 1.15 * roll, 2))
    assert release.end_time_of(load_case("ellipsoid", ["run.end_time=1.0"])) == 1.0
    with pytest.raises(InputError, match="capsizes"):  # ellipsoid_printed_verdict's body
        release.end_time_of(load_case("ellipsoid", ["mass.cog=[0,0,0.08]"]))


def test_cases_extend_one_another(tmp_path):
    child = load_case("sphere_50mm")
    parent = load_case("sphere")
    assert child.release["heave"] == 0.05 and parent.release["heave"] == 0.01
    assert child.mass == parent.mass and child.settings.run.end_time == 3.2
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    (tmp_path / "a" / "case.toml").write_text(f'[case]\nextends = "{tmp_path / "b"}"\n')
    (tmp_path / "b" / "case.toml").write_text(f'[case]\nextends = "{tmp_path / "a"}"\n')
    with pytest.raises(InputError, match="loop"):
        load_case(str(tmp_path / "a"))


def test_a_collapsing_time_step_stops_the_run():
    """100 steps in a row below the floor stop it, with the body's attitude; a short dip (the
    start-up's small steps) does not."""
    stall = Stall(Limits(min_delta_t=5e-5))
    turned = rotation(math.radians(80.4), 0.0)
    dip = [Step(time=i * 1e-5, delta_t=1e-5, orientation=turned) for i in range(99)]
    assert stall.check(dip) is None
    assert stall.check([Step(time=0.1, delta_t=1e-3, orientation=turned)]) is None
    message = stall.check([Step(time=1.0 + i * 1e-5, delta_t=1e-5, orientation=turned)
                           for i in range(100)])
    assert message and "roll 80.4°" in message and "run.outer_distance" in message
    assert Stall(Limits()).check(dip * 2) is None  # no floor: never


def test_the_stall_floor_lies_between_a_collapse_and_a_capsize():
    """The floor (foam.driver.stall_step) stays above the 3–10 µs a collapsing mesh falls to
    and below the 55 µs of a body turning over, for any largest step from 1 ms up, and under
    the largest step itself when that is smaller; a finer level divides it by its factor."""
    from floatfoam.foam.driver import stall_step
    for max_delta_t in (1e-3, 5e-3, 0.01, 0.05, 0.5):
        assert 10e-6 < stall_step(max_delta_t, 1.0) < 55e-6
    assert stall_step(1e-4, 1.0) < 1e-4 / 10
    assert stall_step(0.01, 2.0) == stall_step(0.01, 1.0) / 2


def test_summary_of_a_record_too_short_for_the_fit(tmp_path, capsys):
    """A record of 1.25 cycles (what a strongly radiating section leaves above the noise): the
    run's summary says why the fit is refused and times the period by the first extrema."""
    from floatfoam.cli.run import _dof_summary
    from floatfoam.dofs import dof
    from floatfoam.hydrostatics.theory import theory_summary
    from floatfoam.motion import read_motion, write_motion

    zeta, period = 0.25, 0.8
    wd = 2 * math.pi / period
    t = np.arange(0.0, 1.0, 0.002)
    z = 0.01 * np.exp(-zeta * wd / math.sqrt(1 - zeta**2) * t) * np.cos(wd * t)
    path = write_motion(tmp_path / "motion.csv", t, z=z)
    _dof_summary(dof("heave"), read_motion(path), theory_summary(load_case("elliptic_cylinder")))
    out = capsys.readouterr().out
    assert "CFD heave decay analysis: record: " in out and "need at least 1.5" in out
    found = float(out.split("period from them ")[1].split()[0])
    assert found == pytest.approx(period, rel=0.01)  # extrema at 0.4 and 0.8 s


def test_a_capsizing_release_is_summarised_by_its_turn(capsys):
    """No period to fit when the theory says it capsizes: the run's summary gives how far the
    body turned and when it passed each 10° (here a heel growing as 5° cosh(4t))."""
    from floatfoam import dofs
    from floatfoam.cli.run import _capsize_path

    t = np.linspace(0.0, 0.6, 601)
    heel = np.radians(5.0 * np.cosh(4.0 * t))
    _capsize_path(dofs.dof("roll"), t, heel)
    out = capsys.readouterr().out
    assert "from 5 deg to 27.78 deg at 0.600 s" in out
    assert f"10 deg at {np.arccosh(2.0) / 4:.3f} s" in out and "20 deg at" in out


@pytest.mark.parametrize("name, halved", [("elliptic_cylinder", 1.5), ("sphere", 0.5),
                                          ("ellipsoid_roll", 0.5)])
def test_a_time_step_study_halves_the_bulk_limit_of_its_mesh(name, halved):
    """--dt-divisor 2 halves the bulk's Courant limit the mesh's kind resolves to (3 on a
    section, 1 on a wedge and in a 3D tank), with the interface's and the largest step."""
    from floatfoam.plan.runplan import resolve

    run = resolve(load_case(name), divisor=2, solver=False).case.settings.run
    assert (run.max_courant, run.max_alpha_courant, run.max_delta_t) == pytest.approx(
        (halved, 0.25, 0.005), rel=1e-12)
