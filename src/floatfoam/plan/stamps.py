"""What a run is of: the interFoam it runs (:func:`solver_path`), the digest of everything its
result depends on (:func:`settings_digest`), and the stamp in its folder that records it
(:func:`write_stamp`, read by :func:`stamp_words`, :func:`stamp_of`, :func:`stamped_with`). The
driver writes the stamp before anything else; the analysis reads it to leave out runs of other
settings than the case's today."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from floatfoam import fields, layout, settings
from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.plan import zone
from floatfoam.tank import Pose


def settings_digest(case: Case, level: str, *, divisor: int = 1, morphing: float = 1.0,
                    release: Pose | None = None) -> str:
    """Hash of what a run depends on: the case file, the values it resolves to with the
    defaults (a changed default makes every run made at the former one another run's), the
    bulk's Courant limit and the coupling's tolerance the mesh's kind resolves to
    (:func:`floatfoam.plan.release.bulk_courant`, :func:`~floatfoam.plan.release.
    coupling_tolerance`) and the mesh motion (:func:`_resolved_motion`), the level, the
    time-step divisor and morphing factor of a study's run, the shared dictionaries, the
    body's velocity condition and the coupling's compensation (:data:`BODY_VELOCITY`,
    :data:`COMPENSATION`) and the solver binary; an STL body's file. Not
    the case's words ([case] title, description, and the name of the case it extends: its
    tables are in), nor its [reference] measurements: adding a measurement must not make a
    finished run look foreign; nor run.end_time, which says only how far the run goes (its
    own is in its info.json: :mod:`floatfoam.foam.extension`). ``release``: the body's pose
    at release when already solved (:func:`floatfoam.plan.release.release_state`)."""
    from floatfoam.plan.kind import kind_of
    from floatfoam.plan.release import bulk_courant, coupling_tolerance

    stamp = fields.stamped(case.settings)
    release = _release_pose(case, release)
    if release is not None:
        # the values the mesh's kind resolves to; a tolerance of 0 (the iterations' fixed
        # count, and a body held still's) is left out
        kind = kind_of(case, release)
        if stamp["run"].get("max_courant") is None:
            stamp["run"]["max_courant"] = bulk_courant(case, kind)
        stamp["run"].pop("coupling_tolerance", None)
        tolerance = coupling_tolerance(case, kind)
        if tolerance:
            stamp["run"]["coupling_tolerance"] = tolerance
    raw = {table: values for table, values in case.raw.items() if table != "reference"}
    raw["case"] = {k: v for k, v in raw.get("case", {}).items()
                   if k not in ("title", "description", "extends")}
    for table in settings.TABLES:  # a key the stamp leaves out (0 prism layers, written out)
        if isinstance(raw.get(table), dict):  # is left out of the file's copy too
            kept = _stamped_keys(raw[table], stamp.get(table, {}))
            if kept or not raw[table]:
                raw[table] = kept
            else:  # emptied by it: as if never written
                del raw[table]
    run_table = raw.get("run")
    if isinstance(run_table, dict) and "coupling_tolerance" in run_table:
        # the tolerance resolved is in the stamp: a case that sets its kind's default is the
        # run at the default
        del run_table["coupling_tolerance"]
        if not run_table:
            del raw["run"]
    resolved = {"settings": stamp, "release": case.release,
                "mass": case.mass, "cog": case.cog, "gyradius": case.gyradius, "rho": case.rho,
                "nu": case.nu, "g": case.g, "depth": case.depth, "rho_air": case.rho_air,
                "nu_air": case.nu_air, "mesh_motion": _resolved_motion(case, release)}
    run = {"case": raw, "resolved": resolved, "level": level, "divisor": divisor,
           "morphing": morphing}
    digest = hashlib.sha256(json.dumps(run, sort_keys=True, default=_plain).encode())
    for path in sorted(layout.COMMON_DIR.rglob("*")):
        if path.is_file():
            digest.update(path.read_bytes())
    body = case.raw.get("body", {})
    if body.get("shape") == "stl":  # the file's triangles, not its name alone
        digest.update((Path(case.path) / body["path"]).read_bytes())
    digest.update(f"{BODY_VELOCITY} {COMPENSATION} {COMPENSATION_FORM}".encode())
    digest.update(str(solver_path(case, check=False)).encode())
    return digest.hexdigest()[:16]


def _release_pose(case: Case, release: Pose | None) -> Pose | None:
    """The body's pose at release: ``release``, or solved from the case (its equilibrium);
    None when the case's release or tank is refused (so is its run)."""
    if release is not None:
        return release
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.plan.release import release_state

    try:
        return release_state(case, equilibrium(case))["pose"]
    except InputError:
        return None


