"""The mesh-levels table: for each case and level, the body's discrete volume error and, on
request, the fluid domain's cells and checkMesh quality (a Markdown table for the README)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from floatfoam.layout import LEVELS, build_dir
from floatfoam.meshing.domains import build_domain
from floatfoam.meshing.levels import mesh_spec
from floatfoam.meshing.volume_report import discrete_volume_report


def level_rows(case, levels=LEVELS, domains: bool = False, check: Callable | None = None,
               kind: str = "auto", scratch: Path | None = None) -> list[dict]:
    """One row per level of ``case``: sizes, the discrete volume report and (``domains``) the
    domain's cells, with the mesh's quality when a ``check`` is given (called with the .msh
    and a folder for the OpenFOAM mesh, e.g. :func:`floatfoam.foam.meshcheck.convert_and_check`;
    the meshing never runs OpenFOAM itself)."""
    from floatfoam.hydrostatics.theory import equilibrium

    eq = equilibrium(case)
    rows = []
    for level in levels:
        spec = mesh_spec(case, level)
        report = discrete_volume_report(case, level, equilibrium=eq)
        row = {"case": case.name, "level": level, "ratio": spec.ratio,
               "body_cell": spec.body_size, "elements": report["elements"],
               "discrete": report["discrete"], "volume_error": report["volume_error"],
               "immersed_error": report["immersed_error"],
               "equilibrium_shift": report["equilibrium_shift"]}
        if "meridian" in report:
            row["wedge_immersed_error"] = report["meridian"]["immersed_error"]
        if domains:
            folder = (scratch or build_dir() / "mesh_table") / case.name / level
            result = build_domain(case, level, kind, path=folder / "domain.msh")
            row.update(kind=result["kind"], cells=result["cells"],
                       cell_types=result["cell_types"],
                       patch_immersed_error=result["body_patch"]["immersed_error"])
            if check is not None:
                quality = check(Path(result["path"]), folder / "foam")
                row.update(max_non_orthogonality=quality["max_non_orthogonality"],
                           max_skewness=quality["max_skewness"], mesh_ok=quality["mesh_ok"])
        rows.append(row)
    return rows


def markdown(rows: list[dict]) -> str:
    """The rows as a Markdown table (sizes in mm, errors in %)."""
    with_domain = any("cells" in r for r in rows)
    with_check = any("max_non_orthogonality" in r for r in rows)
    head = ["case", "level", "body cell (mm)", "body elements", "volume error",
            "immersed error at equilibrium", "equilibrium shift (mm)"]
    if with_domain:
        head += ["domain", "cells", "growth"]
    if with_check:
        head += ["max non-orth. (°)", "max skewness"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    previous = {}
    for r in rows:
        cells = [r["case"], r["level"], f"{r['body_cell'] * 1e3:.3g}", str(r["elements"]),
                 f"{r['volume_error'] * 100:+.3f} %", f"{r['immersed_error'] * 100:+.3f} %",
                 f"{r['equilibrium_shift'] * 1e3:+.3f}"]
        if with_domain:
            before = previous.get(r["case"])
            growth = f"×{r['cells'] / before:.2f}" if before else ""
            cells += [r.get("kind", ""), str(r.get("cells", "")), growth]
            previous[r["case"]] = r.get("cells")
        if with_check:
            cells += [f"{r['max_non_orthogonality']:.1f}", f"{r['max_skewness']:.2f}"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)
