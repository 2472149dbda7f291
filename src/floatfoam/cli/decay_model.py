"""``floatfoam decay-model CASE --model M``: a free-decay series from a time-domain model."""

from __future__ import annotations

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
                   help="motion CSV to write (default build/<case>/decay_<model>.csv)")
    p.add_argument("--nonlinear-restoring", action="store_true",
                   help="cummins: exact hydrostatic restoring instead of C x")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    if args.duration is not None and not (math.isfinite(args.duration) and args.duration > 0):
        raise InputError(f"--duration {args.duration:g}: valid is a positive time in seconds")
    if args.nonlinear_restoring and args.model != "cummins":
        raise InputError("--nonlinear-restoring applies to --model cummins only")
    from floatfoam.case import load_case
    from floatfoam.potential.models import decay_series, write_series

    case = load_case(args.case, args.overrides)
    series = decay_series(case, args.model, duration=args.duration,
                          nonlinear_restoring=args.nonlinear_restoring)
    suffix = "_nonlinear_restoring" if args.nonlinear_restoring else ""
    out = Path(args.out) if args.out else \
        layout.case_build_dir(case.name) / f"decay_{args.model}{suffix}.csv"
    write_series(out, series)
    report = {"case": case.name, "model": args.model, "csv": str(out),
              "samples": int(len(series["time"])), "duration": float(series["time"][-1]),
              "dofs": _analyse(case, series)}
    if args.json:
        print(dump_json(report))
        return 0
    print(f"{case.name}: {args.model} model, {report['samples']} samples over "
          f"{report['duration']:.4g} s → {out}")
    for dof, res in report["dofs"].items():
        if "error" in res:
            print(f"  {dof}: not analysed ({res['error']})")
        else:
            print(f"  {dof}: period {res['period']:.5g} s, damping ratio "
                  f"{res['damping_ratio']:.4g} (fit of the whole record)")
    return 0


def _analyse(case, series) -> dict:
    """Period and damping ratio of each released DoF, by the decay analysis."""
    from floatfoam.analysis.decay import analyse_decay

    out = {}
    for entry in dofs.released(case.release):
        column = entry.column
        scale = math.pi / 180.0 if entry.is_angle else 1.0
        try:
            summary = analyse_decay(series["time"], series[column] * scale).summary()
            out[column] = {"period": summary["period_mean"],
                           "damping_ratio": summary["damping_ratio"]}
        except (InputError, ValueError, RuntimeError) as err:
            out[column] = {"error": str(err).splitlines()[0]}
    return out
