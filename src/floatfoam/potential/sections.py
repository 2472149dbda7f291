"""Two-dimensional radiation problem of a floating section: added mass and damping per metre.

Potential flow around a horizontal prism (a 2D section in the (y, z) plane, z up, fluid z < 0,
deep water), time dependence e^{-iωt}, ν = ω²/g. The radiation potential φ_j of mode j (unit
velocity) satisfies ∂φ_j/∂n = n_j on the wetted contour S (n out of the body), the free-surface
condition ∂φ/∂z − νφ = 0 on z = 0 and the outgoing-wave condition. Green's second identity
with the free-surface Green function G (Wehausen & Laitone 1960, §13; Newman 1977, §6.15)

    G = ln r − ln r₁ − 2 PV∫₀^∞ e^{k(z+ζ)} cos k(y−η) / (k − ν) dk − 2πi e^{ν(z+ζ)} cos ν(y−η)
      = ln r + ln r₁ − 2 Re[e^{νw} E₁(νw) + ln w] + 2π e^{νY} sin ν|X| − 2πi e^{νY} cos νX,

with X = y − η, Y = z + ζ, w = Y + i|X|, r₁ the distance to the image point (η, −ζ), gives the
direct boundary integral equation (constant panels, midpoint collocation)

    π φ(x) + ∫_S φ ∂G/∂n_ξ dl = ∫_S G n_j dl.

The Rankine parts ln r and ln r₁ are integrated analytically on each straight panel; the
remainder is smooth and integrated by Gauss–Legendre quadrature. Irregular frequencies are
removed by the extended boundary integral equation (Ohmatsu 1975; Kleinman 1982): Green's
identity with the field point on the interior free surface (the lid, outside the fluid) gives
0 = ∫_S (φ ∂G/∂n_ξ − G n_j) dl, and the over-determined system is solved by least squares.

Forces: A_ij + i B_ij / ω = −ρ ∫_S φ_j n_i dl per unit length. Modes: sway (y), heave (z) and
roll (rotation about the x axis through ``centre``), n_roll = (y − y_G) n_z − (z − z_G) n_y.
At infinite frequency φ = 0 on z = 0 and G = ln r − ln r₁ (A∞, used by the Cummins model).
"""

from __future__ import annotations

import numpy as np
from scipy.special import exp1

MODES = ("sway", "heave", "roll")
DEFAULT_PANELS = 64  # wetted panels: half cylinder within 0.3 % of Ursell (1949), see tests
GAUSS_POINTS = 4
CORNER_ANGLE = np.radians(15.0)  # turning angle above which a polygon vertex is kept exactly


def wetted_contour(polygon: np.ndarray, z_c: float, heel: float) -> np.ndarray:
    """Wetted part of a CCW section polygon (y, z) placed at ``z_c``, heeled by ``heel``.

    Returns the earth-frame polyline (K, 2) from the left waterline point, under the keel, to the
    right one (the CCW order of the body), with both end points exactly on z = 0; for a fully
    submerged section the closed polygon (first point repeated at the end).
    """
    c, s = np.cos(heel), np.sin(heel)
    p = np.column_stack([c * polygon[:, 0] - s * polygon[:, 1],
                         s * polygon[:, 0] + c * polygon[:, 1] + z_c])
    below = p[:, 1] < 0.0
    if below.all():
        return np.concatenate([p, p[:1]])
    if not below.any():
        raise ValueError(f"the section is out of the water (z_c={z_c:.6g} m)")
    k = len(p)
    entries = [i for i in range(k) if not below[i] and below[(i + 1) % k]]
    if len(entries) != 1:
        raise ValueError("the wetted section has several parts; only one waterline pair "
                         "is supported (convex sections)")
    i0 = entries[0]
    points = [_crossing(p[i0], p[(i0 + 1) % k])]
    i = (i0 + 1) % k
    while below[i]:
        points.append(p[i])
        i = (i + 1) % k
    points.append(_crossing(p[i - 1], p[i]))
    return np.array(points)


def _crossing(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    t = a[1] / (a[1] - b[1])
    return np.array([a[0] + t * (b[0] - a[0]), 0.0])


def panel_nodes(contour: np.ndarray, panels: int = DEFAULT_PANELS) -> np.ndarray:
    """Nodes of about ``panels`` straight panels along a polyline, equally spaced in arc length
    between its corners (vertices turning by more than 15°), which are kept exactly."""
    seg = np.diff(contour, axis=0)
    keep = np.linalg.norm(seg, axis=1) > 1e-12 * np.abs(contour).max()
    contour = np.concatenate([contour[:1], contour[1:][keep]])
    seg = np.diff(contour, axis=0)
    heading = np.arctan2(seg[:, 1], seg[:, 0])
    turn = np.abs(np.angle(np.exp(1j * np.diff(heading))))
    breaks = [0, *(np.nonzero(turn > CORNER_ANGLE)[0] + 1), len(contour) - 1]
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(seg, axis=1))])
    nodes = [contour[:1]]
    for a, b in zip(breaks[:-1], breaks[1:], strict=True):
        n = max(1, round(panels * (arc[b] - arc[a]) / arc[-1]))
        s = np.linspace(arc[a], arc[b], n + 1)[1:]
        nodes.append(np.column_stack([np.interp(s, arc[a:b + 1], contour[a:b + 1, i])
                                      for i in range(2)]))
    return np.concatenate(nodes)


