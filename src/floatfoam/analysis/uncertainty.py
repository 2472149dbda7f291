"""The numerical uncertainty a case's grid and time-step study recorded (``floatfoam validate``,
:mod:`floatfoam.analysis.validation`), read back for the comparison table and the report."""

from __future__ import annotations

import json
from pathlib import Path

from floatfoam import layout

STUDY_FILE = "validation.json"  # in <build>/<case>/validation/


def read_study(case_name: str, build: Path | None = None) -> dict | None:
    """The study of a case (its JSON), None when ``floatfoam validate`` has not written one."""
    path = layout.case_build_dir(case_name, build) / "validation" / STUDY_FILE
    return json.loads(path.read_text()) if path.is_file() else None


def fine_band(study: dict, dof: str, key: str) -> tuple[float, float, float | None] | None:
    """(φ_fine, U_num |φ_fine|, φ_ext) of one quantity: the fine level's value, the half-width
    of its uncertainty band (the GCI bands the fine solution, not the extrapolated one) and the
    Richardson extrapolation (None when the levels give no order); None without a U_num."""
    q = study.get("dofs", {}).get(dof, {}).get("quantities", {}).get(key)
    if not q or q.get("uncertainty") is None or "values" not in q["grid"]:
        return None
    fine = q["grid"]["values"][0]
    return fine, abs(fine) * q["uncertainty"], q["grid"].get("extrapolated")
