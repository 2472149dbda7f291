"""Ikeda's component estimate of roll damping for a 2D section at zero speed (per unit length).

The components, each an equivalent linear damping B44 (N·m·s/rad per metre) at roll amplitude
φ_a and frequency ω:

- **friction** (Kato): B_F = 4/(3π) ρ S r_f³ φ_a ω C_f, C_f = 1.328 Rn^-½ + 0.014 Rn^-0.114,
  Rn = 0.512 (r_f φ_a)² ω / ν, with S the wetted girth and r_f the mean distance from the roll
  axis (G) to it (Kato's whole-ship form taken per unit length of the section);
- **eddy making** (Ikeda 1978; Ikeda, Himeno & Tanaka 1978): B_E = 4/(3π) ρ d⁴ ω φ_a C_R,
  the equivalent of a quadratic moment ½ ρ d⁴ C_R |φ̇| φ̇, with C_R from the section's Lewis
  form (its half-beam-to-draught ratio H0 and area coefficient σ), the depth of G below the
  waterline OG and the bilge radius R (:func:`eddy_coefficient`);
- **wave**: the radiation damping of the section in roll about G, from floatfoam's own
  potential flow (not Ikeda's regression);
- **lift**: zero at zero speed.

No bilge keels (no case has them). The formulas are those gathered, checked by derivation and
against Ikeda's 2D measurements, in docs/theory/roll-damping.md, with their sources; C_R of
Ikeda's box sections (H0 = 1.25, R/d 0–0.27) is tested against the published values there.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from floatfoam.errors import InputError

#: Ikeda's 2D test sections (Ikeda 1978, digitised by Alexandersson 2021): the range the eddy
#: coefficient was fitted and checked on
TESTED = {"H0": (0.17, 1.25), "sigma": (0.43, 1.0), "R/d": (0.0, 0.27), "OG/d": (-1.75, 0.0)}


@dataclass(frozen=True)
class Section:
    """The immersed section at the upright equilibrium, about its roll axis G (SI units)."""

    beam: float  # B, at the waterline
    draft: float  # d
    area: float  # A_s, immersed
    girth: float  # S, wetted (both sides and the bottom)
    mean_radius: float  # r_f: the mean distance from G to the wetted contour
    og: float  # OG: depth of G below the waterline (negative above it)
    bilge_radius: float  # R: the section's own, or Ikeda's estimate from σ
    bilge_radius_estimated: bool

    @property
    def H0(self) -> float:  # noqa: N802 (Ikeda's name)
        return self.beam / (2 * self.draft)

    @property
    def sigma(self) -> float:
        return self.area / (self.beam * self.draft)


@dataclass(frozen=True)
class Lewis:
    """The Lewis form of a section: x = M[(1+a1) sin ψ − a3 sin 3ψ],
    y = −M[(1−a1) cos ψ + a3 cos 3ψ], ψ from the keel (0) to the waterline (π/2)."""

    a1: float
    a3: float
    M: float

    def radius(self, psi: float) -> float:
        """Distance from the waterline's centre O to the contour at ψ."""
        x = (1 + self.a1) * math.sin(psi) - self.a3 * math.sin(3 * psi)
        y = (1 - self.a1) * math.cos(psi) + self.a3 * math.cos(3 * psi)
        return self.M * math.hypot(x, y)


def lewis_valid(H0: float, sigma: float) -> bool:  # noqa: N803
    """Whether the Lewis form of (H0, σ) is a section (its contour does not cross itself)."""
    low = 3 * math.pi / 32 * (2 - (H0 if H0 <= 1 else 1 / H0))
    high = math.pi / 32 * (10 + H0 + 1 / H0)
    return low < sigma < high


def lewis_form(beam: float, H0: float, sigma: float) -> Lewis:  # noqa: N803
    if not lewis_valid(H0, sigma):
        raise InputError(f"the section's H0 = {H0:.3g} and σ = {sigma:.4g} have no "
                         "Lewis form (its contour would cross itself), which Ikeda's eddy "
                         "coefficient needs; valid: a ship-like section")
    c1 = (3 + 4 * sigma / math.pi) + (1 - 4 * sigma / math.pi) * ((H0 - 1) / (H0 + 1)) ** 2
    a3 = (-c1 + 3 + math.sqrt(9 - 2 * c1)) / c1
    a1 = (1 + a3) * (H0 - 1) / (H0 + 1)
    return Lewis(a1, a3, beam / (2 * (1 + a1 + a3)))