def _rankine(x: np.ndarray, p: np.ndarray, q: np.ndarray, n: np.ndarray):
    """∫ ln|x − ξ| dl and ∫ ∂/∂n_ξ ln|x − ξ| dl over straight panels p→q (normal n), exactly.

    With u the abscissa along the panel and h the distance of x from its line,
    ∫ ln√(u² + h²) du = u ln√(u² + h²) − u + h atan(u/h) and the normal-derivative integral is
    −[atan(u/h)], i.e. minus the angle the panel subtends at x.
    Shapes: x (M, 2), panels (N, 2) → (M, N).
    """
    length = np.linalg.norm(q - p, axis=1)
    t = (q - p) / length[:, None]
    d = x[:, None, :] - p[None, :, :]
    u1 = -np.einsum("mnk,nk->mn", d, t)
    u2 = u1 + length[None, :]
    h = np.einsum("mnk,nk->mn", d, n)
    ah = np.abs(h)

    def primitive(u):
        rr = u * u + h * h
        with np.errstate(divide="ignore", invalid="ignore"):
            log_term = np.where(rr > 0.0, 0.5 * u * np.log(np.where(rr > 0, rr, 1.0)), 0.0)
        return log_term - u + ah * np.arctan2(u, ah)

    single = primitive(u2) - primitive(u1)
    # a point within 1e-9 of a panel length of its line is on it (the self term, whose
    # principal value is 0): its h is round-off of the coordinates, ~1e-16 of |x|, which
    # exceeded the former 1e-14 × length on panels shorter than 1 % of |x| and made the self
    # term ±π (768 panels on a half circle of radius 1: A∞ came out negative)
    tiny = 1e-9 * length[None, :]
    safe_h = np.where(ah > tiny, h, 1.0)
    double = np.where(ah > tiny, -(np.arctan(u2 / safe_h) - np.arctan(u1 / safe_h)), 0.0)
    return single, double


ASYMPTOTIC_E1 = 40.0  # |z| above which e^z E1(z) is its asymptotic series (error < 1e-11)


def _exp_e1(z: np.ndarray) -> np.ndarray:
    """e^z E1(z) for Re z ≤ 0: scipy's product where |z| ≤ 40, the asymptotic series
    Σ (−1)ⁿ n!/z^{n+1}, n ≤ 10 (Abramowitz & Stegun 5.1.51) beyond, where e^z underflows and
    E1 overflows (deep points at high frequency: there scipy's product is 0 × inf = nan)."""
    far = np.abs(z) > ASYMPTOTIC_E1
    if not far.any():
        return np.exp(z) * exp1(z)
    out = np.empty_like(z)
    near = ~far
    out[near] = np.exp(z[near]) * exp1(z[near])
    inverse = 1.0 / z[far]
    series = np.zeros_like(inverse)
    term = inverse.copy()
    for n in range(11):
        series += term
        term = term * (-(n + 1)) * inverse
    out[far] = series
    return out


def _wave_part(X: np.ndarray, Y: np.ndarray, nu: float):
    """Smooth remainder W̃ = G − ln r − ln r₁ and its derivatives ∂W̃/∂X, ∂W̃/∂Y (module doc)."""
    w = Y + 1j * np.abs(X)
    z = nu * w
    z = np.where(np.abs(z) > 0.0, z, 1e-300 + 0j)
    f = _exp_e1(z)
    ey = np.exp(nu * Y)
    sin_x, cos_x = np.sin(nu * np.abs(X)), np.cos(nu * X)
    sgn = np.sign(X)
    value = (-2.0 * np.real(f + np.log(z)) + 2.0 * np.log(nu)
             + 2 * np.pi * ey * sin_x - 2j * np.pi * ey * cos_x)
    d_y = -2.0 * nu * np.real(f) + 2 * np.pi * nu * ey * sin_x - 2j * np.pi * nu * ey * cos_x
    d_x = (2.0 * sgn * nu * np.imag(f) + 2 * np.pi * nu * ey * cos_x * sgn
           + 2j * np.pi * nu * ey * np.sin(nu * X))
    return value, d_x, d_y


