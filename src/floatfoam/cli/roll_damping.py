"""``floatfoam roll-damping CASE``: Ikeda's components of a 2D section's roll damping at zero
speed (friction, eddy making, wave from floatfoam's potential flow, lift), as B44 and as the
equivalent damping ratio at a roll amplitude (:mod:`floatfoam.damping.ikeda`)."""

from __future__ import annotations

from floatfoam.cli.common import add_case_arguments, dump_json

COMPONENTS = ("friction", "eddy", "wave", "lift", "total")


def register(sub) -> None:
    p = sub.add_parser("roll-damping", help="Ikeda's components of a 2D section's roll damping "
                       "(friction, eddy, wave, lift) at zero speed")
    add_case_arguments(p)
    p.add_argument("--amplitude", type=float, action="append", default=None, metavar="DEG",
                   help="roll amplitude in degrees, repeatable (default the case's release "
                   "heel, else 5)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from floatfoam.case import load_case
    from floatfoam.damping.ikeda import check_amplitude, require_section, roll_damping
    from floatfoam.hydrostatics.theory import equilibrium
    from floatfoam.potential.radiation import potential_summary

    case = load_case(args.case, args.overrides)
    heel = abs(float(case.release.get("heel", 0.0) or 0.0))
    amplitudes = args.amplitude or [heel if heel > 0 else 5.0]
    for a in amplitudes:  # checked before the potential flow is solved
        check_amplitude(a)
    require_section(case)
    eq = equilibrium(case)
    potential = potential_summary(case)
    results = [roll_damping(case, eq, potential, a) for a in amplitudes]
    if args.json:
        print(dump_json({"case": case.name, "method": "Ikeda, zero speed, no bilge keels",
                         "amplitudes": [r.to_dict() for r in results]}))
        return 0
    print("\n".join(format_table(case.name, results)))
    return 0


def format_table(name: str, results) -> list[str]:
    first = results[0]
    s = first.section
    lines = [f"{name}: Ikeda's roll damping at zero speed, at the roll natural frequency with "
             f"added inertia ω = {first.omega:.4g} rad/s (potential flow), I44 + A44 = "
             f"{first.inertia:.4g} kg·m²",
             f"section: B {s['beam']:.4g} m, d {s['draft']:.4g} m, H0 {s['H0']:.3f}, "
             f"σ {s['sigma']:.4f}, OG {s['og']:+.4g} m (G below the waterline +), bilge radius "
             f"{s['bilge_radius']:.4g} m, girth {s['girth']:.4g} m; eddy C_R {first.C_R:.4g}",
             "",
             f"{'amplitude':>9}  " + "  ".join(f"{c + ' B44':>13} {'ζ':>8}" for c in COMPONENTS)]
    for r in results:
        cells = [f"{(r.total if c == 'total' else getattr(r, c)):>13.4g} "
                 f"{r.zeta(r.total if c == 'total' else getattr(r, c)):>8.4f}"
                 for c in COMPONENTS]
        lines.append(f"{r.amplitude_deg:>8.3g}°  " + "  ".join(cells))
    lines.append("B44 in N·m·s/rad for the body's length; ζ = B44 / (2 (I44 + A44) ω); about a "
                 "fixed axis through G, as Ikeda's method is (sway held)")
    if first.wave_zeta_sway_free is not None:
        lines.append(f"wave with sway free as well (a free body): ζ = "
                     f"{first.wave_zeta_sway_free:.4f} (potential flow, roll-sway coupled)")
    lines += [f"note: {flag}" for flag in first.flags]
    return lines
