"""Linear potential flow: added mass A(ω) and radiation damping B(ω) of a body at equilibrium.

* 3D bodies: Capytaine 3.0 (Ancellin & Dias 2019), **direct** boundary integral equation
  (Green's identity, as in WAMIT: converges faster for the forces than Capytaine's default
  source method; the hemisphere at the default 800 panels is within 1.5 % of Hulme 1982),
  constant panels on the wetted surface remeshed by :mod:`~floatfoam.potential.bem_mesh`
  (only the half or quarter of a symmetric hull, Capytaine rebuilding the rest by reflection), a
  lid on the interior waterplane (z = 0) for irregular-frequency removal, infinite or finite depth.
* 2D sections: the panel method of :mod:`floatfoam.potential.sections` (per metre; in finite
  depth :mod:`floatfoam.potential.sections_depth`), multiplied by the section's length L (strip
  theory without end effects, docs/conventions.md: section quantities are for the length L).

Degrees of freedom (heave, roll, pitch, surge, sway: :data:`floatfoam.dofs.COUPLED`), rotations
about the centre of gravity G at equilibrium, earth axes; surge and sway have no restoring but
their added inertia couples them to pitch and roll (a free body does not roll about G alone).
Results are cached in ``build/potential/<sha256>.npz`` keyed by the
body's surface mesh, the attitude, the panel count, G, the depth, the fluid and the
frequencies (and the Capytaine and floatfoam versions).
"""

from __future__ import annotations

import hashlib
import json
import logging
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from floatfoam.dofs import COUPLED, NAMES, PARTNER
from floatfoam.potential import bem_mesh
from floatfoam.potential import sections as section_bem
from floatfoam.potential.bounded import Progress, run_bounded
from floatfoam.potential.sections_depth import radiation_coefficients_2d_depth
from floatfoam.potential.summary import DofPotential, PotentialSummary

CACHE_VERSION = 3  # bump when the numerics change (2: surge and sway; 3: float32, deep at kh ≥ 6)
OMEGA_MIN_ND = 0.05  # ω √(ℓ/g), ℓ = half the waterline beam (2D) or √(A_wp/π) (3D)
OMEGA_MAX_ND = 2.5  # wave length 2πℓ/2.5² ≈ ℓ: ≈ 7 panels per wave length at 800 panels
FREQUENCIES = 32
COUPLING_NOTE = 0.05  # off-diagonal / √(diagonal product) above which a note says so
COUPLED_INDEX = {d.name: d.index for d in COUPLED}
MIN_KH = 0.15  # Capytaine's finite-depth Green function (Prony fit) fails below kh ≈ 0.1–0.15
# Capytaine's Green function in single precision: every A and B within 7e-7 (relative) of
# double precision on the sphere at kh = 0.15, 1 and ∞, the assembly ~20 % and the LU ~3×
# faster (measured here, one thread, Capytaine 3.0)
PRECISION = "float32"
# Finite depth costs ~4.6× deep water's matrix assembly in Capytaine 3.0 (the wave part four
# times, four image integrals per Prony exponential; measured on the sphere at 860 panels:
# 1.26 s against 0.25 s per frequency). Where the waves do not reach the bottom (kh ≥ 6) and
# the tank is deep against the body (h ≥ 8 × its half-size or draft), the deep-water Green
# function is used: it is closer to a tightly fitted finite-depth kernel than Capytaine's own
# default fit there (heave A −0.03 % against +0.17 … +0.59 % at kh 6–26, the sphere at 0.9 m);
# at h = 3 × the half-size it would be 1–2.5 % off (the bottom's near field), hence the ratio.
KH_DEEP, DEPTH_RATIO_DEEP = 6.0, 8.0


@dataclass(frozen=True)
class RadiationCoefficients:
    """A(ω), B(ω) for (heave, roll, pitch, surge, sway) about G, earth axes; for a 2D section,
    for its length L (the 2D values times L).

    Attributes
    ----------
    omega : (n,) rad/s
    added_mass, damping : (n, 5, 5) in kg, kg·m, kg·m² (and N·s/m, N·m·s, N·m·s), in the
        order of :data:`floatfoam.dofs.COUPLED`
    added_mass_inf : (5, 5), the infinite-frequency limit A∞
    method : "capytaine-3d" or "panel-2d"
    panels : number of panels on the wetted surface (the whole hull, lid not counted)
    depth : water depth used by the solver (inf for deep water)
    covered : which of (heave, roll, pitch, surge, sway) the solver covers (2D: no pitch,
        no surge)
    notes : what the user should know about these numbers
    """

    omega: np.ndarray
    added_mass: np.ndarray
    damping: np.ndarray
    added_mass_inf: np.ndarray
    method: str
    panels: int
    depth: float
    covered: tuple[bool, ...] = (True,) * len(COUPLED)
    notes: tuple[str, ...] = field(default=())


