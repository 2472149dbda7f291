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
    ("KG_limit_roll", "KG limit (roll)", "m"),
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
    """Readable table of a theory summary: the exact theory, the memoir's formulas corrected
    (its method derived again) and as printed, side by side; a line flags a printed verdict
    that differs from the exact one."""
    length = s["section_length"]
    per = f" (2D section, per length L = {length:g} m)" if length else ""
    eq = s["equilibrium"]
    columns = [s, s.get("memoir") or {}, s.get("memoir_printed") or {}]
    lines = [f"{s['case']}: {s['body']}{per}, mass {s['mass']:.6g} kg",
             f"equilibrium: heel {eq['heel']:.4g}°, trim {eq['trim']:.4g}°, "
             f"G at z = {eq['z_G']:.6g} m; {'closed form' if s['exact'] else 'numeric'}",
             *([f"body frame: origin at ({', '.join(f'{v:.6g}' for v in s['file_origin'])}) m "
                "in the STL (its volume's centroid in x, y; mid-height), mass.cog moved with it"]
               if s.get("file_origin") else []),
             "", f"{'quantity':<20} {'exact theory':>14} {'memoir':>12} {'memoir':>12}  unit",
             f"{'':<20} {'':>14} {'(corrected)':>12} {'(printed)':>12}",
             "-" * 68]
    for key, label, unit in ROWS:
        cells = [_fmt(_value(col, key), blank=i > 0) for i, col in enumerate(columns)]
        lines.append(f"{label:<20} {cells[0]:>14} {cells[1]:>12} {cells[2]:>12}  {unit}")
    lines.extend(_memoir_notes(s, columns[1], columns[2]))
    return "\n".join(lines)


def _value(column: dict, key: str):
    """A cell: ``key`` of the column; the KG limit of roll is KG + GM_roll unless the column
    gives its own (the printed criterion)."""
    if key == "KG_limit_roll" and key not in column:
        kg, gm = column.get("KG"), column.get("GM_roll")
        return None if kg is None or gm is None else kg + gm
    return column.get(key)


def _memoir_notes(s: dict, corrected: dict, printed: dict) -> list[str]:
    if not corrected and not printed:
        return ["memoir: this body is not among the memoir's"]
    lines = ["memoir (corrected): its method derived again (docs/memoir.md); equals the print "
             "where that is right"]
    if printed:
        errata = printed.get("errata") or []
        state = (f"errata used: {', '.join(errata)}" if errata
                 else "every formula used is right")
        lines.append(f"memoir (printed): {printed['pages']}; {state} (docs/memoir.md, errata)")
        if printed.get("verdict_roll") != s["verdict_roll"]:
            lines.append(f"memoir as printed: {printed['verdict_roll']} — the exact theory says "
                         f"{s['verdict_roll']} ({printed['criterion']} criterion, KG limit "
                         f"{printed['KG_limit_roll']:.6g} m; see docs/memoir.md errata)")
    return lines


def _fmt(value, blank=False) -> str:
    if value is None:
        return "" if blank else "—"
    if isinstance(value, str):
        return value
    return f"{value:.6g}"
