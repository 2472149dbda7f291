"""Two-dimensional radiation problem of a floating section in water of finite depth.

Same problem, unknowns and method as :mod:`floatfoam.potential.sections` (constant panels,
midpoint collocation, π φ + ∫ φ ∂G/∂n_ξ dl = ∫ G n_j dl, lid points against irregular
frequencies, A_ij + i B_ij/ω = −ρ ∫ φ_j n_i dl), with a flat bottom at z = −h where ∂φ/∂z = 0.
Time dependence e^{-iωt}, ν = ω²/g and k₀ tanh k₀h = ν.

Green function of the pulsating source in finite depth (John 1950, Comm. Pure Appl. Math. 3,
45–101; Wehausen & Laitone 1960, Surface Waves, §13), derived here again: with X = y − η,
d = |z − ζ|, Y = z + ζ, its cosine transform in X solves the vertical problem exactly,

    G_h = PV∫₀^∞ g(k) cos kX dk + πi Res_{k=k₀} g(k) e^{ik|X|}  (outgoing: path below k₀),
    g = −(E/k) [e^{−kd} + e^{−k(Y+2h)} + R e^{kY} + R e^{k(d−2h)}],
    R = (k + ν)/(k − ν),  ε = e^{−2kh},  E = 1/(1 − Rε),

whose pole k₀ gives the outgoing wave −2πi e^{k₀Y} m(z) m(ζ) e^{ik₀|X|}/Δ, m(z) = 1 + e^{−2k₀(z+h)},
Δ = 1 − e^{−4k₀h} + 4k₀h e^{−2k₀h} (= −4πi cosh k₀(z+h) cosh k₀(ζ+h) e^{ik₀|X|}/(sinh 2k₀h + 2k₀h)).
−(e^{−kd} + R e^{kY})/k is the transform of the deep-water function G_d of sections.py (ln r,
ln r₁ and the E₁ wave part), −e^{−k(Y+2h)}/k that of ln r₂, r₂ the distance to the bottom image
(η, −2h − ζ).
Hence, with L = 2h,

    G_h = G_d + ln(r₂/L) + M,
    M = Re ∫_ray F(k) dk + W_h − W_d,
    F = −(S/k) ε [2 cosh kd + ε e^{−kY} + R e^{kY}] e^{ik|X|} − e^{−kL}/k,  S = R E,

W_h − W_d the k₀ wave above minus the deep one, −2πi e^{νY + iν|X|}. The cos kX integral is split
into e^{±ik|X|} halves turned onto the rays arg k = ±π/4 (conjugate halves, hence Re; the upper
one picks the residues at ν and k₀, the other poles of S being imaginary, ±ik_n). On the ray F
decays like e^{−k(2h − d)} at least, d < h: M is smooth, its singularities (images) lie ≥ h from
the fluid. ln r, ln r₁ (sections.py) and ln r₂ are integrated analytically per panel,
G_d − ln r − ln r₁ by four Gauss points (sections.py), M at the panel midpoint (a second point
changes A, B by < 1e-5 of the largest coefficient, measured), the ray integral by 6-point
Gauss–Legendre panels [0, τ], [τ, 2τ], [2τ, 4τ] … (τ = min(ν, 1/h)/2) up to F < e^{−30}; the
exponentials of each panel are the squares of the previous one's. G_h agrees with John's
eigenfunction series to ~1e-8 (tests). Cost: ~20 ms per frequency for 64 panels on top of
sections.py's. Small keel clearances need panels shorter than the gap (flow under the keel).

At infinite frequency (φ = 0 on z = 0, ∂φ/∂z = 0 on z = −h) the images ζ + 2hm carry the sign
(−1)^m and −ζ + 2hm the sign −(−1)^m; the series sums to (with c = π/4h)

    G_h^∞ = ln|tanh c(X + i(z − ζ))| − ln|tanh c(X + i(z + ζ))| = ln r − ln r₁ + ln r₂ + T,

T smooth (midpoint rule as for M). Deep-water limit: the waves differ by O(e^{−2k₀h}) but the
local (non-wave) field of a heaving section feels the bottom algebraically: the coefficients
tend to those of sections.py like h⁻² (half-immersed circle of radius a, h = 20a: heave 0.9 %
apart at k₀h = 5, ≤ 0.2 % at k₀h ≥ 12.8 and at ω = ∞, sway within 4e-4; measured, see tests).
Low frequency: the heave damping tends to the long-wave value ρ b² √(g/h) / 2 (b the waterline
beam), the added mass to a finite value (in deep water it grows like ln ν).
"""