def frequency_grid(length: float, *, g: float = 9.81, omega_min_nd: float = OMEGA_MIN_ND,
                   omega_max_nd: float = OMEGA_MAX_ND, count: int = FREQUENCIES) -> np.ndarray:
    """Equally spaced frequencies ω = ω̂ √(g/ℓ) for ω̂ in [omega_min_nd, omega_max_nd] (equal
    spacing suits the cosine transform of the Cummins kernel)."""
    scale = math.sqrt(g / length)
    return np.linspace(omega_min_nd * scale, omega_max_nd * scale, count)


def capytaine_coefficients(vertices: np.ndarray, faces: np.ndarray, *, centre, omegas,
                           depth: float = math.inf, rho: float = 1000.0, g: float = 9.81,
                           lid: bool = True, planes: tuple[str, ...] = (), lid_mesh=None,
                           progress=None):
    """Radiation coefficients of a wetted hull mesh (earth frame, z ≤ 0) with Capytaine.

    ``planes``: the mesh is the part y ≥ 0 ("xOz") and/or x ≥ 0 ("yOz") of a symmetric hull,
    rebuilt by reflection (Capytaine's ReflectionSymmetricMesh). ``lid_mesh``: (vertices,
    faces) of the interior waterplane of that part (default: Capytaine's ``generate_lid``).

    Solves Capytaine's radiation problems for Heave, Roll, Pitch, Surge and Sway about
    ``centre`` with the direct method (one matrix and its LU per frequency, five right-hand
    sides); A_ij = Re F_ij / ω², B_ij = Im F_ij / ω (Capytaine's convention, e^{-iωt}).
    ``omega = inf`` is solved too (A∞). Returns (A (n, 5, 5), B (n, 5, 5), A∞ (5, 5)).
    The Green function is evaluated in single precision (:data:`PRECISION`); at finite depth,
    frequencies whose waves do not reach the bottom (kh ≥ :data:`KH_DEEP`, and ω = ∞) in a tank
    deeper than :data:`DEPTH_RATIO_DEEP` × the body's half-size use the deep-water one.
    ``progress`` (a :class:`~floatfoam.potential.bounded.Progress`) hears of each frequency.
    """
    import capytaine as cpt
    import capytaine.tools.prony_decomposition as prony

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    mesh = cpt.Mesh(vertices, faces, name="hull")
    lid_part = cpt.Mesh(*lid_mesh, name="lid") if (lid and lid_mesh is not None) else None
    for plane in planes:
        mesh = cpt.ReflectionSymmetricMesh(half=mesh, plane=plane, name="hull")
        if lid_part is not None:
            lid_part = cpt.ReflectionSymmetricMesh(half=lid_part, plane=plane, name="lid")
    if lid and lid_part is None:
        lid_part = mesh.generate_lid(z=0.0)
    if lid_part is not None and lid_part.nb_faces == 0:
        lid_part = None  # fully submerged: no interior free surface
    names = tuple(d.name.capitalize() for d in COUPLED)
    body = cpt.FloatingBody(mesh=mesh, lid_mesh=lid_part, name="hull",
                            dofs=cpt.rigid_body_dofs(only=names, rotation_center=centre))
    solver = cpt.BEMSolver(method="direct",
                           green_function=cpt.Delhommeau(floating_point_precision=PRECISION))
    water_depth = np.inf if math.isinf(depth) else float(depth)
    size = max(float(np.abs(vertices[:, :2]).max()), float(-vertices[:, 2].min()))
    all_omegas = [*np.asarray(omegas, dtype=float), np.inf]
    results = []
    for k, w in enumerate(all_omegas):  # one frequency at a time, for the progress line
        problems = [cpt.RadiationProblem(body=body, omega=w, radiating_dof=d,
                                         water_depth=water_depth, rho=rho, g=g) for d in names]
        if math.isfinite(water_depth) and water_depth >= DEPTH_RATIO_DEEP * size and (
                math.isinf(w) or problems[0].wavenumber * water_depth >= KH_DEEP):
            problems = [cpt.RadiationProblem(body=body, omega=w, radiating_dof=d,
                                             water_depth=np.inf, rho=rho, g=g) for d in names]
        # Capytaine fits the finite-depth kernel (Prony) to randomly perturbed samples: seeded,
        # two runs agree to the bit (unseeded they differed by 0.2 % in heave A at kh = 0.15)
        prony.RNG = np.random.default_rng(0)
        results += solver.solve_all(problems, progress_bar=False, _display_errors=False)
        if progress is not None:
            progress.update(k + 1)
    out_a = np.full((len(all_omegas), len(names), len(names)), np.nan)
    out_b = np.full_like(out_a, np.nan)
    for k, res in enumerate(results):
        i_w, j = divmod(k, len(names))
        if hasattr(res, "exception"):
            raise RuntimeError(f"Capytaine failed at ω = {all_omegas[i_w]:.4g} rad/s "
                               f"({res.radiating_dof}): {res.exception}")
        for i, name in enumerate(names):
            out_a[i_w, i, j] = res.added_mass[name]
            out_b[i_w, i, j] = res.radiation_damping[name]
    return out_a[:-1], out_b[:-1], out_a[-1]


