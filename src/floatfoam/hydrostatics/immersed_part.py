"""The immersed part of a body at one attitude: the record every hydrostatic path returns."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Immersed:
    """Immersed part of a body at one attitude, in the earth frame (z up, free surface z = 0).

    Attributes
    ----------
    volume : immersed volume V (m³; for a 2D section, for its length L)
    centroid : centre of buoyancy B (3,) in m
    waterplane_area : A_wp (m²)
    waterplane_centroid : (x_f, y_f) centre of flotation, m
    waterplane_inertia : (I_xx, I_yy, I_xy) second moments of the waterplane about axes through
        its centroid: I_xx = ∫(y − y_f)² dA (roll), I_yy = ∫(x − x_f)² dA (pitch), m⁴
    exact : True when computed from a closed form
    """

    volume: float
    centroid: np.ndarray
    waterplane_area: float
    waterplane_centroid: np.ndarray
    waterplane_inertia: np.ndarray
    exact: bool = False


def nothing_immersed(exact: bool = False) -> Immersed:
    """The record of a body entirely out of the water (``exact``: from a closed form)."""
    return Immersed(0.0, np.zeros(3), 0.0, np.zeros(2), np.zeros(3), exact=exact)
