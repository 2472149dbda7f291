"""``floatfoam theory CASE``: the linear hydrostatic theory of a case."""

from __future__ import annotations

from floatfoam.cli.common import add_case_arguments, dump_json

ROWS = [
    ("draft", "draft", "m"),
    ("displaced_volume", "displaced volume V", "m³"),
    ("waterplane_area", "waterplane area A", "m²"),
    ("KB", "KB", "m"),
    ("KG", "KG", "m"),
    ("BM_roll", "BM roll", "m"),
    ("BM_pitch", "BM pitch", "m"),
    ("GM_roll", "GM roll", "m"),
    ("GM_pitch", "GM pitch", "m"),
    ("heave_period", "heave period", "s"),
    ("roll_period", "roll period", "s"),
    ("pitch_period", "pitch period", "s"),
    ("verdict_roll", "roll verdict", ""),
    ("verdict_pitch", "pitch verdict", ""),
]


def register(sub) -> None:
    p = sub.add_parser("theory", help="hydrostatics, stability and linear periods of a case")
    add_case_arguments(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from floatfoam.case import load_case
    from floatfoam.hydrostatics.theory import theory_summary

    case = load_case(args.case, args.overrides)
    summary = theory_summary(case).to_dict()
    if args.json:
        print(dump_json(summary))
        return 0
    print(format_summary(summary))
    return 0


def format_summary(s: dict) -> str:
    """Readable table of a theory summary, with the memoir's printed values beside."""
    length = s["section_length"]
    per = f" (2D section, per length L = {length:g} m)" if length else ""
    eq = s["equilibrium"]
    lines = [f"{s['case']}: {s['body']}{per}, mass {s['mass']:.6g} kg",
             f"equilibrium: heel {eq['heel']:.4g}°, trim {eq['trim']:.4g}°, "
             f"G at z = {eq['z_G']:.6g} m; {'closed form' if s['exact'] else 'numeric'}",
             "", f"{'quantity':<20} {'exact theory':>14} {'memoir':>15}  unit",
             "-" * 58]
    memoir = s.get("memoir") or {}
    for key, label, unit in ROWS:
        value = s[key]
        printed = memoir.get(key)
        lines.append(f"{label:<20} {_fmt(value):>14} {_fmt(printed, blank=True):>15}  {unit}")
    if memoir.get("source") == "reconstructed":
        lines.append("memoir: the memoir's method (its printed formulas are not recoverable from "
                     "the stored copies; see docs/memoir.md)")
    elif not memoir:
        lines.append("memoir: this body is not among the memoir's")
    return "\n".join(lines)


def _fmt(value, blank=False) -> str:
    if value is None:
        return "" if blank else "—"
    if isinstance(value, str):
        return value
    return f"{value:.6g}"
