"""Where the report takes each case's inputs from (:class:`Sources`): the case loader, the
theory, the potential flow, Cummins' model, the radiation coefficients and the GZ curve."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Sources:
    """Where the report takes each case's inputs from: ``load`` (a case folder → the loaded
    case), ``theory`` (case → theory summary), ``potential`` (case → potential-flow summary,
    None to leave potential flow out), ``model`` (case, duration → Cummins' model,
    :func:`~floatfoam.analysis.cummins.cummins_model`; None to leave it out) and
    ``coefficients`` (case → radiation coefficients for the A(ω), B(ω) figure; None to leave
    it out) and ``gz`` (case → GZ curve, for a case released heeled; None to leave it out).
    :meth:`default` is the project's own; potential flow's results are cached in
    build/potential, so a report drawn again solves nothing again."""

    load: Callable
    theory: Callable
    potential: Callable | None
    model: Callable | None = None
    coefficients: Callable | None = None
    gz: Callable | None = None

    @classmethod
    def default(cls, include_potential: bool = True) -> Sources:
        from floatfoam.analysis.compare import potential_flow
        from floatfoam.analysis.cummins import cummins_model
        from floatfoam.case import load_case
        from floatfoam.hydrostatics.gz import gz_curve
        from floatfoam.hydrostatics.theory import theory_summary
        from floatfoam.potential.radiation import radiation_coefficients

        flow = {"potential": potential_flow, "model": cummins_model,
                "coefficients": radiation_coefficients} if include_potential else \
            {"potential": None}
        return cls(load=lambda folder: load_case(str(folder)), theory=theory_summary,
                   gz=gz_curve, **flow)