def section_coefficients(nodes: np.ndarray, *, centre_yz, omegas, length: float,
                         rho: float = 1000.0, g: float = 9.81, depth: float = math.inf):
    """2D coefficients of a section (:mod:`floatfoam.potential.sections`) as (heave, roll, pitch,
    surge, sway) matrices for the length L: sway, heave and roll (about G) times L; pitch and
    surge rows are zero."""
    if math.isinf(depth):
        res = section_bem.radiation_coefficients_2d(nodes, [*omegas, np.inf], centre=centre_yz,
                                                    rho=rho, g=g)
    else:
        res = radiation_coefficients_2d_depth(nodes, [*omegas, np.inf], depth=depth,
                                              centre=centre_yz, rho=rho, g=g)
    order = [COUPLED_INDEX[m] for m in section_bem.MODES]  # (sway, heave, roll) → matrix rows
    a = np.zeros((len(omegas) + 1, len(COUPLED), len(COUPLED)))
    b = np.zeros_like(a)
    a[np.ix_(range(len(a)), order, order)] = res["added_mass"] * length
    b[np.ix_(range(len(b)), order, order)] = res["damping"] * length
    return a[:-1], b[:-1], a[-1]


def _digest(arrays: dict, scalars: dict) -> str:
    h = hashlib.sha256()
    for name in sorted(arrays):
        h.update(name.encode())
        h.update(np.ascontiguousarray(arrays[name], dtype=float).round(12).tobytes())
    h.update(json.dumps(scalars, sort_keys=True, default=str).encode())
    return h.hexdigest()[:24]


def default_cache_dir() -> Path:
    from floatfoam.layout import build_dir

    return build_dir() / "potential"


