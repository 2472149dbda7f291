"""``floatfoam decay-model CASE --model M``: a free-decay series from a time-domain model."""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

from floatfoam import dofs, layout
from floatfoam.cli.common import add_case_arguments, dump_json
from floatfoam.errors import InputError
from floatfoam.potential.models import MODELS


def register(sub) -> None:
    p = sub.add_parser("decay-model", help="free-decay series from the linear, nonlinear "
                                           "(exact hydrostatics) or Cummins model")
    add_case_arguments(p)
    p.add_argument("--model", required=True, choices=MODELS,
                   help="linear (memoir), nonlinear (memoir's rigorous equations) or cummins "
                        "(added mass and radiation memory)")
    p.add_argument("--duration", type=float, default=None, metavar="S",
                   help="simulated time in s (default ten of the longest linear period)")
    p.add_argument("--out", default=None, metavar="CSV",
                   help="motion CSV to write (default build/<case>/decay_<model>.csv, "
                        "with _<dofs> when --dofs is given and _set-<8 hex digits> with "
                        "--set)")
    p.add_argument("--nonlinear-restoring", action="store_true",
                   help="cummins: exact hydrostatic restoring instead of C x")
    p.add_argument("--dofs", default=None, metavar="LIST",
                   help="cummins: the DoFs solved, e.g. heave,roll (roll about G alone) or "
                        "heave,roll,sway; default the case's [motion] free, else those a free "
                        "body moves in after the release (sway with a heel, surge with a "
                        "trim), as in the CFD")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    """--duration is checked, with the release and the depth, by the library
    (:func:`floatfoam.potential.models.decay_series`) before anything is computed or written;
    a long series says how far it is every 10 s
    (:class:`~floatfoam.potential.bounded.Heartbeat`)."""
    if args.nonlinear_restoring and args.model != "cummins":
        raise InputError("--nonlinear-restoring applies to --model cummins only")
    from floatfoam.case import load_case
    from floatfoam.potential.bounded import Heartbeat
    from floatfoam.potential.models import decay_series, write_series

    chosen = dofs.parse_dofs(args.dofs) if args.dofs is not None else None
    case = load_case(args.case, args.overrides)
    with Heartbeat(f"{case.name}: decay-model") as beat:
        series = decay_series(case, args.model, duration=args.duration,
                              nonlinear_restoring=args.nonlinear_restoring, dofs=chosen,
                              progress=beat)
        suffix = ("_nonlinear_restoring" if args.nonlinear_restoring else "") + (
            "_" + "-".join(d.name for d in chosen) if chosen else "")  # e.g. _heave-roll
        if args.overrides:  # another body or release: never the case's own file
            digest = hashlib.sha256("\n".join(args.overrides).encode()).hexdigest()[:8]
            suffix += f"_set-{digest}"
        out = Path(args.out) if args.out else \
            layout.case_build_dir(case.name) / f"decay_{args.model}{suffix}.csv"
        samples = len(series["time"])
        beat.stage(f"writing {samples:,} samples to {out}")
        write_series(out, series)
        beat.stage(f"analysing {samples:,} samples")
        report = {"case": case.name, "model": args.model, "csv": str(out),
                  "solved_dofs": series.get("dofs"),
                  "samples": int(samples), "duration": float(series["time"][-1]),
                  "dofs": _analyse(case, series)}
    if args.json:
        print(dump_json(report))
        return 0
    solved = f" in {', '.join(series['dofs'])}" if series.get("dofs") else ""
    print(f"{case.name}: {args.model} model{solved}, {report['samples']} samples over "
          f"{report['duration']:.4g} s → {out}")
    for dof, res in report["dofs"].items():
        if "error" in res:
            print(f"  {dof}: not analysed ({res['error']})")
        elif "swing" in res:
            stable = res["stable_attitude"]
            where = f"{stable:.0f}°" if stable is not None else "beyond 180°"
            print(f"  {dof}: capsizes (GM = {res['GM']:.4g} m): the nonlinear model turns the "
                  f"body over towards its stable attitude at {where} (GZ curve), swinging "
                  f"between {res['swing'][0]:.1f}° and {res['swing'][1]:.1f}° (undamped)")
        else:
            print(f"  {dof}: period {res['period']:.5g} s, damping ratio "
                  f"{res['damping_ratio']:.4g} (fit of the whole record)")
    return 0


def _analyse(case, series) -> dict:
    """Period and damping ratio of each released DoF, by the decay analysis; for a DoF the
    theory says capsizes, the attitude the nonlinear model turns the body over to."""
    from floatfoam.analysis.decay import analyse_decay
    from floatfoam.hydrostatics.theory import theory_summary

    theory = theory_summary(case)
    out = {}
    for entry in dofs.released(case.release):
        column = entry.column
        scale = math.pi / 180.0 if entry.is_angle else 1.0
        if entry.is_angle and theory.dofs[entry.name].verdict == "capsizes":
            out[column] = _capsized(case, theory, entry, series[column])
            continue
        try:
            summary = analyse_decay(series["time"], series[column] * scale).summary()
            out[column] = {"period": summary["period_mean"],
                           "damping_ratio": summary["damping_ratio"]}
        except (InputError, ValueError, RuntimeError) as err:
            out[column] = {"error": str(err).splitlines()[0]}
    return out


def _capsized(case, theory, entry, angle) -> dict:
    """Where a capsizing body goes: the stable attitude of the GZ curve (the first angle where
    GZ turns from negative to zero or positive, to 1e-9 of the size), and the range the
    nonlinear model swings over once it has left the upright — with no damping it swings about
    that attitude for ever, so the range brackets it."""
    import numpy as np

    from floatfoam.hydrostatics.gz import gz_curve

    angle = np.asarray(angle, dtype=float)
    away = np.nonzero(np.abs(angle - angle[0]) > 0.5 * np.ptp(angle))[0]
    after = angle[away[0]:] if len(away) else angle
    curve = gz_curve(case, 180.0, 1.0)
    tol = 1e-9 * case.body.size
    turns = [float(a) for a, g0, g1 in zip(curve.angles[1:], curve.gz[:-1], curve.gz[1:],
                                           strict=True) if g0 < -tol and g1 >= -tol]
    return {"GM": theory.dofs[entry.name].metacentric_height,
            "stable_attitude": turns[0] if turns else None,
            "swing": [float(after.min()), float(after.max())]}
