"""A run's mesh level: coarse, medium or fine (:data:`floatfoam.layout.LEVELS`), checked once
(:func:`level_index`), and what it scales by: r^index (:func:`level_factor`), r the case's
refinement ratio between levels (:func:`refinement_ratio`; the sizes each level takes:
:mod:`floatfoam.meshing.levels`)."""

from __future__ import annotations

from floatfoam.case import Case
from floatfoam.errors import InputError
from floatfoam.layout import LEVELS


def level_index(level: str) -> int:
    if level not in LEVELS:
        raise InputError(f"--level {level!r}: valid levels are {', '.join(LEVELS)}")
    return LEVELS.index(level)


def refinement_ratio(case: Case) -> float:
    """The ratio r between consecutive levels: ``mesh.refinement_ratio`` (default √2), > 1."""
    return case.settings.mesh.refinement_ratio


def level_factor(case: Case, level: str) -> float:
    """Cell-count multiplier of a mesh level: r⁰, r¹, r² for coarse, medium, fine."""
    return refinement_ratio(case) ** level_index(level)
