"""The tables of a case file that stages read, as typed, frozen settings validated once.

``[run]``, ``[mesh]`` (with ``[mesh.gmsh]``), ``[domain]``, ``[potential]`` and ``[motion]``
each become a frozen dataclass when the case is loaded (:func:`parse_settings`): an unknown key
is refused with the valid ones and a "did you mean", a boolean must be a TOML boolean, every
number is checked against its range and the relations between numbers are checked (inner <
outer distance, write interval ≤ end time, ω_min < ω_max). Stages read :class:`Settings`,
never the raw TOML.

A field's range, words and stamp flags, the parsing of a table and a run's stamp of them:
:mod:`floatfoam.fields`.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

from floatfoam.errors import InputError
from floatfoam.fields import parse_table, spec

# Memory of an interFoam run: ~2 kB per cell. Measured with /usr/bin/time -v on serial runs of
# cylinder_heave (rebuilt interFoam, v1912): peak resident 134.7 MB at 11,280 cells (coarse),
# 200.3 MB at 45,120 (fine), i.e. 1.94 kB per added cell. The cap keeps a typo from asking for
# more memory than a workstation has.
BYTES_PER_CELL = 2000

# Prism layers at a body given by triangles, in 3D, when the case leaves mesh.gmsh.layers_3d
# out. Measured against no layers (coarse, 2 ranks): on the half-immersed sphere meshed in 3D,
# 3 layers take the first trough from −2.3 % to −0.5 % of the wedge's and its steps from 1,502
# to 989; on the superellipsoid buoy's whole record they halve the periods' shortfall against
# Cummins' (heave −5.1 → −3.5 %, roll −2.2 → −1.0 %); 5 layers give the same
# (cases/superellipsoid_buoy).
TRIANGLE_LAYERS = 3


def max_cells() -> int:
    """The cells this machine's memory holds at :data:`BYTES_PER_CELL` (a run on other
    machines, with --hostfile, is not held to it)."""
    try:
        memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError):
        memory = 24 * 2**30
    return int(memory // BYTES_PER_CELL)


MESH_POSES = ("release", "equilibrium")
MESH_MOTIONS = ("auto", "laplacian", "distances", "layered")
#: run.motion_diffusivity: the Laplacian's diffusivity in the distance d from the body, and
#: its name in words
MOTION_DIFFUSIVITIES = {"quadratic": "1/d²", "linear": "1/d"}


def time_scheme_coefficient(scheme: str, key: str = "run.time_scheme", *,
                            auto: bool = False) -> float | None:
    """ψ of a time scheme "CrankNicolson ψ", None for "Euler" (and for "auto" where ``auto``
    allows it); anything else refused in one line naming the setting ``key``."""
    words = scheme.split()
    if words == ["Euler"] or (auto and words == ["auto"]):
        return None
    valid = ('valid: ' + ('"auto", ' if auto else '') +
             '"Euler" or "CrankNicolson ψ" with 0 ≤ ψ ≤ 1, e.g. "CrankNicolson 0.9"')
    if len(words) != 2 or words[0] != "CrankNicolson":
        raise InputError(f"{key} = {scheme!r}: {valid}")
    try:
        psi = float(words[1])
    except ValueError:
        raise InputError(f"{key} = {scheme!r}: ψ is not a number; {valid}") from None
    if not 0.0 <= psi <= 1.0:
        raise InputError(f"{key} = {scheme!r}: ψ = {psi:g}; {valid}")
    return psi


@dataclass(frozen=True)
class RunSettings:
    """``[run]``: the CFD run (times in s, distances in m)."""

    end_time: float | None = spec(None, minimum=0.0, doc="simulated time", extent=True)
    # in the stamp: it sets the written times, which the adjustable time step lands on (the
    # steps themselves), and the times a run restarts from
    write_interval: float = spec(0.1, minimum=0.0,
                                  doc="s between written fields (the last falls on end_time)")
    # Courant 0.5 at the interface and steps ≤ 10 ms; in the bulk 3 on a 2D section's mesh
    # (gmsh's or an O-grid's), 1 on a wedge and in a 3D tank (floatfoam.plan.release.
    # BULK_COURANT): the project's sections run at 10 ms whatever the bulk's limit (their
    # records the same to 1e-5), while a section with small bilge cells, whose water there holds
    # the step, runs its record in 0.47 × the wall of Courant 1, its period within 0.12 % and ζ
    # within 4 % (docs/studies/time-step-limits.md); in 3D the air's spurious currents over the
    # tetrahedral free surface hold the bulk's step (docs/studies/cases/ellipsoid_roll.md)
    max_courant: float | None = spec(None, minimum=0.0, maximum=5.0,
                                     doc="the largest Courant number the adjustable time step "
                                     "allows in the bulk; by default 3 on a 2D section's mesh, "
                                     "1 on a wedge and in a 3D tank")
    max_alpha_courant: float = spec(0.5, minimum=0.0, maximum=5.0,
                                    doc="the same at the interface (max_courant, if smaller, "
                                        "holds there too)")
    max_delta_t: float = spec(0.01, minimum=0.0,
                               doc="s: the largest time step, at the coarse level")
    # 1: no relaxation, v1912's own default; 0.7 leaves the six-DoF coupling loop unconverged
    # and the lightly damped rolls' ζ 2–10 % short (docs/coupling.md)
    acceleration_relaxation: float = spec(1.0, minimum=0.0, maximum=1.0,
                                           doc="r: each body acceleration = r·new + "
                                           "(1 − r)·previous, in every coupling iteration")
    outer_correctors: int = spec(3, kind=int, minimum=1, closed=True, maximum=20,
                                 doc="body–fluid coupling iterations per time step (PIMPLE's "
                                 "nOuterCorrectors)")
    # 0 on a 2D section's mesh and on a wedge, 0.01 in a 3D tank (floatfoam.plan.release.
    # COUPLING_TOLERANCE): there each iteration costs a third of a step and most steps end
    # after two (docs/coupling.md)
    coupling_tolerance: float | None = spec(None, minimum=0.0, closed=True, added=True,
                                            doc="ε: a step's coupling iterations end after the "
                                            "second, or a later one, when the next one's change "
                                            "of the body's velocity and angular velocity, "
                                            "estimated from the iterations' contraction, is at "
                                            "most ε × their change over the step "
                                            "(src/solver/couplingConvergence.H); 0: always "
                                            "outer_correctors; by default 0 on a 2D section's "
                                            "mesh and on a wedge, 0.01 in a 3D tank")
    mesh_motion: str = spec("auto", kind=str, doc="how the mesh follows the body: "
                             "layered (rows of points that move with the body by their height "
                             "alone: a body free in heave alone), "
                             "laplacian (displacementLaplacian, its diffusivity "
                             "run.motion_diffusivity: no distance to set), "
                             "distances (the six-DoF solver: rigid within inner_distance, "
                             "fixed beyond outer_distance), or auto: distances where "
                             "inner_distance or outer_distance is set, for a body "
                             "released to turn over or a mesh made at equilibrium, else "
                             "layered for a heave release on a 2D, O-grid or wedge mesh, "
                             "else laplacian (docs/morphing.md)")
    motion_diffusivity: str = spec("quadratic", kind=str, added=True,
                                    doc="the Laplacian's diffusivity in the distance d from "
                                    "the body: quadratic (1/d²) or linear (1/d, which spreads "
                                    "the deformation further from the body); the distances "
                                    "ignore it")
    layer_band: float = spec(1.0, minimum=1.0, closed=True, added=True,
                             doc="the layered motion's rows that move with the body: the "
                             "body's height × this, about its middle (docs/morphing.md)")
    inner_distance: float | None = spec(None, minimum=0.0,
                                         doc="m: the distances' mesh moves rigidly with the body "
                                             "within it (default: from the body and the tank, "
                                             "docs/morphing.md)")
    outer_distance: float | None = spec(None, minimum=0.0,
                                         doc="m: and not at all beyond it (default: 0.9 × the room"
                                             " between the body and the nearest held wall)")
    solver: str | None = spec(None, kind=str, doc="interFoam to run (default: floatfoam's)")
    static_body: bool = spec(False, kind=bool, doc="hold the body still (still-water test)")
    interface_gravity: bool = spec(False, kind=bool, added=True,
                                   doc="the gravity term's density jump taken at the free "
                                   "surface's height instead of the face's centre (floatfoam's "
                                   "interFoam, src/solver/interfaceGravity.H)")
    # 2 on the heaved 3D sphere puts its first trough on Cummins' model's (none: 1.1 % early),
    # yet its air bursts at the defaults' steps and its later cycles damp too fast
    # (docs/studies/interface-gravity.md)
    interface_gravity_smoothing: int = spec(0, kind=int, minimum=0, closed=True, maximum=20,
                                            added=True,
                                            doc="with run.interface_gravity: the times each "
                                            "free-surface cell's height is replaced by the "
                                            "mean of its own and its neighbours', weighted by "
                                            "α(1 − α) (src/solver/interfaceGravity.H); 0: "
                                            "each cell's own")
    # a turn that shears the distances' zone past what its cells take (on the morphing mesh
    # alone the 3D ellipsoid gives out 53° after its release; docs/morphing.md) meets a new
    # mesh first
    remesh_angle: float = spec(30.0, minimum=0.0, closed=True, maximum=180.0, added=True,
                                doc="deg: the body's turn from the attitude its mesh was made "
                                "at after which the run meshes the domain anew at the body's "
                                "pose and maps the fields onto it (the distances' mesh motion, "
                                "on a gmsh 2D section or 3D tank); 0: never")
    mesh_pose: str = spec("release", kind=str, doc="the body's pose the mesh is made at: "
                           "release, or equilibrium (heave releases; moved to the release "
                           "before the first step)")
    divergence_courant: float = spec(20.0, minimum=0.0,
                                      doc="a Courant number above it stops the run as diverged")
    divergence_body_speed: float = spec(10.0, minimum=0.0,
                                         doc="m/s: a body speed above it stops the run as diverged")
    # Crank–Nicolson ψ 0.9 on box_bilge diverges at relaxation 0.7, and at 0.4 the roll gains
    # energy (docs/studies/cases/box_bilge.md); the cases keep Euler
    time_scheme: str = spec("Euler", kind=str, doc="the time derivatives' scheme but the "
                             "interface's (run.interface_time_scheme): Euler (first order), "
                             "or \"CrankNicolson ψ\" with 0 ≤ ψ ≤ 1 (second order at ψ = 1)")
    # Crank–Nicolson for the interface alone takes three quarters of the first-order step's
    # error out of a heave's period (floatfoam's interFoam keeps its flux's geometric
    # conservation on the moving mesh: scripts/build_solver.sh); on a roll it measured as
    # Euler, and the damping hangs on the step as much on either (docs/studies/time-step.md)
    interface_time_scheme: str = spec("auto", kind=str,
                                      doc="the interface's (α's) time scheme: \"CrankNicolson "
                                      "ψ\" with 0 ≤ ψ ≤ 1, Euler, or auto: Crank–Nicolson 0.9 "
                                      "for a body free in heave alone, Euler for one free to "
                                      "turn (Crank–Nicolson needs the shared "
                                      "fvSolution's nAlphaSubCycles 1, which interFoam "
                                      "checks; docs/studies/time-step.md)")

    def check(self) -> None:
        time_scheme_coefficient(self.time_scheme)
        time_scheme_coefficient(self.interface_time_scheme, "run.interface_time_scheme",
                                auto=True)
        if self.interface_gravity_smoothing and not self.interface_gravity:
            raise InputError(f"run.interface_gravity_smoothing = "
                             f"{self.interface_gravity_smoothing}: valid with "
                             "run.interface_gravity = true, or 0")
        if self.mesh_motion not in MESH_MOTIONS:
            raise InputError(f"run.mesh_motion = {self.mesh_motion!r}: valid is one of "
                             f"{', '.join(MESH_MOTIONS)}")
        if self.motion_diffusivity not in MOTION_DIFFUSIVITIES:
            raise InputError(f"run.motion_diffusivity = {self.motion_diffusivity!r}: valid is "
                             f"one of {', '.join(MOTION_DIFFUSIVITIES)}")
        if self.mesh_motion in ("laplacian", "layered") and self.mesh_pose != "release":
            raise InputError(f"run.mesh_motion = \"{self.mesh_motion}\" with run.mesh_pose = "
                             f"{self.mesh_pose!r}: valid is mesh_pose \"release\" (a mesh made "
                             "at rest is moved to the release by the six-DoF solver's scale) "
                             "or mesh_motion \"distances\"")
        if self.mesh_pose not in MESH_POSES:
            raise InputError(f"run.mesh_pose = {self.mesh_pose!r}: valid is one of "
                             f"{', '.join(MESH_POSES)}")
        if self.end_time is not None and self.write_interval > self.end_time:
            raise InputError(f"run.write_interval = {self.write_interval:g} > run.end_time = "
                             f"{self.end_time:g}: valid is write_interval ≤ end_time")
        inner, outer = self.inner_distance, self.outer_distance
        if inner is not None and outer is not None and not inner < outer:
            raise InputError(f"run.inner_distance = {inner:g} ≥ run.outer_distance = {outer:g}: "
                             "valid is inner_distance < outer_distance (the mesh moves rigidly "
                             "inside the inner one and not at all beyond the outer one)")


@dataclass(frozen=True)
class GmshSettings:
    """``[mesh.gmsh]``: sizes of the gmsh meshes at the coarse level (meshing.levels)."""

    body_cells: float = spec(24, minimum=0.0, maximum=2000,
                              doc="cells across the body's smallest dimension on its surface (2D, "
                                  "wedge)")
    body_cells_3d: float = spec(12, minimum=0.0, maximum=500, doc="the same in 3D")
    curvature_cells: float = spec(48, minimum=0.0, maximum=5000,
                                   doc="cells per 2π of the surface's turning, where it turns fast")
    # 4: no case here is refined more (the hyperbola's vertex 3.9, box_bilge 2.1); a small
    # bilge radius's cells set the step (docs/studies/section-cost.md: 2 took a flat barge's
    # record from 7.7 to 5.3 min and moved its ζ by +9 %, its T_d by +0.3 %)
    curvature_refinement: float = spec(4.0, minimum=1.0, closed=True, maximum=100.0,
                                       doc="the most the curvature refines the body's cells "
                                       "(2D, wedge): none smaller than the body's cell size / "
                                       "this")
    # 1.2: the elliptic section's coarse 2D mesh has 11.0k cells (17.5k at 1.1), and an
    # interFoam step costs ~11 µs per cell on 2 ranks here: 5 roll periods in ~2 min
    growth: float = spec(1.2, minimum=1.0, maximum=3.0,
                          doc="size ratio of neighbouring cells away from the body (2D, wedge)")
    growth_3d: float = spec(1.2, minimum=1.0, maximum=3.0, doc="the same in 3D")
    # prism layers at the body in 3D (a body given by triangles, or an ellipsoid): their count
    # (left out: TRIANGLE_LAYERS at a body given by triangles, 0 at an exact solid; resolved
    # when the case loads) and their total height in body cells (meshing.domain3d)
    layers_3d: int | None = spec(None, kind=int, minimum=0, closed=True, maximum=20, inert=0,
                                  doc="default: 3 at a body given by triangles (stl, "
                                  "implicit), 0 at an exact solid (an ellipsoid takes them "
                                  "when given)")
    layers_height_3d: float = spec(1.0, minimum=0.0, maximum=5.0, added=True,
                                    doc="the prism layers' total height, in body cells")
    # a flat free surface cut by tetrahedra is out of hydrostatic balance (interFoam's gravity
    # term balances the pressure across horizontal faces alone: docs/openfoam-v1912.md): on
    # the heaved 3D sphere the air far from it carried 0.5–0.9 m/s (median), 10⁻⁴ m/s on this
    # band's prisms; its period stays 1.1–1.4 % short with them (the tetrahedra at the body):
    # off by default (docs/studies/cases/superellipsoid_buoy.md)
    band_prisms_3d: bool = spec(False, kind=bool, added=True,
                                doc="the free-surface band of a 3D tank (|z| ≤ domain.band) in "
                                    "horizontal layers of prisms outside a column about the "
                                    "body, tetrahedra within it (a body given by triangles, or "
                                    "with prism layers); false: tetrahedra throughout")
    # gmsh's own optimiser leaves flat tetrahedra at the free surface (the heaved 3D sphere's
    # coarse mesh: non-orthogonality up to 65°); Netgen's takes it to 52° and the sphere's record
    # on the layered motion to 639 steps from 1,950, its first seven extrema within 0.7 % of
    # Cummins' model (docs/studies/interface-gravity.md, docs/guide/meshes.md)
    optimize_netgen_3d: bool = spec(True, kind=bool, added=True,
                                    doc="optimise a 3D tank's tetrahedra with Netgen's "
                                        "optimiser after gmsh's own (Mesh.OptimizeNetgen); "
                                        "false: gmsh's alone")
    half_3d: bool = spec(True, kind=bool, added=True,
                          doc="mesh half the tank, with a symmetry plane, for a body symmetric "
                              "about x = 0 or y = 0 (found from its shape or triangles) whose "
                              "G and motion keep that plane; false: the whole tank")
    # the heaved 3D sphere's coarse record on tetrahedra: T_d over 1.9 s −0.55 % of Cummins'
    # (the Laplacian; −0.01 % at the medium level), the wedge's whole record +0.2 %
    # (docs/morphing.md)
    wedge: bool = spec(True, kind=bool, added=True,
                       doc="mesh an upright body of revolution about z, released in heave "
                           "alone, as an axisymmetric wedge (a shape of revolution, or "
                           "triangles found to be one); false: in 3D")
    margin: float = spec(0.5, minimum=0.0, maximum=50.0,
                          doc="half-thickness of the core block around the body, × its smallest "
                              "dimension")

    def check(self) -> None:
        pass


def _row_memory(cells: float) -> str:
    """What one row of ``cells`` O-grid cells alone would need in memory, in words."""
    return f"{memory_text(cells)} in one row of cells alone"


@dataclass(frozen=True)
class MeshSettings:
    """``[mesh]``: the refinement ratio between levels and the blockMesh O-grid's counts (at the
    coarse level); ``[mesh.gmsh]`` the gmsh meshes'."""

    refinement_ratio: float = spec(math.sqrt(2.0), minimum=1.0, maximum=4.0,
                                    doc="r: cell sizes and the largest time step shrink by "
                                        "it from one level to the next")
    mesher: str = spec("gmsh", kind=str, doc="gmsh (any body) or ogrid (a circle)")
    square_half_size: float | None = spec(None, minimum=0.0,
                                           doc="m, O-grid: half the side of the square around the "
                                               "circle")
    cells_side: int = spec(40, kind=int, minimum=0, maximum=20000, too_many=_row_memory,
                            doc="O-grid: cells along a side of the square")
    cells_radial: int = spec(16, kind=int, minimum=0, maximum=20000, too_many=_row_memory,
                              doc="O-grid: cells from the circle to the square")
    radial_grading: float = spec(2.0, minimum=0.0, maximum=1000.0,
                                  doc="O-grid: last to first radial cell's size")
    cells_horizontal: int = spec(40, kind=int, minimum=0, maximum=20000, too_many=_row_memory,
                                  doc="O-grid: cells from the square to each end")
    cells_below: int = spec(30, kind=int, minimum=0, maximum=20000, too_many=_row_memory,
                             doc="O-grid: cells below the square")
    cells_above: int = spec(16, kind=int, minimum=0, maximum=20000, too_many=_row_memory,
                             doc="O-grid: cells above the square")
    gmsh: GmshSettings = field(default_factory=GmshSettings)

    def check(self) -> None:
        if self.mesher not in ("gmsh", "ogrid"):
            raise InputError(f"mesh.mesher = {self.mesher!r}: valid are \"gmsh\" (any body) "
                             "and \"ogrid\" (a blockMesh O-grid around a circular section)")
        ring = 4 * self.cells_radial * self.cells_side  # the O-grid around the body alone
        if ring > max_cells():
            raise InputError(f"mesh.cells_radial × mesh.cells_side = {self.cells_radial} × "
                             f"{self.cells_side}: the O-grid around the body alone has "
                             f"{memory_text(ring)}; valid is at most {max_cells():,} cells on "
                             "this machine")