def estimated_bilge_radius(beam: float, draft: float, sigma: float) -> float:
    """Ikeda's bilge radius of a section with two circular bilges of the area it lacks from
    its rectangle, R = √(B d (1 − σ) / (2 (1 − π/4))), at most d (H0 ≥ 1) or B/2."""
    radius = math.sqrt(max(beam * draft * (1 - sigma), 0.0) / (2 * (1 - math.pi / 4)))
    return min(radius, draft if beam / (2 * draft) >= 1 else beam / 2)


@dataclass(frozen=True)
class Eddy:
    """Ikeda's eddy-making coefficient C_R and the quantities it is made of."""

    C_R: float  # noqa: N815
    C_P: float  # noqa: N815
    gamma: float
    r_max: float
    psi: float
    f1: float
    f2: float
    f3: float
    a1: float
    a3: float


def eddy_coefficient(H0: float, sigma: float, draft: float, og: float,  # noqa: N803
                     bilge_radius: float) -> Eddy:
    """C_R of Ikeda's eddy-making damping (zero speed, no bilge keels):
    C_R = (r_max/d)² C_P [(1 − f1 R/d)(1 − OG/d − f1 R/d) + f2 (H0 − f1 R/d)²], with C_P the
    pressure coefficient behind the separation from γ, the ratio of the largest velocity on the
    section to its mean, via the Lewis form."""
    d, R = draft, bilge_radius  # noqa: N806
    lewis = lewis_form(2 * H0 * d, H0, sigma)
    a1, a3, M = lewis.a1, lewis.a3, lewis.M  # noqa: N806
    candidates = [0.0]
    if a3 != 0:
        arg = a1 * (1 + a3) / (4 * a3)
        candidates.append(0.5 * math.acos(min(1.0, max(-1.0, arg))))
    psi = max(candidates, key=lewis.radius)
    r_max = lewis.radius(psi)
    A = (-2 * a3 * math.cos(5 * psi) + a1 * (1 - a3) * math.cos(3 * psi)  # noqa: N806
         + ((6 - 3 * a1) * a3**2 + (a1**2 - 3 * a1) * a3 + a1**2) * math.cos(psi))
    B = (-2 * a3 * math.sin(5 * psi) + a1 * (1 - a3) * math.sin(3 * psi)  # noqa: N806
         + ((6 + 3 * a1) * a3**2 + (a1**2 + 3 * a1) * a3 + a1**2) * math.sin(psi))
    H = (1 + a1**2 + 9 * a3**2 + 2 * a1 * (1 - 3 * a3) * math.cos(2 * psi)  # noqa: N806
         - 6 * a3 * math.cos(4 * psi))
    below = 1 - og / d
    H0_g, sigma_g = H0 / below, (sigma - og / d) / below  # noqa: N806 (about G)
    f1 = 0.5 * (1 + math.tanh(20 * (sigma - 0.7)))
    f2 = (0.5 * (1 - math.cos(math.pi * sigma))
          - 1.5 * (1 - math.exp(-5 * (1 - sigma))) * math.sin(math.pi * sigma) ** 2)
    f3 = 1 + 4 * math.exp(-1.65e5 * (1 - sigma) ** 2)
    gamma = (math.sqrt(math.pi) * f3 * (r_max + 2 * M / H * math.hypot(A, B))
             / (2 * d * below * math.sqrt(H0_g * sigma_g)))
    c_p = 0.5 * (0.87 * math.exp(-gamma) - 4 * math.exp(-0.187 * gamma) + 3)
    r = f1 * R / d
    c_r = (r_max / d) ** 2 * c_p * ((1 - r) * (1 - og / d - r) + f2 * (H0 - r) ** 2)
    return Eddy(c_r, c_p, gamma, r_max, psi, f1, f2, f3, a1, a3)


