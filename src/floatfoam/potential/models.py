"""Free-decay motion series of a case from the three time-domain models.

* ``linear``: the memoir's linear model M ẍ + C x = 0 (no added mass, no damping);
* ``nonlinear``: the memoir's rigorous equations, exact hydrostatics at every instant
  (:mod:`floatfoam.potential.rigid_body`);
* ``cummins``: Cummins (1962) with A∞ and the radiation memory from the potential-flow
  coefficients (:mod:`floatfoam.potential.radiation`), linear or nonlinear restoring, in the
  DoFs the body is free in, as in the CFD (:func:`floatfoam.dofs.free_dofs`: the case's
  ``[motion] free``, else sway follows a roll, surge a pitch) or those ``dofs`` names.

The body is released from rest at its equilibrium displaced by the case's [release] offsets
(heave of G in m, heel and trim in degrees). The series has the motion-CSV columns
(docs/conventions.md): G's position, the angles in degrees, G's velocity and the angular
velocity in earth axes in deg/s (p, q, r = the Euler-angle rates φ̇, θ̇, 0 for the linear
models).
"""

from __future__ import annotations

import math

import numpy as np

from floatfoam.bodies.geometry import rotation
from floatfoam.dofs import DOFS, HORIZONTAL, free_dofs, released
from floatfoam.errors import InputError, number

MODELS = ("linear", "nonlinear", "cummins")
PERIODS = 10  # default duration: ten of the longest characteristic period
STEPS_PER_PERIOD = 200  # of the shortest characteristic period
# Memory of a series: float64 arrays per time sample at the models' peak, measured with
# tracemalloc on the sphere (linear 29, nonlinear 39, cummins 34 + its kernel's, ~46 at 1.5e5
# samples), rounded up; the cap holds 2.8e6 samples, over 10⁴ periods at 200 steps each, far
# more than a decay test needs, and is fixed rather than the machine's free memory so that the
# same duration is valid on every machine. Under it, the longest series (nonlinear: ~8 min,
# then the analysis) report progress every 10 s (potential.bounded.Heartbeat).
BYTES_PER_SAMPLE = 48 * 8
SERIES_MEMORY = 2**30  # bytes
#: A release is large — Cummins' model beside the CFD takes the exact restoring force
#: (:func:`floatfoam.analysis.cummins.cummins_model`) — where the linear force C x₀ is off the
#: exact hydrostatic one at the release by more than this fraction in a released DoF
#: (:func:`linear_restoring_error`). A period goes as 1/√(restoring): 1 % moves it by 0.5 % at
#: the release and by less as the motion decays, below the coarse CFD's own uncertainty (1–2 %,
#: the grid studies). The cases span 0 (a wall-sided box in heave) to 33 % (lab_sphere_05D's
#: drop of half a diameter); elliptic_cylinder_roll's 10° heel is 3.8 %, the sphere's 10 mm
#: heave 0.3 %.
LARGE_RELEASE = 0.01


def _setup(case):
    from floatfoam.hydrostatics.fluid_domain import check_release
    from floatfoam.hydrostatics.theory import equilibrium, stiffness_matrix
    from floatfoam.potential.resonance import mass_matrix

    eq = equilibrium(case)
    check_release(case, eq)  # the body inside the tank at release, as the CFD needs it
    g_pos = rotation(eq.heel, eq.trim) @ case.cog + np.array([0.0, 0.0, eq.z_c])
    stiffness = stiffness_matrix(case, eq)
    mass = mass_matrix(case.mass, case.gyradius, rotation(eq.heel, eq.trim))
    x0 = np.array([math.radians(case.release[d.release_key]) if d.is_angle
                   else case.release[d.release_key] for d in DOFS])  # heave, roll, pitch
    return eq, g_pos, mass, stiffness, x0


