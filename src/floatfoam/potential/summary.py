"""What potential flow says about a case, as a record: :class:`PotentialSummary`.

Per degree of freedom (:mod:`floatfoam.dofs`) a :class:`DofPotential`;
:meth:`PotentialSummary.to_dict` gives the flat JSON of ``floatfoam potential --json``
(``heave_period``, ``roll_added_mass`` …), :meth:`PotentialSummary.from_dict` reads it back.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields

from floatfoam.dofs import NAMES


@dataclass(frozen=True)
class DofPotential:
    """One DoF with added mass (SI, about G): the natural period with added mass (s), the
    damping ratio from radiation, A and B at the natural frequency (rad/s) and the undamped
    period without added mass; for roll (pitch) the period and damping ratio with sway
    (surge) free as well; None where the DoF does not oscillate or is not solved."""

    period: float | None = None
    damping_ratio: float | None = None
    added_mass: float | None = None
    radiation_damping: float | None = None
    natural_frequency: float | None = None
    period_no_added_mass: float | None = None
    # roll with sway free, pitch with surge free (resonance.condensed): what a free body does
    coupled_period: float | None = None
    coupled_damping_ratio: float | None = None


@dataclass(frozen=True)
class PotentialSummary:
    """Natural periods with added mass and radiation damping ratios of a case, and what was
    solved (method, panels, depth in m or None for deep water, the frequencies)."""

    case: str | None
    method: str | None
    panels: int | None
    depth: float | None
    frequencies: dict
    section_length: float | None
    notes: list[str]
    dofs: dict[str, DofPotential]
    added_mass_inf: list = field(default_factory=list)
    stiffness: list = field(default_factory=list)
    mass_matrix: list = field(default_factory=list)

    def dof(self, name: str) -> DofPotential:
        return self.dofs.get(name, DofPotential())

    def to_dict(self) -> dict:
        """The flat dictionary of ``floatfoam potential --json``."""
        out = {"case": self.case, "method": self.method, "panels": self.panels,
               "depth": self.depth, "frequencies": self.frequencies,
               "section_length": self.section_length, "notes": self.notes}
        for name in NAMES:
            out.update({f"{name}_{k}": v for k, v in asdict(self.dof(name)).items()})
        out.update(added_mass_inf=self.added_mass_inf, stiffness=self.stiffness,
                   mass_matrix=self.mass_matrix)
        return out

    @classmethod
    def from_dict(cls, data: dict) -> PotentialSummary:
        """The summary of a :meth:`to_dict` dictionary (absent keys read as None)."""
        keys = [f.name for f in fields(DofPotential)]
        dofs = {name: DofPotential(**{k: data.get(f"{name}_{k}") for k in keys})
                for name in NAMES}
        return cls(case=data.get("case"), method=data.get("method"), panels=data.get("panels"),
                   depth=data.get("depth"), frequencies=data.get("frequencies") or {},
                   section_length=data.get("section_length"), notes=list(data.get("notes") or []),
                   dofs=dofs, added_mass_inf=data.get("added_mass_inf") or [],
                   stiffness=data.get("stiffness") or [],
                   mass_matrix=data.get("mass_matrix") or [])
