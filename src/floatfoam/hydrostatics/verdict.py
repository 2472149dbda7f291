"""Le Barbier's verdict, in one place: a body oscillates, stays put (neutral) or capsizes as
its metacentric height (or any stability margin, in m) is positive, zero or negative.

"Zero" is within a tolerance relative to the body's size: round-off for closed forms, the
surface discretisation for the numeric path (docs/conventions.md).
"""

from __future__ import annotations

NEUTRAL_TOL_EXACT = 1e-9  # |GM| / size below which GM is zero, closed forms (round-off)
NEUTRAL_TOL_NUMERIC = 1e-5  # same, numeric path (surface discretisation ~1e-6 of the size)


def verdict(gm: float, size: float, exact: bool = True) -> str:
    """"oscillates", "neutral" or "capsizes" as ``gm`` (m) is > 0, zero within the tolerance
    (× ``size``), or < 0 (Le Barbier 1817, p. 53: "il restera dans la position où on l'aura
    placé" when it is zero)."""
    tol = (NEUTRAL_TOL_EXACT if exact else NEUTRAL_TOL_NUMERIC) * size
    if abs(gm) <= tol:
        return "neutral"
    return "oscillates" if gm > 0 else "capsizes"