from __future__ import annotations

import numpy as np

from floatfoam.potential.sections import (
    MODES,
    _influence,
    _lid_points,
    _rankine,
    _wave_part,
)

REMAINDER_POINTS = 1  # Gauss points per panel for the smooth corrections M and T
RAY_ANGLE = np.pi / 4
RAY_POINTS = 6  # Gauss–Legendre points per ray panel
RAY_DECAY = 30.0  # the ray ends where F < e^{-30} (relative)


def wavenumber(nu: float, depth: float) -> float:
    """Root k₀ of k tanh(kh) = ν by Newton's method from the upper bound x² /(1 + x) = νh."""
    c = nu * depth
    x = 0.5 * (c + np.sqrt(c * c + 4.0 * c))
    for _ in range(100):
        t = np.tanh(x)
        step = (x * t - c) / (t + x * (1.0 - t * t))
        x -= step
        if abs(step) < 1e-15 * x:
            break
    return x / depth


def _ray(nu: float, depth: float, span: float):
    """Nodes k and weights dk on the ray arg k = π/4: Gauss–Legendre on [0, τ], τ = min(ν, 1/h)/2,
    then on panels [2ⁱτ, 2ⁱ⁺¹τ] until e^{−k(2h − span) cos π/4} < e^{−30}, ``span`` the largest
    |z − ζ| (the slowest decay of F). Returns k, dk and the panel count (≥ 2)."""
    first = 0.5 * min(nu, 1.0 / depth)
    t_max = RAY_DECAY / ((2.0 * depth - span) * np.cos(RAY_ANGLE))
    count = max(2, 1 + int(np.ceil(np.log2(t_max / first))))
    edges = np.concatenate([[0.0], first * 2.0 ** np.arange(count)])
    x, w = np.polynomial.legendre.leggauss(RAY_POINTS)
    half = 0.5 * np.diff(edges)[:, None]
    t = (0.5 * (edges[1:] + edges[:-1])[:, None] + half * x).ravel()
    rotation = np.exp(1j * RAY_ANGLE)
    return t * rotation, (half * w).ravel() * rotation, count


def _ray_exp(u: np.ndarray, k: np.ndarray, count: int) -> np.ndarray:
    """e^{k u} (P, J) at the ray nodes. Panel 1 is panel 0 shifted by τ (one more exponential);
    panel i ≥ 2 holds the nodes of panel 1 times 2^{i−1}, so its exponentials are the squares of
    the previous panel's (exact to ~2^count ulp)."""
    first = np.exp(np.outer(u, k[:RAY_POINTS]))
    block = first * np.exp(u * (k[RAY_POINTS] - k[0]))[:, None]
    blocks = [first, block]
    for _ in range(count - 2):
        block = block * block
        blocks.append(block)
    return np.concatenate(blocks, axis=1)


def _remainder(X, z, zeta, nu: float, depth: float):
    """M(X, z, ζ) = G_h − G_d − ln(r₂/2h) and its derivatives ∂M/∂η, ∂M/∂ζ (module docstring)."""
    shape = np.shape(X)
    ax, Y = np.abs(X).ravel(), (z + zeta).ravel()
    d, sd, sx = np.abs(z - zeta).ravel(), np.sign(z - zeta).ravel(), np.sign(X).ravel()
    k, dk, count = _ray(nu, depth, d.max())
    eps = np.exp(-2.0 * k * depth)
    s = (k + nu) / ((k - nu) - (k + nu) * eps) * eps / k * dk
    a, b, c = -s, -s * eps, -s * (k + nu) / (k - nu)
    constant = np.sum(dk * (-np.exp(-2.0 * k * depth) / k)).real
    e_up, e_down = _ray_exp(d + 1j * ax, k, count), _ray_exp(-d + 1j * ax, k, count)
    e_low, e_high = _ray_exp(-Y + 1j * ax, k, count), _ray_exp(Y + 1j * ax, k, count)
    value = (e_up + e_down) @ a + e_low @ b + e_high @ c
    d_x = sx * ((e_up + e_down) @ (1j * k * a) + e_low @ (1j * k * b) + e_high @ (1j * k * c)).real
    d_zeta = (-sd * ((e_up - e_down) @ (k * a)) - e_low @ (k * b) + e_high @ (k * c)).real
    wave, wave_x, wave_zeta = _wave_difference(ax, sx, Y, zeta.ravel(), nu, depth)
    return ((value.real + constant + wave).reshape(shape),
            -(d_x + wave_x).reshape(shape), (d_zeta + wave_zeta).reshape(shape))