def _influence(x: np.ndarray, p: np.ndarray, q: np.ndarray, n: np.ndarray, nu: float):
    """Single- and double-layer influence matrices S_mn = ∫_n G(x_m, ξ) dl and
    D_mn = ∫_n ∂G/∂n_ξ dl; ``nu = inf`` gives the infinite-frequency Green function."""
    s_direct, d_direct = _rankine(x, p, q, n)
    flip = np.array([1.0, -1.0])
    s_image, d_image = _rankine(x, p * flip, q * flip, n * flip)
    if np.isinf(nu):
        return (s_direct - s_image).astype(complex), (d_direct - d_image).astype(complex)
    s_mat = (s_direct + s_image).astype(complex)
    d_mat = (d_direct + d_image).astype(complex)
    g, wg = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    length = np.linalg.norm(q - p, axis=1)
    for gk, wk in zip(g, wg, strict=True):
        xi = 0.5 * (p + q) + 0.5 * gk * (q - p)
        X = x[:, None, 0] - xi[None, :, 0]
        Y = x[:, None, 1] + xi[None, :, 1]
        value, d_x, d_y = _wave_part(X, Y, nu)
        weight = 0.5 * wk * length[None, :]
        s_mat += weight * value
        # ∂/∂η = −∂/∂X and ∂/∂ζ = +∂/∂Y
        d_mat += weight * (-n[None, :, 0] * d_x + n[None, :, 1] * d_y)
    return s_mat, d_mat


def radiation_coefficients_2d(nodes: np.ndarray, omegas, *, centre=(0.0, 0.0), rho=1000.0,
                              g=9.81, lid: bool = True) -> dict:
    """Added mass A(ω) and radiation damping B(ω) per unit length of a 2D section.

    Parameters
    ----------
    nodes : (N+1, 2) panel end points (y, z) along the wetted contour, in the body's CCW order
        (left waterline → keel → right waterline), earth frame.
    omegas : angular frequencies (rad/s); ``np.inf`` gives the infinite-frequency limit.
    centre : (y, z) of the roll axis (the centre of gravity G), m.
    rho, g : water density (kg/m³) and gravity (m/s²).
    lid : remove irregular frequencies by the extended integral equation (module docstring).

    Returns
    -------
    dict with ``omega`` (n,), ``added_mass`` and ``damping`` (n, 3, 3) for the modes
    ``MODES`` = (sway, heave, roll): kg/m, kg·m/m, kg·m²/m (and N·s/m per metre likewise).
    """
    p, q = nodes[:-1], nodes[1:]
    length = np.linalg.norm(q - p, axis=1)
    tangent = (q - p) / length[:, None]
    normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])  # right of a CCW contour: outward
    mid = 0.5 * (p + q)
    y_g, z_g = centre
    n_modes = np.column_stack([normal[:, 0], normal[:, 1],
                               (mid[:, 0] - y_g) * normal[:, 1] - (mid[:, 1] - z_g) * normal[:, 0]])
    lid_points = _lid_points(nodes, length.mean()) if lid else np.empty((0, 2))
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    added_mass = np.empty((len(omegas), 3, 3))
    damping = np.empty((len(omegas), 3, 3))
    for k, omega in enumerate(omegas):
        nu = omega * omega / g
        s_mat, d_mat = _influence(mid, p, q, normal, nu)
        lhs = np.pi * np.eye(len(mid)) + d_mat
        rhs = s_mat @ n_modes
        if len(lid_points) and np.isfinite(nu):
            s_lid, d_lid = _influence(lid_points, p, q, normal, nu)
            lhs = np.vstack([lhs, d_lid])
            rhs = np.vstack([rhs, s_lid @ n_modes])
            phi = np.linalg.lstsq(lhs, rhs, rcond=None)[0]
        else:
            phi = np.linalg.solve(lhs, rhs)
        force = -rho * (n_modes * length[:, None]).T @ phi  # [i, j] = −ρ ∫ φ_j n_i dl
        added_mass[k] = force.real
        damping[k] = 0.0 if np.isinf(omega) else omega * force.imag
    return {"omega": omegas, "added_mass": added_mass, "damping": damping, "modes": MODES}


def _lid_points(nodes: np.ndarray, spacing: float) -> np.ndarray:
    """Field points on the interior free surface between the two waterline points."""
    if not (abs(nodes[0, 1]) < 1e-12 and abs(nodes[-1, 1]) < 1e-12):
        return np.empty((0, 2))  # fully submerged: no interior free surface
    left, right = sorted([nodes[0, 0], nodes[-1, 0]])
    count = max(2, int(np.ceil((right - left) / spacing)))
    y = left + (right - left) * (np.arange(count) + 0.5) / count
    return np.column_stack([y, np.zeros(count)])