def friction(section: Section, amplitude: float, omega: float, rho: float,
             nu: float) -> float:
    """Kato's frictional B44 per unit length (N·m·s/rad per m) at amplitude φ_a (rad), ω."""
    r_f = section.mean_radius
    rn = 0.512 * (r_f * amplitude) ** 2 * omega / nu
    c_f = 1.328 * rn**-0.5 + 0.014 * rn**-0.114
    return 4 / (3 * math.pi) * rho * section.girth * r_f**3 * amplitude * omega * c_f


def eddy(section: Section, amplitude: float, omega: float, rho: float) -> tuple[float, Eddy]:
    """Ikeda's eddy-making B44 per unit length at amplitude φ_a (rad), ω, and its C_R."""
    e = eddy_coefficient(section.H0, section.sigma, section.draft, section.og,
                         section.bilge_radius)
    c_r = max(e.C_R, 0.0)  # Ikeda's fit can fall below 0 for large bilge radii: no eddy
    return 4 / (3 * math.pi) * rho * section.draft**4 * omega * amplitude * c_r, e


def require_section(case) -> None:
    """Ikeda's components here are per unit length of a horizontal prism's section."""
    body = case.body
    if not getattr(body, "is_section", False):
        raise InputError(f"case {case.name!r} is not a 2D section (shape "
                         f"{type(body).__name__}); valid: a horizontal prism's section (box, "
                         "circular, elliptic, parabolic or conic cylinder)")


def check_amplitude(amplitude_deg: float) -> None:
    if not (math.isfinite(amplitude_deg) and 0 < amplitude_deg <= 45):
        raise InputError(f"--amplitude {amplitude_deg:g}: valid is a roll amplitude in degrees, "
                         "0 < φ_a ≤ 45")


def section_of(case, eq, resolution: int = 2000) -> Section:
    """The immersed section of a 2D case at its upright equilibrium, about G."""
    body = case.body
    require_section(case)
    if abs(eq.heel) > 1e-9 or abs(float(case.cog[1])) > 1e-12:
        raise InputError(f"case {case.name!r} floats heeled (G off the centre "
                         "plane); valid: a section upright at equilibrium")
    waterline = -eq.z_c
    poly = _below(np.asarray(body.section_polygon(resolution), dtype=float), waterline)
    y, z = poly[:, 0], poly[:, 1]
    area = 0.5 * abs(float(np.sum(y * np.roll(z, -1) - np.roll(y, -1) * z)))
    beam = float(np.ptp(y[np.isclose(z, waterline, atol=1e-12)])) if np.any(
        np.isclose(z, waterline, atol=1e-12)) else 0.0
    draft = waterline - float(z.min())
    # the wetted contour: every edge but the waterline's
    nxt = np.roll(poly, -1, axis=0)
    wet = ~(np.isclose(poly[:, 1], waterline, atol=1e-12)
            & np.isclose(nxt[:, 1], waterline, atol=1e-12))
    lengths = np.linalg.norm(nxt - poly, axis=1)[wet]
    mid = (0.5 * (poly + nxt))[wet]
    g = np.array([float(case.cog[1]), float(case.cog[2])])
    girth = float(lengths.sum())
    mean_radius = float(np.sum(lengths * np.linalg.norm(mid - g, axis=1)) / girth)
    sigma = area / (beam * draft)
    own = getattr(body, "r", None)
    radius = own if own is not None else estimated_bilge_radius(beam, draft, sigma)
    return Section(beam, draft, area, girth, mean_radius, waterline - g[1],
                   float(radius), own is None)


def _below(poly: np.ndarray, level: float) -> np.ndarray:
    """The part of a closed polygon (y, z) at or below z = level (Sutherland–Hodgman)."""
    out = []
    for a, b in zip(poly, np.roll(poly, -1, axis=0), strict=True):
        a_in, b_in = a[1] <= level, b[1] <= level
        if a_in:
            out.append(a)
        if a_in != b_in:
            t = (level - a[1]) / (b[1] - a[1])
            out.append(np.array([a[0] + t * (b[0] - a[0]), level]))
    return np.array(out)