def _resolved_motion(case: Case, release: Pose | None) -> list | None:
    """How the run's mesh follows the body once "auto" and the distances' defaults are
    resolved (:func:`floatfoam.plan.zone.of_case`): ["laplacian"], or ["distances", inner,
    outer], and "wedge" after them for a body given by triangles meshed as one; a rule that
    resolves them otherwise makes the runs made before it foreign. None when the case's
    release or tank is refused (so is its run)."""
    from floatfoam.plan.kind import kind_of

    release = _release_pose(case, release)
    if release is None:
        return None
    try:
        mesh = zone.of_case(case, release)
        # a body given by triangles may be found to be of revolution and meshed as a wedge:
        # its run then is not the 3D one made of the same case file
        wedge = ["wedge"] if case.body.given_by_triangles and \
            kind_of(case, release) == "wedge" else []
    except InputError:
        return None
    if mesh.motion != "distances":
        return [mesh.motion, *wedge]
    return [mesh.motion, float(f"{mesh.inner:.9g}"), float(f"{mesh.outer:.9g}"), *wedge]


def _stamped_keys(values: dict, stamped: dict) -> dict:
    """A settings table of the case file with only the keys its stamp keeps (nested tables
    alike; one emptied by that is left out, one written empty is kept)."""
    kept = {}
    for key, value in values.items():
        if key not in stamped:
            continue
        if isinstance(value, dict):
            inner = _stamped_keys(value, stamped[key])
            if value and not inner:
                continue
            value = inner
        kept[key] = value
    return kept


def _plain(value):
    """JSON for the digest: arrays as lists (their repr would wrap and elide), else str."""
    return value.tolist() if hasattr(value, "tolist") else str(value)


def stamp_of(run_dir: Path) -> str | None:
    """The settings digest a run directory was stamped with (None without a stamp)."""
    return stamp_words(run_dir)[0]


def stamp_words(run_dir: Path) -> tuple[str | None, str | None]:
    """A run directory's stamp: the settings digest and the MPI ranks it was made with (None
    for each it does not hold)."""
    stamp = _stamp_path(run_dir)
    digest, ranks = ((stamp.read_text().split() if stamp.exists() else []) + [None, None])[:2]
    return digest, ranks


def write_stamp(run_dir: Path, digest: str, ranks: int) -> None:
    """Stamp a new run directory with its settings digest and its MPI ranks (the driver does
    it before anything else)."""
    stamp = _stamp_path(run_dir)
    stamp.parent.mkdir(parents=True)
    stamp.write_text(f"{digest} {ranks}\n")


def _stamp_path(run_dir: Path) -> Path:
    return Path(run_dir) / layout.MARKERS / "settings"


def stamped_with(case: Case, level: str, run_dir: Path, divisor: int = 1,
                 morphing: float = 1.0) -> bool | None:
    """Whether the run directory's settings stamp is that of ``case`` run at ``level`` with
    its time steps divided by ``divisor`` and its mesh motion scaled by ``morphing`` (the
    case as the command gives it: a study's run stamps its own digest); None when it has no
    stamp (the driver writes it before anything else: a folder without one was not made by a
    run)."""
    if not _stamp_path(run_dir).exists():
        return None
    digest = stamp_of(run_dir)
    return digest is not None and digest == settings_digest(case, level, divisor=divisor,
                                                            morphing=morphing)