def _wave_difference(ax, sx, Y, zeta, nu: float, depth: float):
    """W_h − W_d (the residues at k₀ and ν) and its derivatives in X and ζ (real parts)."""
    k0 = wavenumber(nu, depth)
    delta = 1.0 - np.exp(-4 * k0 * depth) + 4 * k0 * depth * np.exp(-2 * k0 * depth)
    z = Y - zeta
    m_z = 1.0 + np.exp(-2 * k0 * (z + depth))
    e_h = -2j * np.pi * np.exp(k0 * Y + 1j * k0 * ax) * m_z / delta
    w_h = e_h * (1.0 + np.exp(-2 * k0 * (zeta + depth)))
    w_deep = 2j * np.pi * np.exp(nu * Y + 1j * nu * ax)
    value = w_h + w_deep
    d_x = 1j * sx * (k0 * w_h + nu * w_deep)
    d_zeta = k0 * e_h * (1.0 - np.exp(-2 * k0 * (zeta + depth))) + nu * w_deep
    return value, d_x, d_zeta


def _image_remainder(X, z, zeta, depth: float):
    """T = G_h^∞ − ln r + ln r₁ − ln r₂ and its derivatives ∂T/∂η, ∂T/∂ζ (module docstring)."""
    c = np.pi / (4.0 * depth)
    total, d_eta, d_zeta = 0.0, 0.0, 0.0
    for w, sign, dw_zeta in ((X + 1j * (z - zeta), 1.0, -1j), (X + 1j * (z + zeta), -1.0, 1j)):
        u = c * w
        small = np.abs(u) < 1e-4
        safe = np.where(small, 1.0, u)
        ratio = np.where(small, 1.0 - u * u / 3.0, np.tanh(safe) / safe)  # tanh(cw)/(cw)
        slope = np.where(small, -2.0 * c * u / 3.0, c * (_csch(2 * safe) * 2.0 - 1.0 / safe))
        total = total + sign * np.log(np.abs(ratio))
        d_eta = d_eta - sign * slope.real
        d_zeta = d_zeta + sign * (slope * dw_zeta).real
    w2 = X + 1j * (z + zeta + 2.0 * depth)
    return total - np.log(np.abs(w2)), d_eta + (1.0 / w2).real, d_zeta - (1j / w2).real


def _csch(u):
    """1/sinh u without overflow for large |Re u|."""
    sign = np.where(u.real < 0, -1.0, 1.0)
    v = sign * u
    return sign * 2.0 * np.exp(-v) / (1.0 - np.exp(-2.0 * v))


def green_function_depth(field, source, nu: float, depth: float):
    """G_h at field points (M, 2) due to sources (N, 2) → (M, N), pointwise (for checks)."""
    X = field[:, None, 0] - source[None, :, 0]
    z, zeta = field[:, None, 1] + 0.0 * X, source[None, :, 1] + 0.0 * X
    r = np.log(np.hypot(X, z - zeta))
    r1 = np.log(np.hypot(X, z + zeta))
    r2 = np.log(np.hypot(X, z + zeta + 2.0 * depth))
    if np.isinf(nu):
        return r - r1 + r2 + _image_remainder(X, z, zeta, depth)[0]
    wave = _wave_part(X, z + zeta, nu)[0]
    return r + r1 + wave + r2 - np.log(2.0 * depth) + _remainder(X, z, zeta, nu, depth)[0]


def _influence_depth(x, p, q, n, nu: float, depth: float):
    """Influence matrices S_mn = ∫_n G_h(x_m, ξ) dl and D_mn = ∫_n ∂G_h/∂n_ξ dl."""
    s_mat, d_mat = _influence(x, p, q, n, nu)
    if np.isinf(depth):
        return s_mat, d_mat
    bottom = np.array([0.0, -2.0 * depth])
    flip = np.array([1.0, -1.0])
    s_image, d_image = _rankine(x, bottom + p * flip, bottom + q * flip, n * flip)
    s_mat = s_mat + s_image
    d_mat = d_mat + d_image
    g, wg = np.polynomial.legendre.leggauss(REMAINDER_POINTS)
    length = np.linalg.norm(q - p, axis=1)
    for gk, wk in zip(g, wg, strict=True):
        xi = 0.5 * (p + q) + 0.5 * gk * (q - p)
        X = x[:, None, 0] - xi[None, :, 0]
        z, zeta = x[:, None, 1] + 0.0 * X, xi[None, :, 1] + 0.0 * X
        if np.isinf(nu):
            value, d_eta, d_zeta = _image_remainder(X, z, zeta, depth)
        else:
            value, d_eta, d_zeta = _remainder(X, z, zeta, nu, depth)
            value = value - np.log(2.0 * depth)
        weight = 0.5 * wk * length[None, :]
        s_mat = s_mat + weight * value
        d_mat = d_mat + weight * (n[None, :, 0] * d_eta + n[None, :, 1] * d_zeta)
    return s_mat, d_mat


