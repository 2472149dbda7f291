"""``floatfoam analyse RUN_OR_CSV``: period and damping of one free-decay record (RUN: a run
folder or a CASE with ``--level``, :func:`floatfoam.cli.common.resolve_run`).

The DoF is ``--dof``'s, else the DoF(s) the run released, else, for a CSV that is no run's,
the one that moves most (:func:`floatfoam.analysis.released.choose`, which also refuses a DoF
that does not move above the noise). With ``--json`` it prints one object per DoF (keys in
:func:`floatfoam.analysis.decay.decay_dict`, with ``dof`` and ``dof_from``, why that DoF;
confidence intervals are 95 % [lo, hi] pairs), a list of them for a run that released
several; otherwise a readable table per DoF. ``--extinction`` (``--cubic``) adds the record's
extinction curve, an ``extinction`` object in the JSON (keys in
:meth:`floatfoam.analysis.extinction.ExtinctionCurve.to_dict`).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from floatfoam import dofs
from floatfoam.cli.common import add_run_argument, dump_json, resolve_run


def add_arguments(parser) -> None:
    """The analyse command's arguments (shared with postprocess/analyse.py)."""
    add_run_argument(parser, csv=True)
    parser.add_argument("--dof", choices=list(dofs.NAMES), default=None,
                        help="degree of freedom to analyse (default: the DoF(s) the run "
                             "released, from its .floatfoam/info.json; for a CSV that is no "
                             "run's, the one that moves most relative to its scale, 1 rad or "
                             "the body's size)")
    parser.add_argument("--equilibrium", metavar="VALUE",
                        help="level the motion decays to, in file units (m, deg), or 'tail'; "
                             "default: fitted")
    parser.add_argument("--drift", action="store_true", help="fit a linear drift of the mean")
    parser.add_argument("--quadratic", action="store_true",
                        help="fit linear + quadratic damping (integrates the ODE; slower)")
    parser.add_argument("--extinction", action="store_true",
                        help="also the extinction curve (ITTC 7.5-02-07-04.5): the decrement "
                             "per half swing against the mean amplitude, fitted a φ_m + "
                             "b φ_m², ITTC's p1, p2, the equivalent damping ratio and the "
                             "quasi-linear ζ1 + ζ2 φ_m; with --plot also <PNG stem>-extinction"
                             ".png")
    parser.add_argument("--cubic", action="store_true",
                        help="add the cubic term c φ_m³ (p3) to the extinction fit (implies "
                             "--extinction)")
    parser.add_argument("--start", type=float, metavar="T",
                        help="ignore the record before time T (s)")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object (a list of one per DoF for a run that "
                             "released several)")
    parser.add_argument("--plot", metavar="PNG",
                        help="write the decay figure to PNG (several DoFs: PNG's name with "
                             "-<dof> before its suffix); a run of a case is drawn "
                             "beside Cummins' model and the case's measurement, as in the "
                             "report")


def register(sub) -> None:
    p = sub.add_parser("analyse", help="period and damping of a free-decay motion record")
    add_arguments(p)
    p.set_defaults(func=run)


def _equilibrium(text: str | None, scale: float):
    from floatfoam.errors import InputError

    if text is None or text == "tail":
        return text
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"--equilibrium {text!r}: valid is a number (m or deg) or 'tail'"
                         ) from None
    if not math.isfinite(value):
        raise InputError(f"--equilibrium {text}: valid is a finite number (m or deg) or 'tail'")
    return value / scale


def run(args) -> int:
    from floatfoam.analysis.released import choose
    from floatfoam.errors import InputError
    from floatfoam.motion import motion_path, read_motion

    path = motion_path(resolve_run(args.run, args.level, csv=True))
    motion = read_motion(path)
    choice = choose(path, motion, args.dof)
    if choice.released is not None and args.dof and args.dof not in choice.released:
        print(f"note: {path.parent} released {', '.join(choice.released)}, not {args.dof}: "
              f"its {args.dof} follows the released motion and is no free decay",
              file=sys.stderr)
    several = len(choice.dofs) > 1
    if several and args.equilibrium not in (None, "tail"):
        raise InputError(f"--equilibrium {args.equilibrium}: a level in one DoF's units, and "
                         f"the run released {', '.join(choice.dofs)}; valid is --dof with it, "
                         "or 'tail'")
    analysed = [_analyse(args, path, motion, dof, choice.reason) for dof in choice.dofs]
    results = []  # every DoF analysed (and refused, if it is) before any figure is written
    for dof, (data, drawn) in zip(choice.dofs, analysed, strict=True):
        if args.plot:
            _draw(args, path, dof, data, drawn, _plot_path(args.plot, dof) if several
                  else args.plot)
        results.append(data)
    if args.json:
        print(dump_json(results if several else results[0]))
    else:
        print("\n\n".join(format_result(data) for data in results))
    return 0


