"""The memoir's printed formulas evaluated for a case (see floatfoam.memoir, docs/memoir.md)."""

from __future__ import annotations


def memoir_values(case, summary: dict) -> dict:
    """Values of Le Barbier's printed formulas where the memoir covers the body, else {}."""
    return {}
