"""The formal orders a study of the CFD takes (:mod:`floatfoam.analysis.validation`): the time
scheme's, read from the fvSchemes the runs take (:func:`time_order`), and the space schemes'."""

from __future__ import annotations

from pathlib import Path

from floatfoam import layout
from floatfoam.errors import InputError
from floatfoam.settings import time_scheme_coefficient

#: the order taken where a study holds none (Euler's: :func:`time_order` reads the scheme)
TIME_ORDER = 1.0


#: the schemes' formal order in space (second: cases/_common/system/fvSchemes; the time error
#: has its own GCI, below). An observed order beyond twice it says the three levels'
#: differences are not the power law the extrapolation assumes (two of them agree by chance,
#: or the error changes sign): such a quantity's GCI is flagged, and U_num takes instead the
#: fine pair's as a two-grid study with this order and F_s = 3 (Roache)
FORMAL_ORDER = 2.0


#: the formal order of each ddtSchemes entry a run may take (Crank–Nicolson's 2 only at ψ = 1:
#: ψ < 1 blends in Euler's first-order error)
DDT_ORDERS = {"Euler": 1.0, "backward": 2.0, "CrankNicolson": 2.0}


def time_order(case, schemes: Path | None = None) -> float:
    """The formal order of the time scheme the case's runs take: Crank–Nicolson where the case
    names it (``run.time_scheme``), else the ``ddtSchemes`` default of the shared fvSchemes
    (``schemes``, default cases/_common/system/fvSchemes), read there so that the GCI follows
    a change of it. A scheme of no known order is refused (InputError naming it). The
    interface's own scheme (``run.interface_time_scheme``) does not raise it: the momentum's
    Euler stays first order, and a study's halved step measures what it leaves."""
    psi = time_scheme_coefficient(case.settings.run.time_scheme)
    if psi is None:
        from foamlib import FoamFile

        path = schemes or layout.COMMON_DIR / "system" / "fvSchemes"
        entry = FoamFile(path)["ddtSchemes"]["default"]
        words = [str(w) for w in (entry if isinstance(entry, (list, tuple)) else
                                  str(entry).split())]
        if words[0] not in DDT_ORDERS:
            raise InputError(f"{path}: ddtSchemes default {' '.join(words)!r} has no formal "
                             f"order here: valid is {', '.join(DDT_ORDERS)}")
        psi = float(words[1]) if words[0] == "CrankNicolson" and len(words) > 1 else None
        if psi is None:
            return DDT_ORDERS[words[0]]
    return DDT_ORDERS["CrankNicolson"] if psi == 1.0 else DDT_ORDERS["Euler"]