def _plot_path(plot: str | None, dof: str) -> str | None:
    """The figure of one of several DoFs: ``--plot``'s name with ``-<dof>`` before its suffix."""
    if plot is None:
        return None
    given = Path(plot)
    return str(given.with_name(f"{given.stem}-{dof}{given.suffix}"))


def _analyse(args, path, motion: dict, dof: str, reason: str) -> tuple[dict, tuple]:
    """The decay analysis of one DoF of the record, as :func:`decay_dict` plus its source (and
    its extinction curve when asked), and what its figures are drawn from."""
    from floatfoam.analysis.decay import analyse_decay, decay_dict
    from floatfoam.motion import dof_series, file_unit

    scale, unit = file_unit(dof)
    time, value = dof_series(motion, dof)
    result = analyse_decay(time, value, equilibrium=_equilibrium(args.equilibrium, scale),
                           drift=args.drift, quadratic=args.quadratic, t_start=args.start,
                           units=(scale, unit), name=dofs.dof(dof).column)
    data = {"source": str(path), **decay_dict(result, scale=scale, unit=unit, dof=dof),
            "dof_from": reason}
    curve = None
    if args.extinction or args.cubic:
        from floatfoam.analysis.extinction import extinction_curve

        curve = extinction_curve(result, cubic=args.cubic, name=f"{dof} of {path}")
        data["extinction"] = curve.to_dict(unit=unit, scale=scale)
    return data, (time, value, result, curve, scale, unit)


def _draw(args, path, dof: str, data: dict, drawn: tuple, plot: str) -> None:
    """The decay figure (and the extinction figure) of one analysed DoF, their paths in
    ``data``."""
    from floatfoam.analysis.overlay import run_overlay
    from floatfoam.analysis.plots import plot_decay
    from floatfoam.analysis.released import run_folder

    time, value, result, curve, scale, unit = drawn
    overlay, why = None, ""
    if run_folder(path) is not None:  # a run of a case: Cummins' model beside it
        overlay, why = run_overlay(run_folder(path), dof, float(time[-1]), drift=args.drift,
                                   quadratic=args.quadratic, t_start=args.start)
    if why:
        print(f"note: the figure has no model beside the record: {why}", file=sys.stderr)
    data["plot"] = str(plot_decay(plot, time, value, result, overlay=overlay, scale=scale,
                                  unit=unit, title=f"{path}: {dof} decay"))
    if curve is not None:
        from floatfoam.analysis.plots import plot_extinction

        given = Path(plot)
        data["extinction"]["plot"] = str(plot_extinction(
            given.with_name(f"{given.stem}-extinction{given.suffix}"), curve, scale=scale,
            unit=unit, title=f"{path}: {dof} extinction curve"))


def _ci(pair) -> str:
    return f"[{pair[0]:.5g}, {pair[1]:.5g}]"


