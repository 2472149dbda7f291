"""The coarse CFD runs of the tests and what they are set beside: a case's run on one rank
(:func:`cfd`; :func:`shared_run` for a run several tests read), Cummins' model in the DoFs the
CFD leaves free (:func:`cummins`, its radiation coefficients computed once per body), and the
decay analysis of a record (:func:`analysed`)."""

import fcntl
import hashlib
import json
import math

import numpy as np
import pytest

from floatfoam.analysis.decay import analyse_decay, decay_dict
from floatfoam.analysis.extrema import first_extrema, parabola_peak, period_from_extrema
from floatfoam.case import load_case
from floatfoam.dofs import dof
from floatfoam.foam.driver import run_case
from floatfoam.hydrostatics.theory import equilibrium, theory_summary
from floatfoam.motion import dof_series, read_motion
from floatfoam.potential.models import decay_series

#: the ranks of make test's CFD runs: one each, two runs at once on the 2 cores
#: (conftest.solvers_share_the_cores). The coarse 2D meshes run 1.4 × faster on 2 ranks than
#: on one (elliptic_cylinder's make-test heave: 22.2 s against 31.9 s with the set-up), so two
#: 1-rank runs side by side make 1.4 × the throughput of 2-rank runs in turn; the tests of the
#: parallel route (decomposePar, mpirun, reconstructPar) ask for 2.
RANKS = 1
#: the ranks of make test-extended's CFD runs, which run one at a time: both cores
ALONE = 2


def cfd(name, tmp_path, overrides=(), ranks=RANKS):
    """The coarse run of case ``name`` on ``ranks``; its case, theory, motion and run info."""
    case = load_case(name, list(overrides))
    result = run_case(case, "coarse", ranks, build_dir=tmp_path)
    motion = read_motion(result.motion_csv)
    assert motion["time"][-1] == pytest.approx(result.info.end_time, abs=1e-6)
    for column in ("z", "roll", "y"):
        assert np.all(np.isfinite(motion[column]))
    return case, theory_summary(case), motion, result.info


def shared_run(name, overrides, runs, ranks):
    """The build folder holding the coarse run of case ``name`` with ``overrides`` on ``ranks``,
    made once for the tests that ask for the same run (``runs``: the session's shared folder,
    conftest.shared_runs): the first to ask runs it, under a lock, and the others find it
    finished. Tests read it, and write nothing into it."""
    key = hashlib.sha256(json.dumps([name, list(overrides), ranks]).encode()).hexdigest()[:12]
    folder = runs / f"{name}-{key}"
    folder.mkdir(parents=True, exist_ok=True)
    with open(runs / f"{name}-{key}.lock", "a") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)  # released when the file closes
        run_case(load_case(name, list(overrides)), "coarse", ranks, build_dir=folder)
    return folder


_COEFFICIENTS = {}


def cummins(case, **options) -> dict:
    """Cummins' model of ``case`` (`floatfoam decay-model --model cummins`) in the DoFs the
    CFD leaves free (sway with a heel: a free body does not roll about G alone); the radiation
    coefficients are computed once per body, mass and fluid (the sphere's three releases share
    them: ~12 s of BEM each)."""
    from floatfoam.potential.radiation import radiation_coefficients

    key = json.dumps([case.raw.get(t) for t in ("body", "mass", "fluid", "potential")],
                     sort_keys=True, default=str)
    if key not in _COEFFICIENTS:
        _COEFFICIENTS[key] = radiation_coefficients(case, equilibrium(case))
    return decay_series(case, "cummins", coefficients=_COEFFICIENTS[key], **options)


def potential_period(case, name: str) -> float:
    """Damped period of DoF ``name`` by Cummins' model (potential-flow added mass and
    radiation damping)."""
    series = cummins(case)
    entry = dof(name)
    scale = math.pi / 180.0 if entry.is_angle else 1.0
    return analyse_decay(series["time"], series[entry.column] * scale).summary()["period_mean"]


def extrema(t, x, count: int):
    """Times of the first ``count`` extrema of a smooth record (sign changes of its slope)."""
    turns = first_extrema(x, count)
    assert len(turns) >= count, f"only {len(turns)} extrema"
    return t[turns]


def refined_extrema(t, x, count: int) -> np.ndarray:
    """Times of the first ``count`` extrema of a smooth record, each the vertex of the
    parabola through its sample and the two beside it (analysis.extrema.parabola_peak: a
    step of up to 10 ms is up to 3 % of the sphere's half period)."""
    turns = first_extrema(x, count)[:count]
    assert len(turns) >= count, f"only {len(turns)} extrema"
    return np.array([parabola_peak(t, x, k)[0] for k in turns])


def early_period(t, x, count: int = 4) -> float:
    """The period from the first ``count`` extrema (analysis.extrema). A heavily damped record
    (ζ ≈ 0.2) leaves the noise after 1.5 cycles, too few for the decay fit; the extrema still
    time its first cycles."""
    turns = first_extrema(x, count)
    assert len(turns) >= count, f"only {len(turns)} extrema"
    return period_from_extrema(t, turns)


def first_sway(t, y, period: float) -> float:
    """G's largest sideways excursion from its release position over the first roll period."""
    first = t <= period
    excursion = y[first] - y[0]
    return float(excursion[np.argmax(np.abs(excursion))])


# Sway with the roll: G's first swing within 10 % of the coupled model. Measured on the coarse
# meshes, make test's records and step: ellipse −7.57 mm against −7.65 mm (−1 %), hyperbola
# −9.39 against −9.07 mm (+4 %), ellipsoid (3D) −7.93 against −8.34 mm (−5 %; by 0.35 s).
# On the 2D studies' levels (make validate, relaxation 1.0, whole records; coarse / medium /
# fine): ellipse −7.47 / −7.28 / −7.31 mm (fine −4 %), hyperbola −9.20 / −9.33 / −9.13 mm
# (+0.7 %); the mesh moves the swing by ≤ 2.5 %, so 10 % is for the 3D ellipsoid's −5 %,
# whose finer level was not run. Below 1 mm (the box, whose G is near its roll centre: 0.38
# against 0.39 mm) the swing is within the CFD's drift and is not checked.
SWAY_TOLERANCE, SWAY_CHECKED = 0.10, 1e-3


def analysed(motion, name: str) -> dict:
    """The decay analysis of DoF ``name``: its summary (period, damping ratio, cycles) and
    the fitted equilibrium level."""
    t, x = dof_series(motion, name)
    result = analyse_decay(t, x)
    return {**result.summary(), "equilibrium": decay_dict(result)["equilibrium"]}