def time_scales(mass: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
    """Characteristic periods 2π √(M_ii / |C_ii|) of the DoFs with a non-zero stiffness."""
    diag_c, diag_m = np.abs(np.diag(stiffness)), np.diag(mass)
    ok = diag_c > 1e-12 * diag_c.max()
    return 2.0 * math.pi * np.sqrt(diag_m[ok] / diag_c[ok])


def decay_series(case, model: str, *, duration: float | None = None, dt: float | None = None,
                 nonlinear_restoring: bool = False, coefficients=None, dofs=None,
                 progress=None) -> dict:
    """Motion series of ``case`` by ``model`` (one of MODELS), in file units (degrees).

    ``dofs`` (cummins only): the DoFs solved (:class:`floatfoam.dofs.Dof` list), default the
    ones a free body moves in after the release; the others stay at equilibrium. ``duration``
    is bounded by the series' memory (:func:`check_duration`); ``progress`` (a
    :class:`~floatfoam.potential.bounded.Heartbeat`) hears how far the integration is.

    Returns a dict with the motion-CSV columns (time, x, y, z, roll, pitch, yaw, u, v, w, p,
    q, r) as arrays, plus ``model`` and, for cummins, ``added_mass_inf`` and ``dofs`` (names).
    """
    if model not in MODELS:
        raise InputError(f"--model {model!r}: valid models are {', '.join(MODELS)}")
    if dofs is not None and model != "cummins":
        raise InputError(f"--dofs applies to --model cummins only (not {model}): the memoir's "
                         "models have no fluid to couple the DoFs")
    eq, g_pos, mass, stiffness, x0 = _setup(case)
    if model != "nonlinear":
        refuse_capsizing(case, eq, stiffness, model)
    scales = time_scales(mass, stiffness)
    given = duration is not None
    if not given:
        duration = PERIODS * float(scales.max()) if len(scales) else 10.0
    if dt is not None:
        dt = number(dt, "dt", minimum=0.0)
    dt = dt or (float(scales.min()) if len(scales) else duration) / STEPS_PER_PERIOD
    check_duration(duration, dt, given=given)
    t = np.arange(0.0, duration + 0.5 * dt, dt)
    out = {"model": model, "time": t, "x": np.full_like(t, g_pos[0]),
           "y": np.full_like(t, g_pos[1]), "u": np.zeros_like(t), "v": np.zeros_like(t)}
    if model == "nonlinear":
        from floatfoam.potential.rigid_body import RigidBody, nonlinear_decay

        _stage(progress, model, t)
        res = nonlinear_decay(RigidBody.from_case(case), g_pos[2] + x0[0], eq.heel + x0[1],
                              eq.trim + x0[2], t, progress=progress)
        deg = math.degrees(1.0)
        out.update(z=res["z"], roll=res["heel"] * deg, pitch=res["trim"] * deg,
                   yaw=res["yaw"] * deg, w=res["w"], p=res["omega_earth"][:, 0] * deg,
                   q=res["omega_earth"][:, 1] * deg, r=res["omega_earth"][:, 2] * deg)
        return out
    if model == "linear":
        from floatfoam.potential.timedomain import linear_decay

        x, v = linear_decay(mass, stiffness, x0, t)
    else:
        x, v, a_inf, chosen = _cummins(case, eq, g_pos, stiffness, x0, t,
                                       nonlinear_restoring, coefficients, dofs, progress)
        out.update(added_mass_inf=a_inf, dofs=[d.name for d in chosen],
                   x=g_pos[0] + x[:, 3], y=g_pos[1] + x[:, 4], u=v[:, 3], v=v[:, 4])
    deg = math.degrees(1.0)
    out.update(z=g_pos[2] + x[:, 0], roll=math.degrees(eq.heel) + x[:, 1] * deg,
               pitch=math.degrees(eq.trim) + x[:, 2] * deg, yaw=np.zeros_like(t),
               w=v[:, 0], p=v[:, 1] * deg, q=v[:, 2] * deg, r=np.zeros_like(t))
    return out


def linear_restoring_error(case) -> float:
    """How far the linear restoring force is off the exact one at the release: the largest
    |F_i(x₀) / (C x₀)_i − 1| over the released DoFs i, with C the hydrostatic stiffness at
    equilibrium and F the exact hydrostatic force of
    :func:`floatfoam.potential.rigid_body.restoring_force` (Cummins' equation's F(x), whose
    Jacobian at x = 0 is C). 0 for a DoF without stiffness (C x₀ = 0: nothing to compare)."""
    from floatfoam.potential.rigid_body import RigidBody, restoring_force

    eq, g_pos, _, stiffness, x0 = _setup(case)
    exact = restoring_force(RigidBody.from_case(case), g_pos[2], eq.heel, eq.trim)(x0)
    linear = stiffness @ x0
    errors = [abs(exact[d.index] / linear[d.index] - 1.0) for d in released(case.release)
              if d.index < 3 and linear[d.index] != 0.0]
    return max(errors, default=0.0)


def _stage(progress, model: str, t) -> None:
    """Tell ``progress`` the integration starts (after every check of the input)."""
    if progress is not None:
        progress.stage(f"{model} model", total=float(t[-1]), unit="s simulated")


def check_duration(duration, dt: float, *, given: bool = True) -> int:
    """The number of samples of a series ``duration`` s long at steps of ``dt`` s; an
    InputError naming --duration, its value, the memory its series would need and the longest
    valid duration when it is not a finite number from one step to what
    :data:`SERIES_MEMORY` holds at :data:`BYTES_PER_SAMPLE` (``given``: by the user, else the
    default, said so)."""
    longest = (SERIES_MEMORY // BYTES_PER_SAMPLE - 1) * dt
    valid = f"valid is {dt:.3g} s (one step) to {longest:.6g} s"
    what = "--duration" if given else "--duration (default: ten of the longest period)"
    if not (isinstance(duration, (int, float)) and not isinstance(duration, bool)
            and math.isfinite(duration) and duration > 0):
        shown = f"{duration:g}" if isinstance(duration, (int, float)) else repr(duration)
        raise InputError(f"{what} {shown}: {valid}")
    if duration < dt:
        raise InputError(f"{what} {duration:g} s: shorter than one time step; {valid}")
    samples = math.floor(duration / dt + 0.5) + 1
    need = samples * BYTES_PER_SAMPLE
    if need > SERIES_MEMORY:
        raise InputError(f"{what} {duration:g} s: {samples:.3g} samples (one every {dt:.3g} s) "
                         f"would need ~{need / 2**30:.3g} GiB at {BYTES_PER_SAMPLE} B each; "
                         f"{valid} (the series within {SERIES_MEMORY / 2**30:g} GiB)")
    return samples


def refuse_capsizing(case, eq, stiffness, model: str) -> None:
    """A linear model follows oscillations only: a released DoF whose theory says it capsizes
    (GM < 0) would grow without bound (e^{t/τ}); refuse, with the verdict and what is valid."""
    from floatfoam.hydrostatics.verdict import verdict

    rgv = case.rho * case.g * eq.immersed.volume
    for entry in released(case.release):
        if entry.index == 0:
            continue  # heave: a floating body's heave stiffness ρgA is positive
        gm = stiffness[entry.index, entry.index] / rgv
        if verdict(gm, case.body.size, eq.immersed.exact) == "capsizes":
            raise InputError(f"--model {model}: {entry.name} capsizes (GM = {gm:.4g} m), and a "
                             "linear model has no oscillation to follow; valid is --model "
                             "nonlinear (exact hydrostatics: it turns the body over to its "
                             "stable attitude)")


def _cummins(case, eq, g_pos, stiffness, x0, t, nonlinear_restoring, coefficients, dofs,
             progress=None):
    """Cummins' equation in the chosen DoFs; returns (x, v) in all five (heave, roll, pitch,
    surge, sway; the others zero), A∞ of the chosen ones and the chosen DoFs."""
    from floatfoam.potential.radiation import radiation_coefficients
    from floatfoam.potential.resonance import mass_matrix
    from floatfoam.potential.timedomain import cummins_decay, retardation_kernel

    chosen = list(dofs) if dofs is not None else free_dofs(
        case.release, chosen=case.settings.motion.free)
    given = "--dofs " + ",".join(d.name for d in chosen) if dofs is not None else \
        f"motion.free = {[d.name for d in chosen]!r}"  # the DoFs' source, for the errors
    missing = [d.name for d in released(case.release) if d not in chosen]
    if missing:
        raise InputError(f"{given}: the release displaces {', '.join(missing)}; valid lists "
                         "include it")
    coef = coefficients or radiation_coefficients(case, eq)
    uncovered = [d.name for d in chosen if not coef.covered[d.index]]
    if uncovered:
        raise InputError(f"{given}: {', '.join(uncovered)} not solved by the potential flow "
                         f"({coef.method}); valid are "
                         + ", ".join(d.name for d in DOFS + HORIZONTAL if coef.covered[d.index]))
    pick = [d.index for d in chosen]
    block = np.ix_(pick, pick)
    mass_all = mass_matrix(case.mass, case.gyradius, rotation(eq.heel, eq.trim),
                           horizontal=True)
    stiffness_all = np.zeros_like(mass_all)
    stiffness_all[:3, :3] = stiffness
    x0_all = np.concatenate([x0, np.zeros(2)])
    spacing = float(coef.omega[1] - coef.omega[0])
    # the kernel is resolved up to t ≈ 2π/Δω by the frequency sampling; it has decayed by then
    kernel_t = t[t <= min(t[-1], 2.0 * math.pi / spacing)]
    kernel = retardation_kernel(coef.omega, coef.damping[(slice(None), *block)], kernel_t)
    restoring = None
    if nonlinear_restoring:
        from floatfoam.potential.rigid_body import RigidBody, restoring_force

        full = restoring_force(RigidBody.from_case(case), g_pos[2], eq.heel, eq.trim)
        hydrostatic = [k for k in pick if k < 3]  # heave, roll, pitch

        def restoring(x_chosen):
            x3 = np.zeros(3)
            where = [pick.index(k) for k in hydrostatic]
            x3[hydrostatic] = x_chosen[where]
            force = np.zeros(len(pick))
            force[where] = full(x3)[hydrostatic]
            return force
    a_inf = coef.added_mass_inf[block]
    _stage(progress, "cummins", t)
    x, v = cummins_decay(mass_all[block], stiffness_all[block], a_inf, kernel_t, kernel,
                         x0_all[pick], t, restoring=restoring, progress=progress)
    x_all = np.zeros((len(t), len(mass_all)))
    v_all = np.zeros_like(x_all)
    x_all[:, pick], v_all[:, pick] = x, v
    return x_all, v_all, a_inf, chosen


def write_series(path, series: dict):
    """Write a series as a motion CSV (docs/conventions.md)."""
    from floatfoam.motion import MOTION_COLUMNS, write_motion

    return write_motion(path, series["time"],
                        **{k: series[k] for k in MOTION_COLUMNS[1:] if k in series})
