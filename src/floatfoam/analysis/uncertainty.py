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


def extrapolated(study: dict, dof: str, key: str) -> tuple[float, float] | None:
    """(value, uncertainty) of the fine solution's extrapolation for the comparison: the
    Richardson value and U_num × it; None when the grids do not converge."""
    q = study.get("dofs", {}).get(dof, {}).get("quantities", {}).get(key)
    if not q or q["grid"].get("extrapolated") is None or q["uncertainty"] is None:
        return None
    value = q["grid"]["extrapolated"]
    return value, abs(value) * q["uncertainty"]