@dataclass(frozen=True)
class DomainSettings:
    """``[domain]``: the tank around the body (m); absent values scale with the body."""

    half_length: float | None = spec(None, minimum=0.0,
                                      doc="m: from the body to each end (y in 2D, x in 3D, a "
                                          "wedge's radius; default 20 × the body's largest "
                                          "dimension)")
    half_width: float | None = spec(None, minimum=0.0,
                                     doc="m, 3D: to each side (default: half_length)")
    depth: float | None = spec(None, minimum=0.0,
                                doc="m of water (default: fluid.depth, else 10 × the body's "
                                    "largest dimension)")
    air_height: float | None = spec(None, minimum=0.0,
                                     doc="m of air above the water (default 3 × the body's largest"
                                         " dimension)")
    band: float | None = spec(None, minimum=0.0,
                               doc="m: half-height of the refined band about the free surface "
                                   "(default: where the waterline goes in the first oscillation)")
    thickness: float | None = spec(None, minimum=0.0,
                                    doc="m: a 2D slab's (default: the section's length)")

    def check(self) -> None:
        pass


@dataclass(frozen=True)
class PotentialSettings:
    """``[potential]``: the panel count and the frequencies (ω√(ℓ/g)) of potential flow; absent
    values take the module defaults."""

    panels: int | None = spec(None, kind=int, minimum=7, maximum=20000,
                               doc="wetted panels (default 64 for a 2D section, 800 in 3D)")
    omega_min: float | None = spec(None, minimum=0.0,
                                    doc="lowest frequency, ω√(ℓ/g) (default 0.05)")
    omega_max: float | None = spec(None, minimum=0.0,
                                    doc="highest frequency, ω√(ℓ/g) (default 2.5)")
    frequencies: int | None = spec(None, kind=int, minimum=1, maximum=2000,
                                    doc="frequencies between them (default 32)")

    def check(self) -> None:
        if self.omega_min is not None and self.omega_max is not None \
                and not self.omega_min < self.omega_max:
            raise InputError(f"potential.omega_min = {self.omega_min:g} ≥ potential.omega_max = "
                             f"{self.omega_max:g}: valid is omega_min < omega_max")