def radiation_coefficients(case, eq=None, *, panels: int | None = None, omegas=None,
                           cache: bool = True, cache_dir: Path | None = None
                           ) -> RadiationCoefficients:
    """A(ω), B(ω) and A∞ of a case's body at its equilibrium (adapter over the solvers).

    Options come from the case's ``[potential]`` settings when present (``panels``,
    ``omega_min``/``omega_max`` as ω√(ℓ/g), ``frequencies``), else the module defaults.
    """
    from floatfoam.bodies.geometry import rotation
    from floatfoam.hydrostatics.theory import equilibrium

    eq = eq or equilibrium(case)
    opts = case.settings.potential
    body = case.body
    centre = rotation(eq.heel, eq.trim) @ case.cog + np.array([0.0, 0.0, eq.z_c])
    notes = []
    if body.is_section:
        panels = int(panels or opts.panels or section_bem.DEFAULT_PANELS)
        nodes = bem_mesh.section_panels(body, eq.z_c, eq.heel, panels)
        half_beam = 0.5 * float(np.ptp(nodes[:, 0]))
        depth = case.depth  # greater than the draft: equilibrium() checks it (fluid_domain)
        geometry = {"polygon": body.section_polygon(), "nodes": nodes}
        ell = half_beam
    else:
        panels = int(panels or opts.panels or bem_mesh.DEFAULT_PANELS_3D)
        depth = case.depth
        vertices, faces = body.surface_mesh()
        geometry = {"vertices": vertices, "faces": faces}
        ell = math.sqrt(eq.immersed.waterplane_area / math.pi) if eq.immersed.waterplane_area \
            else 0.5 * body.size
    if omegas is None:
        omegas = frequency_grid(ell, g=case.g,
                                omega_min_nd=opts.omega_min or OMEGA_MIN_ND,
                                omega_max_nd=opts.omega_max or OMEGA_MAX_ND,
                                count=opts.frequencies or FREQUENCIES)
    omegas = np.asarray(omegas, dtype=float)
    if not body.is_section and math.isfinite(depth) and omegas.size:
        # Capytaine's finite-depth Green function (Delhommeau) needs kh ≥ 0.1
        lowest = math.sqrt(case.g * MIN_KH / depth * math.tanh(MIN_KH))
        if omegas[0] < lowest:
            omegas = np.linspace(lowest, omegas[-1], len(omegas))
            notes.append(f"finite depth {depth:g} m: frequencies from kh = {MIN_KH:g} "
                         f"(ω = {lowest:.4g} rad/s), the lowest Capytaine evaluates")
    from importlib.metadata import version  # not `import capytaine`: 0.5 s a section needs not

    from floatfoam import __version__

    key = _digest({**geometry, "omegas": omegas, "centre": centre},
                  {"z_c": round(eq.z_c, 12), "heel": round(eq.heel, 12),
                   "trim": round(eq.trim, 12), "panels": panels, "depth": depth,
                   "rho": case.rho, "g": case.g, "length": body.length,
                   "section": body.is_section, "cache": CACHE_VERSION,
                   "capytaine": version("capytaine"), "floatfoam": __version__})
    path = (cache_dir or default_cache_dir()) / f"{key}.npz"
    if cache and path.is_file():
        data = np.load(path, allow_pickle=False)
        return _from_arrays(data, notes)
    if body.is_section:
        a, b, a_inf = section_coefficients(nodes, centre_yz=centre[1:], omegas=omegas,
                                           length=body.length, rho=case.rho, g=case.g,
                                           depth=depth)
        count, method = len(nodes) - 1, "panel-2d"
        covered = tuple(d.name in section_bem.MODES for d in COUPLED)
    else:
        draft = f"z_c = {eq.z_c:.6g} m, heel {math.degrees(eq.heel):.3g}°, trim " \
            f"{math.degrees(eq.trim):.3g}°"
        a, b, a_inf, count, planes = run_bounded(
            _solve_3d, body, eq, panels, centre, omegas, depth, case.rho, case.g, case.name,
            limit=time_limit(panels, len(omegas), depth),
            label=f"potential flow of {case.name} ({draft}, {panels} panels)",
            advice="valid: another [potential] panels (or --panels), or report the body")
        method, covered = "capytaine-3d", (True,) * len(COUPLED)
        if planes:
            method += f" (symmetric about {' and '.join(planes)})"
    arrays = {"omega": omegas, "added_mass": a, "damping": b, "added_mass_inf": a_inf,
              "panels": np.array(count), "depth": np.array(depth),
              "covered": np.array(covered), "method": np.array(method)}
    if cache:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(".tmp.npz")
        np.savez(tmp, **arrays)
        tmp.replace(path)
    return _from_arrays(arrays, notes)


def time_limit(panels: int, frequencies: int, depth: float) -> float:
    """The bound on meshing and solving a 3D body, s: 20 × the expected time, at least 2 min.

    Expected: 8 s for the laboratory sphere (lab_sphere) at 860 panels and 33 frequencies in
    deep water, 24 s at its finite depth (measured here, one thread, five DoFs), scaling as
    panels² × frequencies.
    """
    per = (24.0 if math.isfinite(depth) else 8.0) / (860**2 * 33)
    return max(120.0, 20.0 * per * panels**2 * (frequencies + 1))


def _solve_3d(body, eq, panels, centre, omegas, depth, rho, g, label):
    """Mesh the wetted hull and solve it (run in a bounded child process)."""
    vertices, faces, planes = bem_mesh.wetted_hull(body, eq.z_c, eq.heel, eq.trim, panels)
    lid = bem_mesh.waterplane_lid(vertices, faces, planes, bem_mesh.panel_size(vertices, faces))
    progress = Progress(f"{label}: potential flow", len(omegas) + 1)
    a, b, a_inf = capytaine_coefficients(vertices, faces, centre=centre, omegas=omegas,
                                         depth=depth, rho=rho, g=g, planes=planes,
                                         lid_mesh=lid, progress=progress)
    return a, b, a_inf, len(faces) * 2 ** len(planes), planes


def _from_arrays(data, notes) -> RadiationCoefficients:
    return RadiationCoefficients(
        omega=np.asarray(data["omega"]), added_mass=np.asarray(data["added_mass"]),
        damping=np.asarray(data["damping"]), added_mass_inf=np.asarray(data["added_mass_inf"]),
        method=str(data["method"]), panels=int(data["panels"]), depth=float(data["depth"]),
        covered=tuple(bool(x) for x in np.asarray(data["covered"])), notes=tuple(notes))