def format_result(d: dict) -> str:
    """Readable summary of :func:`decay_dict` output."""
    from floatfoam.analysis.decay import log_decrement_damping

    u = d["unit"]
    chosen = "" if d.get("dof_from", "--dof") == "--dof" else f" ({d['dof_from']})"
    lines = [f"{d['source']}: {d['dof']} ({u}){chosen}, model {d['model']}",
             f"mean level {d['equilibrium']:.6g} {u} ({d['equilibrium_source']}), drift "
             f"{d['drift']:.3g} {u}/s; initial amplitude {d['amplitude']:.4g} {u}",
             f"usable: t = {d['t_first']:g} … {d['t_usable']:.4g} s, {d['n_cycles']:.3g} cycles; "
             f"noise rms {d['noise_rms']:.3g} {u}, fit residual rms {d['residual_rms']:.3g} {u}",
             "",
             f"{'':24}{'value':>12}  95 % interval",
             f"{'damped period T_d (s)':<24}{d['period_mean']:>12.5g}  {_ci(d['period_ci95'])}",
             f"{'natural period T_n (s)':<24}{d['natural_period']:>12.5g}  "
             f"{_ci(d['natural_period_ci95'])}",
             f"{'damping ratio ζ':<24}{d['damping_ratio']:>12.5g}  "
             f"{_ci(d['damping_ratio_ci95'])}"]
    if "quadratic_damping" in d:
        lines += [f"{'quadratic c_q (1/' + u + ')':<24}{d['quadratic_damping']:>12.5g}  "
                  f"{_ci(d['quadratic_damping_ci95'])}",
                  f"{'equivalent ζ at A₀':<24}{d['damping_ratio_equivalent']:>12.5g}"]
    lines += ["", f"{'cycle':>5} {'T zero-up (s)':>14} {'amplitude':>11}"]
    lines += [f"{i + 1:>5} {p:>14.5g} {a:>11.4g}"
              for i, (p, a) in enumerate(zip(d["periods"], d["period_amplitudes"], strict=True))]
    lines += ["", f"{'cycle':>5} {'δ':>9} {'ζ':>9} {'mean amplitude':>15}"]
    zetas = log_decrement_damping(d["log_decrements"])
    lines += [f"{i + 1:>5} {delta:>9.4f} {z:>9.4f} {a:>15.4g}" for i, (delta, z, a)
              in enumerate(zip(d["log_decrements"], zetas, d["damping_amplitudes"], strict=True))]
    if "extinction" in d:
        lines += ["", *format_extinction(d["extinction"])]
    if "plot" in d:
        lines += ["", f"plot: {d['plot']}"]
    return "\n".join(lines)


def format_extinction(e: dict) -> list[str]:
    """Readable lines of :meth:`ExtinctionCurve.to_dict` output: the half swings, then the
    fits with their 95 % intervals."""
    u = e["unit"]
    lines = [f"extinction curve Δφ = {e['terms']} (ITTC 7.5-02-07-04.5), ω = 2π/T_n = "
             f"{e['natural_frequency_rad_per_s']:.5g} rad/s",
             f"{'half swing':>10} {'t (s)':>8} {f'mean amplitude ({u})':>21} "
             f"{f'decrement ({u})':>16} {'ζ_eq':>8} {'ζ_eq fit':>9}"]
    lines += [f"{i + 1:>10} {t:>8.4g} {a:>21.4g} {d:>16.4g} {z:>8.4f} {f:>9.4f}"
              for i, (t, a, d, z, f) in enumerate(zip(
                  e["half_swing_time_s"], e[f"mean_amplitude_{u}"], e[f"decrement_{u}"],
                  e["damping_ratio_equivalent"], e["damping_ratio_equivalent_fit"],
                  strict=True))]
    rows = [("a", e["a"], e["a_ci95"]),
            (f"b (1/{u})", e[f"b_per_{u}"], e[f"b_per_{u}_ci95"])]
    if f"c_per_{u}2" in e:
        rows.append((f"c (1/{u}²)", e[f"c_per_{u}2"], e[f"c_per_{u}2_ci95"]))
    rows += [("p1 = 2α (1/s)", e["p1_per_s"], e["p1_per_s_ci95"]),
             (f"p2 = β (1/{u})", e[f"p2_per_{u}"], e[f"p2_per_{u}_ci95"])]
    if f"p3_s_per_{u}2" in e:
        rows.append((f"p3 = γ (s/{u}²)", e[f"p3_s_per_{u}2"], e[f"p3_s_per_{u}2_ci95"]))
    q = e["quasi_linear"]
    rows += [(f"ζ_eq at {e[f'release_amplitude_{u}']:.4g} {u} (first)",
              e["damping_ratio_equivalent_release"], e["damping_ratio_equivalent_release_ci95"]),
             ("quasi-linear ζ1", q["zeta1"], q["zeta1_ci95"]),
             (f"quasi-linear ζ2 (1/{u})", q[f"zeta2_per_{u}"], q[f"zeta2_per_{u}_ci95"])]
    lines += ["", f"{'':28}{'value':>12}  95 % interval"]
    lines += [f"{label:<28}{value:>12.5g}  {_ci(ci)}" for label, value, ci in rows]
    lines.append(f"fit residual rms {e[f'residual_rms_{u}']:.3g} {u} ({e['fit_dof']} degrees "
                 f"of freedom); quasi-linear over {len(q['damping_ratio'])} cycles")
    if "plot" in e:
        lines.append(f"extinction plot: {e['plot']}")
    return lines