def _panels(nodes: np.ndarray, centre):
    """Panel end points, lengths, outward normals, midpoints and the modal normals n_j."""
    p, q = nodes[:-1], nodes[1:]
    length = np.linalg.norm(q - p, axis=1)
    tangent = (q - p) / length[:, None]
    normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])
    mid = 0.5 * (p + q)
    y_g, z_g = centre
    n_modes = np.column_stack([normal[:, 0], normal[:, 1],
                               (mid[:, 0] - y_g) * normal[:, 1] - (mid[:, 1] - z_g) * normal[:, 0]])
    return p, q, length, normal, mid, n_modes


def radiation_potentials_depth(nodes: np.ndarray, omega: float, *, depth: float,
                               centre=(0.0, 0.0), g=9.81, lid: bool = True) -> np.ndarray:
    """Panel values φ_j (N, 3) of the radiation potentials (unit velocities) at one frequency."""
    p, q, length, normal, mid, n_modes = _panels(nodes, centre)
    if nodes[:, 1].min() <= -depth:
        raise ValueError(f"the section reaches the bottom (depth {depth:.6g} m)")
    if not omega > 0.0:
        raise ValueError(f"the frequency must be positive (omega={omega:.6g} rad/s)")
    nu = omega * omega / g
    s_mat, d_mat = _influence_depth(mid, p, q, normal, nu, depth)
    lhs = np.pi * np.eye(len(mid)) + d_mat
    rhs = s_mat @ n_modes
    lid_points = _lid_points(nodes, length.mean()) if lid else np.empty((0, 2))
    if len(lid_points) and np.isfinite(nu):
        s_lid, d_lid = _influence_depth(lid_points, p, q, normal, nu, depth)
        return np.linalg.lstsq(np.vstack([lhs, d_lid]), np.vstack([rhs, s_lid @ n_modes]),
                               rcond=None)[0]
    return np.linalg.solve(lhs, rhs)


def radiation_coefficients_2d_depth(nodes: np.ndarray, omegas, *, depth: float,
                                    centre=(0.0, 0.0), rho=1000.0, g=9.81,
                                    lid: bool = True) -> dict:
    """Added mass A(ω) and radiation damping B(ω) per unit length of a 2D section in water of
    finite depth (module docstring).

    Parameters
    ----------
    nodes : (N+1, 2) panel end points (y, z) along the wetted contour, in the body's CCW order
        (left waterline → keel → right waterline), earth frame, all above z = −depth.
    omegas : angular frequencies (rad/s, > 0); ``np.inf`` gives the infinite-frequency limit.
    depth : water depth h (m), flat bottom at z = −h; ``np.inf`` is sections.py exactly.
    centre : (y, z) of the roll axis (the centre of gravity G), m.
    rho, g : water density (kg/m³) and gravity (m/s²).
    lid : remove irregular frequencies by the extended integral equation.

    Returns
    -------
    dict with ``omega`` (n,), ``added_mass`` and ``damping`` (n, 3, 3) for the modes
    ``MODES`` = (sway, heave, roll), as sections.radiation_coefficients_2d.
    """
    _, _, length, _, _, n_modes = _panels(nodes, centre)
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    added_mass = np.empty((len(omegas), 3, 3))
    damping = np.empty((len(omegas), 3, 3))
    for k, omega in enumerate(omegas):
        phi = radiation_potentials_depth(nodes, omega, depth=depth, centre=centre, g=g, lid=lid)
        force = -rho * (n_modes * length[:, None]).T @ phi  # [i, j] = −ρ ∫ φ_j n_i dl
        added_mass[k] = force.real
        damping[k] = 0.0 if np.isinf(omega) else omega * force.imag
    return {"omega": omegas, "added_mass": added_mass, "damping": damping, "modes": MODES}
