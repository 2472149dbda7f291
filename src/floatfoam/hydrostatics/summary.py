"""What the linear theory says about a case, as a record: :class:`TheorySummary`.

Per degree of freedom (:mod:`floatfoam.dofs`) a :class:`DofTheory`; :meth:`TheorySummary.to_dict`
gives the flat JSON of ``floatfoam theory --json`` (``heave_period``, ``GM_roll``,
``verdict_pitch`` …), :meth:`TheorySummary.from_dict` reads it back.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from floatfoam.dofs import NAMES

ANGULAR = ("roll", "pitch")  # the DoFs with a metacentre and a verdict


@dataclass(frozen=True)
class DofTheory:
    """Linear theory of one DoF: the undamped natural period (s; None when the DoF does not
    oscillate) and, for roll and pitch, GM and BM (m) and Le Barbier's verdict (oscillates,
    neutral, capsizes)."""

    period: float | None
    metacentric_height: float | None = None
    metacentric_radius: float | None = None
    verdict: str | None = None


@dataclass(frozen=True)
class TheorySummary:
    """The linear hydrostatic theory of a case (SI units, seconds; equilibrium angles in
    degrees). ``memoir`` holds the memoir's values where it covers the body, by its method
    derived again (the corrected formulas; keys as in :meth:`to_dict`, plus ``source`` and
    ``reference``); ``memoir_printed`` its formulas as printed, errata included (see
    :func:`floatfoam.hydrostatics.memoir_case.memoir_printed_values`)."""

    case: str
    body: str
    section_length: float | None
    mass: float
    draft: float
    displaced_volume: float
    waterplane_area: float
    KB: float
    KG: float
    dofs: dict[str, DofTheory]
    equilibrium: dict
    stiffness: list
    exact: bool
    memoir: dict = field(default_factory=dict)
    memoir_printed: dict = field(default_factory=dict)
    #: an STL body's frame origin in its file's coordinates (m), for a body moved there
    #: (:func:`floatfoam.bodies.surfaces.centred`); None otherwise
    file_origin: list | None = None

    def period(self, dof: str) -> float | None:
        """Undamped natural period of ``dof`` (s), None when it does not oscillate."""
        entry = self.dofs.get(dof)
        return None if entry is None else entry.period

    def to_dict(self) -> dict:
        """The flat dictionary of ``floatfoam theory --json``."""
        out = {"case": self.case, "body": self.body, "section_length": self.section_length,
               "mass": self.mass, "draft": self.draft,
               "displaced_volume": self.displaced_volume,
               "waterplane_area": self.waterplane_area, "KB": self.KB, "KG": self.KG}
        out.update({f"BM_{d}": self.dofs[d].metacentric_radius for d in ANGULAR})
        out.update({f"GM_{d}": self.dofs[d].metacentric_height for d in ANGULAR})
        out.update({f"{d}_period": self.dofs[d].period for d in NAMES})
        out.update({f"verdict_{d}": self.dofs[d].verdict for d in ANGULAR})
        out.update(equilibrium=self.equilibrium, stiffness=self.stiffness, exact=self.exact,
                   memoir=self.memoir, memoir_printed=self.memoir_printed)
        if self.file_origin is not None:
            out["file_origin"] = self.file_origin
        return out

    @classmethod
    def from_dict(cls, data: dict) -> TheorySummary:
        """The summary of a :meth:`to_dict` dictionary (absent keys read as None)."""
        dofs = {d: DofTheory(data.get(f"{d}_period"), data.get(f"GM_{d}"),
                             data.get(f"BM_{d}"), data.get(f"verdict_{d}")) for d in NAMES}
        scalars = ("case", "body", "section_length", "mass", "draft", "displaced_volume",
                   "waterplane_area", "KB", "KG", "stiffness", "exact")
        return cls(**{k: data.get(k) for k in scalars}, dofs=dofs,
                   equilibrium=data.get("equilibrium") or {}, memoir=data.get("memoir") or {},
                   memoir_printed=data.get("memoir_printed") or {},
                   file_origin=data.get("file_origin"))