@dataclass(frozen=True)
class RollDamping:
    """Ikeda's components of a section's roll damping at one amplitude, for the whole body
    (per-metre values × its length), and the equivalent damping ratio of each."""

    amplitude_deg: float
    omega: float  # rad/s: the roll natural frequency with added inertia (potential flow)
    inertia: float  # I44 + A44 about G (kg·m²)
    friction: float  # N·m·s/rad
    eddy: float
    wave: float
    lift: float
    C_R: float  # noqa: N815
    section: dict
    flags: list[str]
    # the radiation damping ratio with sway free as well (what a free body radiates; the
    # components above are about a fixed axis through G, as Ikeda's method is)
    wave_zeta_sway_free: float | None = None

    @property
    def total(self) -> float:
        return self.friction + self.eddy + self.wave + self.lift

    def zeta(self, b44: float) -> float:
        return b44 / (2 * self.inertia * self.omega)

    def to_dict(self) -> dict:
        out = asdict(self)
        out["total"] = self.total
        out["zeta"] = {k: self.zeta(getattr(self, k) if k != "total" else self.total)
                       for k in ("friction", "eddy", "wave", "lift", "total")}
        return out


def validity_flags(section: Section, eddy_c: Eddy) -> list[str]:
    """Where the section lies outside what Ikeda's eddy coefficient was checked on."""
    flags = []
    values = {"H0": section.H0, "sigma": section.sigma,
              "R/d": section.bilge_radius / section.draft, "OG/d": section.og / section.draft}
    for key, (lo, hi) in TESTED.items():
        value, slack = values[key], 0.02 * (hi - lo)  # 2 % of the range: not a flag for round-off
        if not lo - slack <= value <= hi + slack:
            flags.append(f"{key} = {value:.3g} outside Ikeda's 2D tests ({lo:g} to {hi:g}): "
                         "the eddy component is extrapolated")
    if 0.99 < section.sigma < 1.0:
        flags.append(f"σ = {section.sigma:.4f}: between a rounded and a sharp-cornered section, "
                     f"where f3 (here {eddy_c.f3:.3g}) makes the eddy component very sensitive "
                     "to σ")
    if eddy_c.C_R <= 0:
        flags.append("the eddy coefficient's formula gives C_R ≤ 0 for this section (a bilge "
                     "radius this large leaves no separation in Ikeda's fit): taken as 0")
    if section.bilge_radius_estimated:
        flags.append(f"bilge radius {section.bilge_radius:.4g} m estimated from σ (two circular "
                     "bilges)")
    return flags


def roll_damping(case, eq, potential, amplitude_deg: float) -> RollDamping:
    """Ikeda's components of ``case``'s roll damping at ``amplitude_deg``, at the natural
    frequency of roll with added inertia from ``potential`` (a PotentialSummary of the case),
    whose radiation damping is the wave component."""
    check_amplitude(amplitude_deg)
    roll = potential.dof("roll")
    if roll.natural_frequency is None or roll.added_mass is None:
        raise InputError(f"case {case.name!r} does not oscillate in roll (no "
                         "natural frequency, which Ikeda's components need); valid: a section "
                         "with GM > 0")
    section = section_of(case, eq)
    length = float(case.body.length)
    omega, phi = float(roll.natural_frequency), math.radians(amplitude_deg)
    inertia = float(potential.mass_matrix[1][1]) + float(roll.added_mass)
    b_f = friction(section, phi, omega, case.rho, case.nu) * length
    b_e, e = eddy(section, phi, omega, case.rho)
    info = {**asdict(section), "H0": section.H0, "sigma": section.sigma, "length": length,
            "lewis": {"a1": e.a1, "a3": e.a3}, "gamma": e.gamma, "C_P": e.C_P,
            "r_max": e.r_max}
    return RollDamping(amplitude_deg, omega, inertia, b_f, b_e * length,
                       float(roll.radiation_damping or 0.0), 0.0, max(e.C_R, 0.0), info,
                       validity_flags(section, e), roll.coupled_damping_ratio)
