"""``floatfoam gz CASE``: righting-arm curve at constant displacement."""

from __future__ import annotations

from pathlib import Path

from floatfoam import layout
from floatfoam.cli.common import add_case_arguments, dump_json


def register(sub) -> None:
    p = sub.add_parser("gz", help="righting-arm (GZ) curve to large heel angles")
    add_case_arguments(p)
    p.add_argument("--max-angle", type=float, default=90.0, metavar="DEG",
                   help="largest heel angle in degrees (0 < DEG ≤ 180, default 90)")
    p.add_argument("--step", type=float, default=1.0, metavar="DEG",
                   help="angle step in degrees (default 1)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="PNG", default=None,
                   help="write the curve as a PNG (default build/<case>/gz.png)")
    p.set_defaults(func=run)


def run(args) -> int:
    """--max-angle and --step are checked by the library
    (:func:`floatfoam.hydrostatics.gz.check_angles`), first; a long curve says how far it is
    every 10 s."""
    from floatfoam.case import load_case
    from floatfoam.hydrostatics.gz import check_angles, gz_curve, plot_gz
    from floatfoam.potential.bounded import Heartbeat

    check_angles(args.max_angle, args.step)
    case = load_case(args.case, args.overrides)
    with Heartbeat(f"{case.name}: gz") as beat:
        curve = gz_curve(case, args.max_angle, args.step, progress=beat)
    plot = Path(args.plot) if args.plot else layout.case_build_dir(case.name) / "gz.png"
    plot.parent.mkdir(parents=True, exist_ok=True)
    plot_gz(curve, plot, title=f"{case.name}: righting arm")
    if args.json:
        print(dump_json({"case": case.name, **curve.as_dict(), "plot": str(plot)}))
        return 0
    print(f"{case.name}: GZ at constant displacement ({case.displacement:.6g} m³)")
    print(f"{'heel (deg)':>10} {'GZ (m)':>12}")
    every = max(1, int(round(5.0 / args.step)))
    for a, g in list(zip(curve.angles, curve.gz, strict=True))[::every]:
        print(f"{a:>10.1f} {g:>12.6g}")
    avs = curve.vanishing_angle
    avs_text = f"beyond {args.max_angle:g}" if avs is None else f"{avs:.2f}"
    print(f"angle of vanishing stability: {avs_text} deg")
    print(f"max GZ {curve.max_gz:.6g} m at {curve.max_gz_angle:g} deg; plot: {plot}")
    return 0
