"""The comparison's rows as a table: one row's fields (:func:`table_row`), its text cells in
Markdown (:func:`comparison_table`, :func:`comparison_markdown`) and the files
``comparison.md`` and ``comparison.csv`` (:func:`write_comparison`). The rows are made by
:mod:`floatfoam.analysis.compare`."""

from __future__ import annotations

import csv
from pathlib import Path

CSV_FIELDS = ("case", "dof", "source", "period", "period_lo", "period_hi", "damping_ratio",
              "damping_lo", "damping_hi", "period_rel_diff", "damping_rel_diff",
              "period_rel_diff_measured", "damping_rel_diff_measured", "basis", "note")


THEORY = "linear theory (exact)"


def optional_float(value) -> float | None:
    """A row's number, or None where there is none."""
    return None if value is None else float(value)


def table_row(case, dof, source, period=None, period_ci=None, zeta=None, zeta_ci=None, note=""):
    return {"case": case, "dof": dof, "source": source, "period": period,
            "period_ci": period_ci, "damping_ratio": zeta, "damping_ci": zeta_ci,
            "period_rel_diff": None, "damping_rel_diff": None,
            "period_rel_diff_measured": None, "damping_rel_diff_measured": None, "basis": "",
            "note": note}


def fmt(value, spec: str = ".4g") -> str:
    """A number for a table; an em dash when missing."""
    return "—" if value is None else format(value, spec)


def _interval(ci) -> str:
    return "" if ci is None else f"[{fmt(ci[0])}, {fmt(ci[1])}]"


def _percent(value) -> str:
    return "" if value is None else f"{100 * value:+.2f} %"


TABLE_HEADER = ("DoF", "source", "period (s)", "period 95 % CI / ± uncertainty",
                "Δ period vs model", "damping ratio ζ", "ζ 95 % CI / ± uncertainty",
                "Δ ζ vs model", "Δ period vs measured", "Δ ζ vs measured", "note")


MEASURED_COLUMNS = (8, 9)  # of TABLE_HEADER: left out of a table without a reference


def comparison_table(rows: list[dict]) -> tuple[list[str], list[list[str]]]:
    """Header and text cells of the comparison's rows, in the order of TABLE_HEADER, without
    the Δ-vs-measured columns when no row has one (a case without a reference). The columns
    name what their Δ is against; a row's note names it only where the model's Δ is the
    linear theory's (the model not computed)."""
    def note(r):
        basis = r["basis"] if f"vs {THEORY}" in r["basis"] else ""
        return "; ".join(x for x in (basis, r["note"]) if x)

    cells = [[r["dof"], r["source"], fmt(r["period"]), _interval(r["period_ci"]),
              _percent(r["period_rel_diff"]), fmt(r["damping_ratio"]),
              _interval(r["damping_ci"]), _percent(r["damping_rel_diff"]),
              _percent(r["period_rel_diff_measured"]), _percent(r["damping_rel_diff_measured"]),
              note(r)] for r in rows]
    keep = [i for i in range(len(TABLE_HEADER))
            if i not in MEASURED_COLUMNS or any(row[i] for row in cells)]
    return [TABLE_HEADER[i] for i in keep], [[row[i] for i in keep] for row in cells]


def comparison_markdown(comparison) -> str:
    """The comparison (:class:`floatfoam.analysis.compare.Comparison`: its ``rows`` and
    ``notes``) as a Markdown table, with the notes below it."""
    header, cells = comparison_table(comparison.rows)
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell.replace("|", "\\|") for cell in row) + " |"
              for row in cells]
    lines += [""] + [f"- {note}" for note in comparison.notes]
    return "\n".join(lines) + "\n"


def write_comparison(comparison, out_dir: str | Path) -> tuple[Path, Path]:
    """Write ``comparison.md`` and ``comparison.csv`` into ``out_dir``; return their paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    md_path, csv_path = out_dir / "comparison.md", out_dir / "comparison.csv"
    md_path.write_text(f"# {comparison.case}: period and damping\n\n"
                       + comparison_markdown(comparison))
    with csv_path.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=CSV_FIELDS)
        writer.writeheader()
        for r in comparison.rows:
            p_ci, z_ci = r["period_ci"] or (None, None), r["damping_ci"] or (None, None)
            writer.writerow({**{k: r[k] for k in CSV_FIELDS if k in r},
                             "period_lo": p_ci[0], "period_hi": p_ci[1],
                             "damping_lo": z_ci[0], "damping_hi": z_ci[1]})
    return md_path, csv_path
