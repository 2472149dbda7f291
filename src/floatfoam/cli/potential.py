"""``floatfoam potential CASE``: natural periods with added mass and radiation damping."""

from __future__ import annotations

from pathlib import Path

from floatfoam import dofs, layout
from floatfoam.cli.common import add_case_arguments, dump_json
from floatfoam.errors import InputError


def register(sub) -> None:
    p = sub.add_parser("potential", help="added mass, radiation damping and natural periods "
                                         "with added mass (potential flow, Capytaine / 2D)")
    add_case_arguments(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", nargs="?", const="", default=None, metavar="PNG",
                   help="write A(ω), B(ω) as a PNG (default build/<case>/potential.png)")
    p.add_argument("--panels", type=int, default=None, metavar="N",
                   help="panels on the wetted surface (default 800 in 3D, 64 for a section)")
    p.add_argument("--no-cache", action="store_true",
                   help="solve again even if build/potential holds the result")
    p.set_defaults(func=run)


def run(args) -> int:
    from floatfoam.case import load_case
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.potential.radiation import potential_summary, radiation_coefficients

    if args.panels is not None and not 8 <= args.panels <= 20000:
        raise InputError(f"--panels {args.panels}: valid is an integer from 8 to 20000")
    case = load_case(args.case, args.overrides)
    eq = equilibrium(case)
    coef = radiation_coefficients(case, eq, panels=args.panels, cache=not args.no_cache)
    result = potential_summary(case, coefficients=coef)
    summary = result.to_dict()
    if args.plot is not None:
        from floatfoam.potential.plot import plot_coefficients

        path = Path(args.plot) if args.plot else layout.case_build_dir(case.name) / "potential.png"
        summary["plot"] = str(plot_coefficients(coef, path, summary=result,
                                                title=f"{case.name}: radiation coefficients"))
    if args.json:
        print(dump_json(summary))
        return 0
    print(format_summary(summary))
    return 0


def format_summary(s: dict) -> str:
    """Readable table of :func:`floatfoam.potential.radiation.potential_summary`."""
    depth = "deep water" if s["depth"] is None else f"depth {s['depth']:g} m"
    per = f", for the section's length L = {s['section_length']:g} m" \
        if s["section_length"] else ""
    f = s["frequencies"]
    lines = [f"{s['case']}: {s['method']}, {s['panels']} panels, {depth}, {f['count']} "
             f"frequencies {f['min']:.4g}–{f['max']:.4g} rad/s{per}", "",
             f"{'dof':<6} {'T no A (s)':>11} {'T with A (s)':>13} {'A(ω_n)':>11} "
             f"{'B(ω_n)':>11} {'ζ':>8}  units of A, B", "-" * 78]
    for entry in dofs.DOFS:
        dof, unit_a, unit_b = entry.name, entry.inertia_unit, entry.damping_unit
        lines.append(f"{dof:<6} {_fmt(s[f'{dof}_period_no_added_mass']):>11} "
                     f"{_fmt(s[f'{dof}_period']):>13} {_fmt(s[f'{dof}_added_mass']):>11} "
                     f"{_fmt(s[f'{dof}_radiation_damping']):>11} "
                     f"{_fmt(s[f'{dof}_damping_ratio'], 4):>8}  {unit_a}, {unit_b}")
    for dof, partner in dofs.PARTNER.items():
        if s.get(f"{dof}_coupled_period") is not None:
            lines.append(f"{dof} with {partner} free (a free body): period "
                         f"{s[f'{dof}_coupled_period']:.5g} s, ζ "
                         f"{s[f'{dof}_coupled_damping_ratio']:.4g}")
    lines.append("— : the DoF does not oscillate (or, pitch of a 2D section, is not solved)")
    lines += [f"note: {n}" for n in s["notes"]]
    if "plot" in s:
        lines.append(f"plot: {s['plot']}")
    return "\n".join(lines)


def _fmt(value, digits: int = 5) -> str:
    return "—" if value is None else f"{value:.{digits}g}"