def potential_summary(case, *, coefficients: RadiationCoefficients | None = None,
                      **kw) -> PotentialSummary:
    """Natural periods with added mass and radiation damping ratios of a case.

    For each degree of freedom i that oscillates (positive stiffness; Le Barbier's verdict for
    roll and pitch), uncoupled: ω_n² = C_ii / (M_ii + A_ii(ω_n)) and
    ζ = B_ii(ω_n) / (2 ω_n (M_ii + A_ii(ω_n))) (:mod:`floatfoam.potential.resonance`): one
    :class:`~floatfoam.potential.summary.DofPotential` per DoF (None where the DoF does not
    oscillate or is not covered, e.g. pitch of a 2D section), A∞ and what was solved.
    """
    from floatfoam.bodies.geometry import rotation
    from floatfoam.hydrostatics.theory import equilibrium, stiffness_matrix
    from floatfoam.hydrostatics.verdict import verdict
    from floatfoam.potential.resonance import (
        condensed,
        damping_ratio,
        mass_matrix,
        natural_frequency,
    )

    eq = equilibrium(case)
    coef = coefficients or radiation_coefficients(case, eq, **kw)
    stiffness = stiffness_matrix(case, eq)
    mass_all = mass_matrix(case.mass, case.gyradius, rotation(eq.heel, eq.trim),
                           horizontal=True)
    mass = mass_all[:3, :3]
    rgv = case.rho * case.g * eq.immersed.volume
    oscillates = [stiffness[0, 0] > 0.0] + [
        verdict(stiffness[i, i] / rgv, case.body.size, eq.immersed.exact) == "oscillates"
        for i in (1, 2)]
    notes = list(coef.notes)
    per_dof = {}
    for i, dof in enumerate(NAMES):
        values = per_dof[dof] = {}
        if not oscillates[i]:
            continue
        values["period_no_added_mass"] = 2 * math.pi * math.sqrt(mass[i, i] / stiffness[i, i])
        if not coef.covered[i]:
            continue
        a_ii, b_ii = coef.added_mass[:, i, i], coef.damping[:, i, i]
        omega_n, inside = natural_frequency(mass[i, i], stiffness[i, i], coef.omega, a_ii)
        if not inside:
            notes.append(f"{dof}: ω_n = {omega_n:.4g} rad/s is outside the solved "
                         "frequencies; A and B held at their end values")
        w = min(max(omega_n, coef.omega[0]), coef.omega[-1])
        a_n = float(np.interp(w, coef.omega, a_ii))
        b_n = float(np.interp(w, coef.omega, b_ii))
        values.update(period=2 * math.pi / omega_n, natural_frequency=omega_n, added_mass=a_n,
                      radiation_damping=b_n,
                      damping_ratio=damping_ratio(mass[i, i], omega_n, a_n, b_n))
        partner = COUPLED_INDEX[PARTNER[dof]] if dof in PARTNER else None
        if partner is not None and coef.covered[partner]:
            a_eff, b_eff = condensed(coef.omega, mass_all, coef.added_mass, coef.damping,
                                     i, [partner])
            omega_c, _ = natural_frequency(mass[i, i], stiffness[i, i], coef.omega, a_eff)
            w = min(max(omega_c, coef.omega[0]), coef.omega[-1])
            values.update(coupled_period=2 * math.pi / omega_c, coupled_damping_ratio=(
                damping_ratio(mass[i, i], omega_c, float(np.interp(w, coef.omega, a_eff)),
                              float(np.interp(w, coef.omega, b_eff)))))
    for i, j in ((0, 1), (0, 2), (1, 2)):
        if coef.covered[i] and coef.covered[j]:
            ratios = [abs(m[i, j]) / math.sqrt(abs(m[i, i] * m[j, j]) or 1.0)
                      for m in (stiffness, coef.added_mass_inf[:3, :3] + mass)]
            if max(ratios) > COUPLING_NOTE:
                notes.append(f"{NAMES[i]}–{NAMES[j]} coupling {max(ratios):.0%} (stiffness "
                             "or inertia): the periods above are uncoupled")
    return PotentialSummary(
        case=case.name, method=coef.method, panels=coef.panels,
        depth=None if math.isinf(coef.depth) else coef.depth,
        frequencies={"min": float(coef.omega[0]), "max": float(coef.omega[-1]),
                     "count": int(len(coef.omega))},
        section_length=case.body.length, notes=notes,
        dofs={dof: DofPotential(**values) for dof, values in per_dof.items()},
        added_mass_inf=coef.added_mass_inf[:3, :3].tolist(), stiffness=stiffness.tolist(),
        mass_matrix=mass.tolist())
