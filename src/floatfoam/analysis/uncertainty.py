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


def current_study(case, build: Path | None = None) -> tuple[dict | None, list[str]]:
    """(the study of ``case``, []) when every run it was made from was stamped with the case's
    settings of today; (None, the names of those that were not) when the case file, a --set or
    a default has changed since (the study is not of this case any more); (None, []) without
    a study. The stamps are those the study recorded when it was made; a study that holds no
    stamps is checked against the stamps in the run folders. A run without a stamp (made by
    hand) leaves the study as it is."""
    from floatfoam.plan.stamps import settings_digest, stamp_of

    study = read_study(case.name, build)
    if study is None:
        return None, []
    recorded = study.get("stamps")
    foreign = []
    for name in study.get("runs", []):
        level, divisor, morphing = layout.parse_run_name(name)
        if recorded is not None:
            stamp = recorded.get(name)
        else:
            stamp = stamp_of(layout.run_dir(case.name, level, build, time_step_divisor=divisor,
                                            morphing=morphing))
        if stamp is not None and stamp != settings_digest(case, level, divisor=divisor,
                                                          morphing=morphing):
            foreign.append(name)
    return (None, foreign) if foreign else (study, [])


def fine_band(study: dict, dof: str, key: str) -> tuple[float, float, float | None] | None:
    """(φ_fine, U_num |φ_fine|, φ_ext) of one quantity: the fine level's value, the half-width
    of its uncertainty band (the GCI bands the fine solution, not the extrapolated one) and the
    Richardson extrapolation (None when the levels give no order); None without a U_num."""
    q = study.get("dofs", {}).get(dof, {}).get("quantities", {}).get(key)
    if not q or q.get("uncertainty") is None or "values" not in q["grid"]:
        return None
    fine = q["grid"]["values"][0]
    return fine, abs(fine) * q["uncertainty"], q["grid"].get("extrapolated")
