"""Discretisation uncertainty: the grid convergence index of Celik et al. (2008).

Celik, Ghia, Roache, Freitas, Coleman and Raad (2008), "Procedure for estimation and reporting
of uncertainty due to discretization in CFD applications", J. Fluids Eng. 130(7):078001. With
three grids, fine (1) to coarse (3), of representative cell sizes h1 < h2 < h3 (their eq. 1:
h = (V/N)^(1/d) for N cells filling the same domain) and a quantity φ1, φ2, φ3 on them:

    r21 = h2/h1,  r32 = h3/h2,  ε21 = φ2 − φ1,  ε32 = φ3 − φ2,  s = sign(ε32/ε21)
    p = |ln|ε32/ε21| + q(p)| / ln r21,   q(p) = ln((r21^p − s)/(r32^p − s))        (eqs. 3a-c)
    φ_ext21 = (r21^p φ1 − φ2)/(r21^p − 1)                                            (eq. 4)
    e_a21 = |(φ1 − φ2)/φ1|,  e_ext21 = |(φ_ext21 − φ1)/φ_ext21|                      (eq. 5)
    GCI_fine21 = 1.25 e_a21/(r21^p − 1)                                              (eq. 6)

p is the observed order, solved by fixed-point iteration (q = 0 when r21 = r32). The ratio
R = ε21/ε32 says how the three grids converge (Stern et al. 2001, J. Fluids Eng. 123:793, the
classification Celik et al. refer to): 0 < R < 1 monotonic convergence, −1 < R < 0
oscillatory convergence (Celik et al.: "negative values of ε32/ε21 are an indication of
oscillatory convergence"; the procedure is applied with s = −1 and the result says so),
R ≥ 1 monotonic divergence and R ≤ −1 oscillatory divergence: then there is no asymptotic
range, no order and no GCI, and the result says that instead of inventing one. ε21 = 0 or
ε32 = 0 (to round-off) is "converged to the digits given": no order either.

Two solutions only (the time-step halving of a validation, :func:`two_level`): Roache (1998,
*Verification and Validation in Computational Science and Engineering*, Hermosa), GCI =
F_s |ε|/(r^p − 1) for the finer solution and F_s |ε| r^p/(r^p − 1) for the coarser, with the
scheme's formal order p and the safety factor F_s = 3 he gives for two-grid studies.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

SAFETY_THREE_GRIDS = 1.25  # Celik et al. (2008) eq. 6
SAFETY_TWO_GRIDS = 3.0  # Roache (1998): a two-grid study with an assumed order
MONOTONIC, OSCILLATORY = "monotonic convergence", "oscillatory convergence"
DIVERGENT_MONOTONIC, DIVERGENT_OSCILLATORY = "monotonic divergence", "oscillatory divergence"
CONVERGED = "no change between grids"
NO_ORDER = "converging, but no observed order"  # the fixed point of eq. 3 does not exist


@dataclass(frozen=True)
class GridConvergence:
    """One quantity on three grids and what Celik et al.'s procedure makes of it.

    ``order``, ``extrapolated``, ``extrapolated_coarse``, ``relative_error_extrapolated``,
    ``gci_fine`` and ``gci_fine32`` (fractions, not %) are None when the grids do not converge
    or give no order (``kind``).
    """

    values: tuple[float, float, float]  # φ1 (fine), φ2, φ3 (coarse)
    ratios: tuple[float, float]  # r21, r32
    kind: str
    ratio_r: float | None  # R = ε21/ε32
    order: float | None
    extrapolated: float | None  # φ_ext21
    extrapolated_coarse: float | None  # φ_ext32
    relative_error: float  # e_a21
    relative_error_extrapolated: float | None  # e_ext21
    gci_fine: float | None  # GCI_fine21
    relative_error_coarse: float  # e_a32
    gci_fine32: float | None  # GCI_fine32 = 1.25 e_a32/(r32^p − 1), the medium grid's

    @property
    def converges(self) -> bool:
        return self.kind in (MONOTONIC, OSCILLATORY)

    def as_dict(self) -> dict:
        return asdict(self) | {"converges": self.converges}


def cell_size(cells: int, dimension: int, extent: float = 1.0) -> float:
    """Celik et al.'s eq. 1: the representative cell size (extent/N)^(1/d) of N cells filling
    a domain of the given area (d = 2) or volume (d = 3)."""
    if cells < 1 or dimension not in (2, 3):
        raise ValueError(f"cells = {cells}, dimension = {dimension}: valid are N ≥ 1, d = 2 or 3")
    return (extent / cells) ** (1.0 / dimension)


def observed_order(e21: float, e32: float, r21: float, r32: float, *,
                   tol: float = 1e-12, max_iter: int = 500) -> float:
    """Celik et al.'s eqs. 3a-c by fixed-point iteration, from p = |ln|ε32/ε21|| / ln r21.

    Raises ArithmeticError when the iteration leaves the real numbers or does not settle."""
    s = math.copysign(1.0, e32 / e21)
    log_ratio = math.log(abs(e32 / e21))
    p = abs(log_ratio) / math.log(r21)
    for _ in range(max_iter):
        num, den = r21**p - s, r32**p - s
        if num <= 0 or den <= 0:
            raise ArithmeticError(f"q(p) undefined at p = {p:g}")
        new = abs(log_ratio + math.log(num / den)) / math.log(r21)
        if abs(new - p) <= tol * max(1.0, abs(new)):
            return new
        p = new
    raise ArithmeticError(f"the observed order did not settle (last p = {p:g})")


def three_grids(fine: float, medium: float, coarse: float, r21: float, r32: float, *,
                round_off: float = 1e-12) -> GridConvergence:
    """Celik et al. (2008) on φ1 (fine), φ2, φ3 (coarse) with refinement ratios r21, r32 > 1."""
    if not (r21 > 1 and r32 > 1):
        raise ValueError(f"r21 = {r21}, r32 = {r32}: valid are refinement ratios > 1")
    values = (float(fine), float(medium), float(coarse))
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"values {values}: valid are finite numbers")
    e21, e32 = medium - fine, coarse - medium
    e_a21 = abs(e21 / fine) if fine else math.inf
    e_a32 = abs(e32 / medium) if medium else math.inf
    scale = round_off * max(abs(v) for v in values)
    common = {"values": values, "ratios": (r21, r32), "relative_error": e_a21,
              "relative_error_coarse": e_a32}
    none = dict.fromkeys(("order", "extrapolated", "extrapolated_coarse",
                          "relative_error_extrapolated", "gci_fine", "gci_fine32"))
    if abs(e21) <= scale or abs(e32) <= scale:
        return GridConvergence(kind=CONVERGED, ratio_r=None, **common, **none)
    ratio = e21 / e32
    if abs(ratio) >= 1:
        kind = DIVERGENT_MONOTONIC if ratio > 0 else DIVERGENT_OSCILLATORY
        return GridConvergence(kind=kind, ratio_r=ratio, **common, **none)
    kind = MONOTONIC if ratio > 0 else OSCILLATORY
    try:
        p = observed_order(e21, e32, r21, r32)
    except ArithmeticError:
        return GridConvergence(kind=NO_ORDER, ratio_r=ratio, **common, **none)
    f21, f32 = r21**p, r32**p
    ext21 = (f21 * fine - medium) / (f21 - 1)
    ext32 = (f32 * medium - coarse) / (f32 - 1)
    return GridConvergence(
        kind=kind, ratio_r=ratio, order=p, extrapolated=ext21, extrapolated_coarse=ext32,
        relative_error_extrapolated=abs((ext21 - fine) / ext21) if ext21 else math.inf,
        gci_fine=SAFETY_THREE_GRIDS * e_a21 / (f21 - 1),
        gci_fine32=SAFETY_THREE_GRIDS * e_a32 / (f32 - 1), **common)


@dataclass(frozen=True)
class TwoLevel:
    """A quantity at two resolutions (e.g. two time steps) and Roache's two-grid GCI of each.

    ``gci_fine`` bands the finer solution, ``gci_coarse`` the coarser one (fractions)."""

    values: tuple[float, float]  # fine, coarse
    ratio: float
    order: float  # the scheme's formal order, assumed
    relative_error: float  # |(φ_coarse − φ_fine)/φ_coarse|
    gci_fine: float
    gci_coarse: float

    def as_dict(self) -> dict:
        return asdict(self)


def two_level(fine: float, coarse: float, ratio: float, order: float) -> TwoLevel:
    """Roache's (1998) two-grid GCI with F_s = 3 and p the scheme's formal order (an
    assumption: two solutions cannot observe it), ε = |(φc − φf)/φc|: the finer solution's
    GCI = F_s ε/(r^p − 1), the coarser one's F_s ε r^p/(r^p − 1)."""
    if ratio <= 1 or order <= 0:
        raise ValueError(f"ratio = {ratio}, order = {order}: valid are r > 1, p > 0")
    if not (math.isfinite(fine) and math.isfinite(coarse)):
        raise ValueError(f"values {fine}, {coarse}: valid are finite numbers")
    rel = abs((coarse - fine) / coarse) if coarse else math.inf
    f = ratio**order
    return TwoLevel((float(fine), float(coarse)), ratio, order, rel,
                    SAFETY_TWO_GRIDS * rel / (f - 1), SAFETY_TWO_GRIDS * rel * f / (f - 1))