@dataclass(frozen=True)
class MotionSettings:
    """``[motion]``: the DoFs the body is free in, in the CFD and in the models alike, as a rig
    holds a model (a roll-only rig: ``free = ["roll"]``, about a fixed axis through G); absent,
    those a body released in a fluid moves in (:func:`floatfoam.dofs.free_dofs`)."""

    free: tuple[str, ...] | None = spec(None, kind=tuple, added=True,
                                         doc="names among heave, roll, pitch, surge, sway; "
                                         "the released ones must be in it")

    def check(self) -> None:
        from floatfoam.dofs import COUPLED_NAMES

        for name in self.free or ():
            if name not in COUPLED_NAMES:
                raise InputError(f"motion.free = {list(self.free)!r}: {name!r} is not a DoF; "
                                 f"valid names are {', '.join(COUPLED_NAMES)}")
        if self.free is not None and len(set(self.free)) != len(self.free):
            raise InputError(f"motion.free = {list(self.free)!r}: a DoF is named twice; valid "
                             "is each at most once")


@dataclass(frozen=True)
class Settings:
    """The settings of every stage of a case."""

    run: RunSettings = field(default_factory=RunSettings)
    mesh: MeshSettings = field(default_factory=MeshSettings)
    domain: DomainSettings = field(default_factory=DomainSettings)
    potential: PotentialSettings = field(default_factory=PotentialSettings)
    motion: MotionSettings = field(default_factory=MotionSettings, metadata={"added": True})


TABLES = {"run": RunSettings, "mesh": MeshSettings, "domain": DomainSettings,
          "potential": PotentialSettings, "motion": MotionSettings}


def parse_settings(cfg: dict) -> Settings:
    """The :class:`Settings` of a case's merged tables."""
    return Settings(**{table: parse_table(cls, cfg.get(table), table)
                       for table, cls in TABLES.items()})


def memory_text(cells: float) -> str:
    """What ``cells`` interFoam cells would need in memory, in words."""
    gib = cells * BYTES_PER_CELL / 2**30
    return f"{cells:.3g} cells, ~{gib:.3g} GiB for interFoam at ~{BYTES_PER_CELL} B per cell"
