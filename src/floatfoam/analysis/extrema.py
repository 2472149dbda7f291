"""The first extrema of a smooth decay record and the period they give.

A record too damped for the decay fit (a flat section radiating strongly, ζ ≈ 0.2, leaves the
noise after ~1.5 cycles) still times its first cycles by its extrema: the sign changes of its
slope, half a period apart.
"""

from __future__ import annotations

import numpy as np


def first_extrema(x, count: int) -> np.ndarray:
    """Indices of the first ``count`` (or fewer) extrema of ``x``: where its slope changes sign."""
    slope = np.diff(np.asarray(x, dtype=float))
    return (np.nonzero(np.sign(slope[1:]) != np.sign(slope[:-1]))[0] + 1)[:count]


def period_from_extrema(t, turns) -> float:
    """The period from extrema at the indices ``turns`` (≥ 2): twice their mean spacing."""
    t = np.asarray(t, dtype=float)
    return 2.0 * float(t[turns[-1]] - t[turns[0]]) / (len(turns) - 1)