def solver_path(case: Case, check: bool = True) -> Path:
    """The interFoam to run: floatfoam's rebuilt one unless [run] solver names another.
    ``check``: refuse one that does not exist (a digest, which only names it, does not)."""
    path = Path(case.settings.run.solver or layout.SOLVER)
    path = path if path.is_absolute() else layout.ROOT / path
    if check and not path.is_file():
        raise InputError(f"run.solver = {str(path)!r} does not exist; run `make setup` to build "
                         "floatfoam's interFoam (scripts/build_solver.sh)")
    return path


#: floatfoam's velocity condition of the body (src/solver/): the rigid body's velocity at the
#: step's end, where v1912's movingWallVelocity gives the wall's over the step, half a step
#: late (docs/openfoam-v1912.md)
BODY_VELOCITY = "bodyVelocity"

#: floatfoam's six-DoF restraint that compensates the coupling's correctors by the body's
#: added mass and takes its added-mass force at the step's end (src/solver/, docs/coupling.md)
COMPENSATION = "addedMassCompensation"

#: the acceleration the restraint gives a corrector (A: half the added mass at infinite
#: frequency; q_last, q_step: the corrector before's and the step before's): a run made with
#: another is another run's
COMPENSATION_FORM = "q = (M + 2A)^-1 (F + A (q_last + q_step))"


def solver_has(case: Case, name: str) -> bool:
    """Whether the interFoam to run (:func:`solver_path`) has floatfoam's ``name``
    (:data:`BODY_VELOCITY`, :data:`COMPENSATION`); another build (``run.solver``) may lack
    them: the body then takes v1912's own conditions (``movingWallVelocity``,
    ``sixDoFRigidBodyDisplacement``), uncompensated. A solver that is not there has none."""
    path = solver_path(case, check=False)
    if not path.is_file():
        return False
    with open(path, "rb") as binary:
        return name.encode() in binary.read()


def has_body_velocity(case: Case) -> bool:
    """Whether the interFoam to run has floatfoam's :data:`BODY_VELOCITY`."""
    return solver_has(case, BODY_VELOCITY)


#: floatfoam's gravity term at the free surface's height (src/solver/interfaceGravity.H), which
#: PIMPLE's ``interfaceGravity`` (``run.interface_gravity``) switches on
INTERFACE_GRAVITY = "interfaceGravity"


def check_interface_gravity_solver(case: Case) -> None:
    """InputError when ``run.interface_gravity`` is on and the interFoam to run lacks it
    (another build, ``run.solver``, or floatfoam's own built before it): it would ignore the
    setting."""
    if not case.settings.run.interface_gravity or solver_has(case, INTERFACE_GRAVITY):
        return
    raise InputError(f"run.interface_gravity = true: run.solver = "
                     f"{str(solver_path(case))!r} lacks floatfoam's gravity term at the free "
                     "surface (src/solver/interfaceGravity.H): valid is floatfoam's interFoam "
                     "(`make setup` builds it) or run.interface_gravity = false")


def check_layered_solver(case: Case) -> None:
    """InputError when the interFoam to run (:func:`solver_path`) lacks floatfoam's layered
    motion, which the run's mesh takes: another build (``run.solver``), or floatfoam's own
    built before it (``make setup`` builds it again)."""
    path = solver_path(case)
    if solver_has(case, zone.LAYERED_SOLVER):
        return
    raise InputError(f"run.solver = {str(path)!r} lacks floatfoam's layered mesh motion "
                     "(src/solver/), which a body free in heave alone takes: valid is "
                     "floatfoam's interFoam (`make setup` builds it) or --set "
                     "run.mesh_motion='\"laplacian\"'")
