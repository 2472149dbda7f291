"""2D section radiation in water of finite depth (floatfoam.potential.sections_depth).

Checks: the Green function against John's eigenfunction series (an independent formula) and its
boundary conditions; the deep-water limit against sections.py; energy conservation (damping
from the pressure = damping from the radiated wave amplitude, Kochin function at finite depth);
the long-wave limit of the heave damping; the infinite-frequency images against the
high-frequency trend; symmetry of A and B; the lid against irregular frequencies.
No published 2D finite-depth table is used: none was available to check numbers against.
"""

import math

import numpy as np
import pytest

from floatfoam.bodies.shapes import EllipticCylinder
from floatfoam.potential import sections as deep
from floatfoam.potential import sections_depth as sd

G, RHO = 9.81, 1000.0


def _half_circle(radius=1.0):
    polygon = EllipticCylinder(radius, radius, 1.0).section_polygon()
    return deep.panel_nodes(deep.wetted_contour(polygon, 0.0, 0.0), deep.DEFAULT_PANELS)


def _heeled_ellipse():
    """An asymmetric wetted section (ellipse 2.4 m × 1.6 m, heeled 0.25 rad): all couplings."""
    polygon = EllipticCylinder(1.2, 0.8, 1.0).section_polygon()
    return deep.panel_nodes(deep.wetted_contour(polygon, -0.2, 0.25), deep.DEFAULT_PANELS)


def _john_series(X, z, zeta, nu, h, terms=40000):
    """G_h from John's (1950) eigenfunction expansion (no shared formula with the module):
    −4πi cosh k₀(z+h) cosh k₀(ζ+h) e^{ik₀|X|}/(sinh 2k₀h + 2k₀h)
    − Σ 4π cos kₙ(z+h) cos kₙ(ζ+h) e^{−kₙ|X|}/(sin 2kₙh + 2kₙh),  kₙ tan kₙh = −ν."""
    k0 = sd.wavenumber(nu, h)
    n = np.arange(1, terms + 1)
    lo, hi = (n - 0.5) * np.pi / h + 1e-13, n * np.pi / h - 1e-13
    for _ in range(100):  # bisection: kₙ tan kₙh + ν changes sign once on each branch
        mid = 0.5 * (lo + hi)
        negative = mid * np.tan(mid * h) + nu < 0
        lo, hi = np.where(negative, mid, lo), np.where(negative, hi, mid)
    kn = 0.5 * (lo + hi)
    wave = (-4j * np.pi * np.cosh(k0 * (z + h)) * np.cosh(k0 * (zeta + h))
            * np.exp(1j * k0 * abs(X)) / (np.sinh(2 * k0 * h) + 2 * k0 * h))
    return wave - np.sum(4 * np.pi * np.cos(kn * (z + h)) * np.cos(kn * (zeta + h))
                         * np.exp(-kn * abs(X)) / (np.sin(2 * kn * h) + 2 * kn * h))


@pytest.mark.parametrize("depth, nu", [(20.0, 0.25), (3.0, 1.0), (1.0, 0.3), (2.0, 1e-4),
                                       (20.0, 10.0)])
def test_green_function_against_john_series(depth, nu):
    """Ray integral + residues + deep-water function vs the eigenfunction series, at points from
    near the source (|X| = 0.02 m: 40 000 terms converge there) to 2.5 m, from the surface to
    near the bottom, νh from 2e-4 to 200. Measured ≤ 2e-8 of |G|; 1e-6 allows for the
    6-point ray panels (their error ~1e-8) and the series' truncation."""
    rng = np.random.default_rng(5)
    for _ in range(5):
        X, z, zeta = rng.uniform(0.02, 2.5), *rng.uniform(-0.98 * depth, 0.0, 2)
        value = sd.green_function_depth(np.array([[X, z]]), np.array([[0.0, zeta]]), nu, depth)
        reference = _john_series(X, z, zeta, nu, depth)
        assert abs(value[0, 0] - reference) < 1e-6 * max(1.0, abs(reference))


@pytest.mark.parametrize("nu", [1.3, 0.01, np.inf])
def test_green_function_boundary_conditions(nu):
    """∂G/∂z = νG on z = 0 (G = 0 for ν = ∞) and ∂G/∂z = 0 on z = −h, by central differences
    (step 1e-5 m: truncation ~1e-10, rounding ~1e-16/1e-5 = 1e-11 of |G|, ray quadrature ~1e-8;
    measured ≤ 1e-8)."""
    depth, step = 2.0, 1e-5
    source = np.array([[0.3, -0.7]])
    y = np.linspace(-3.0, 3.0, 7)

    def dg_dz(z):
        up = sd.green_function_depth(np.column_stack([y, np.full(7, z + step)]), source, nu, depth)
        down = sd.green_function_depth(np.column_stack([y, np.full(7, z - step)]), source, nu,
                                       depth)
        return (up - down) / (2 * step)

    surface = sd.green_function_depth(np.column_stack([y, np.zeros(7)]), source, nu, depth)
    if np.isinf(nu):
        assert np.abs(surface).max() < 1e-12
    else:
        assert np.abs(dg_dz(0.0) - nu * surface).max() < 1e-6 * np.abs(surface).max()
    assert np.abs(dg_dz(-depth)).max() < 1e-6 * np.abs(surface).max() + 1e-9


@pytest.mark.parametrize("nu", [1.3, 0.01, np.inf])
def test_smooth_part_derivatives(nu):
    """The source derivatives ∂/∂η, ∂/∂ζ of the smooth parts M (finite ν) and T (ν = ∞) used in
    ∂G/∂n_ξ agree with central differences of the values (step 1e-6 m; measured ≤ 5e-9,
    1e-6 allowed: rounding ~1e-16/1e-6 of |M| ≤ 20, and the ray quadrature)."""
    rng = np.random.default_rng(2)
    depth, step = 2.0, 1e-6
    X, z, zeta = rng.uniform(-3, 3, 7), *rng.uniform(-1.9, 0.0, (2, 7))

    def part(X, zeta):
        if np.isinf(nu):
            return sd._image_remainder(X, z, zeta, depth)
        return sd._remainder(X, z, zeta, nu, depth)

    _, d_eta, d_zeta = part(X, zeta)
    assert np.abs(d_eta - (part(X - step, zeta)[0] - part(X + step, zeta)[0]) / (2 * step)
                  ).max() < 1e-6
    assert np.abs(d_zeta - (part(X, zeta + step)[0] - part(X, zeta - step)[0]) / (2 * step)
                  ).max() < 1e-6


def test_deep_water_limit():
    """h = 20 m for a 2.4 m wide, 1 m deep heeled ellipse, k₀h ≥ 12.8: the finite-depth A and B
    equal the deep-water ones of sections.py within 0.5 % (largest gap measured 0.26 %: heave
    A∞, heave and roll damping; sway within 1e-4, 3e-4 allowed); depth = inf is sections.py
    exactly. The gap is physical, not numerical: the local (non-wave) field of the heaving
    section reaches the bottom, and it falls like h⁻² (its ratio between h = 20 m and 40 m is
    4.0, measured; 3 to 5 allowed)."""
    nodes, centre = _heeled_ellipse(), (0.0, -0.1)
    omegas = np.array([0.8, 1.0, 1.5]) * math.sqrt(G)
    ref = deep.radiation_coefficients_2d(nodes, [*omegas, np.inf], centre=centre)
    same = sd.radiation_coefficients_2d_depth(nodes, [1.0], depth=np.inf, centre=centre)
    assert np.array_equal(same["added_mass"][0], deep.radiation_coefficients_2d(
        nodes, [1.0], centre=centre)["added_mass"][0])
    gaps = {}
    for depth in (20.0, 40.0):
        res = sd.radiation_coefficients_2d_depth(nodes, [*omegas, np.inf], depth=depth,
                                                 centre=centre)
        gaps[depth] = []
        for key in ("added_mass", "damping"):
            a, b = np.diagonal(ref[key], axis1=1, axis2=2), np.diagonal(res[key], axis1=1, axis2=2)
            gaps[depth].append(np.abs(b - a) / np.where(a > 0, a, 1.0))
        gaps[depth] = np.concatenate(gaps[depth])
    assert gaps[20.0].max() < 5e-3
    assert gaps[20.0][:, 0].max() < 3e-4
    assert 3.0 < gaps[20.0].max() / gaps[40.0].max() < 5.0


def _far_field_damping(nodes, omega, depth, centre):
    """B_jj from the radiated waves: φ_j → −2i C cosh k₀(z+h) H± e^{ik₀|y|} as y → ±∞ with
    C = 1/(sinh 2k₀h + 2k₀h) and the Kochin function H± = ∫ (n_j − φ_j ∂/∂n) cosh k₀(ζ+h)
    e^{∓ik₀η} dl (Green's identity with the outgoing wave of G); wave amplitude
    |A±| = (ω/g)|φ(z=0)|, energy flux ½ρg|A±|² c_g, c_g = ω/(2k₀) (1 + 2k₀h/sinh 2k₀h),
    so B_jj = ρ g c_g (|A₊|² + |A₋|²) for a unit velocity (Newman 1977, §6.14–6.18)."""
    _, _, length, normal, mid, n_modes = sd._panels(nodes, centre)
    phi = sd.radiation_potentials_depth(nodes, omega, depth=depth, centre=centre, g=G)
    k0 = sd.wavenumber(omega * omega / G, depth)
    c = 1.0 / (np.sinh(2 * k0 * depth) + 2 * k0 * depth)
    total = np.zeros(3)
    for side in (1.0, -1.0):
        phase = np.exp(-1j * side * k0 * mid[:, 0])
        profile = np.cosh(k0 * (mid[:, 1] + depth)) * phase
        d_profile = (normal[:, 0] * (-1j * side * k0) * profile
                     + normal[:, 1] * k0 * np.sinh(k0 * (mid[:, 1] + depth)) * phase)
        kochin = (n_modes * profile[:, None] - phi * d_profile[:, None]).T @ length
        total += (omega / G * 2 * c * np.cosh(k0 * depth) * np.abs(kochin)) ** 2
    group = omega / (2 * k0) * (1 + 2 * k0 * depth / np.sinh(2 * k0 * depth))
    return RHO * G * group * total


@pytest.mark.parametrize("omega_nd", [0.3, 0.8, 1.5])
def test_damping_equals_radiated_energy(omega_nd):
    """Energy conservation at h = 1.5 m (k₀h = 0.39 to 3.4): the pressure damping and the
    far-field damping agree within 0.5 % for sway, heave and roll (measured ≤ 0.22 %, the
    panel error of the two integrals, growing like (k₀ Δl)²). A wrong wave amplitude factor C
    or depth profile in G would break it (e.g. dropping 2k₀h halves C at k₀h = 0.39)."""
    nodes, centre, depth = _heeled_ellipse(), (0.0, -0.2), 1.5
    omega = omega_nd * math.sqrt(G)
    res = sd.radiation_coefficients_2d_depth(nodes, [omega], depth=depth, centre=centre)
    far = _far_field_damping(nodes, omega, depth, centre)
    assert np.diag(res["damping"][0]) == pytest.approx(far, rel=5e-3)


def test_long_wave_limit():
    """ω → 0 at h = 2a: the heaving section pushes a flux U·b (b the waterline beam) into two
    long waves of speed √(gh): energy flux ρU²b²√(gh)/(4h) = ½ B U², so B₃₃ → ρ b² √(g/h)/2
    (shallow-water theory; correction O((k₀h)²) = 2e-4 here, measured 4e-5; 1e-3 allowed).
    The heave added mass tends to a finite value (0.4984 ρπa²/2 at h = 2a): within 0.1 % from
    ω√(a/g) = 0.003 to 0.03 (measured 0.01 %), where the deep-water one grows by 70 %."""
    omegas = np.array([0.003, 0.01, 0.03]) * math.sqrt(G)
    res = sd.radiation_coefficients_2d_depth(_half_circle(), omegas, depth=2.0)
    limit = RHO * 2.0 ** 2 * math.sqrt(G / 2.0) / 2.0
    assert res["damping"][1, 1, 1] == pytest.approx(limit, rel=1e-3)
    heave = res["added_mass"][:, 1, 1]
    assert heave[0] == pytest.approx(heave[2], rel=1e-3)
    deep_heave = deep.radiation_coefficients_2d(_half_circle(), omegas)["added_mass"][:, 1, 1]
    assert deep_heave[0] > 1.5 * deep_heave[2]


def test_infinite_frequency_images_against_high_frequencies():
    """The depth effect ΔA = A_h − A_deep at ω√(a/g) = 6 and 8, extrapolated as A∞ + c/ν
    (Richardson), equals ΔA∞ from the tanh image sum, at h = 1.3a where it is large (ΔA₃₃ =
    0.66 ρπa²/2): the infinite-frequency Green function and the finite-frequency one were
    derived separately. Measured 0.02 % (heave) and 0.08 % (sway) of ΔA∞; 1 % allowed."""
    nodes, depth = _half_circle(), 1.3
    omegas = [6.0 * math.sqrt(G), 8.0 * math.sqrt(G), np.inf]
    res = sd.radiation_coefficients_2d_depth(nodes, omegas, depth=depth)
    ref = deep.radiation_coefficients_2d(nodes, omegas)
    for j in (0, 1):
        gap = res["added_mass"][:, j, j] - ref["added_mass"][:, j, j]
        extrapolated = (64.0 * gap[1] - 36.0 * gap[0]) / 28.0
        assert extrapolated == pytest.approx(gap[2], rel=0.01)


def test_symmetric_matrices_and_positive_damping():
    """Asymmetric section at h = 1.5 m: A and B symmetric to 1e-3 of their largest term
    (measured 3e-4, as in deep water: the constant-panel discretisation of Green's identity is
    not exactly symmetric), B_jj ≥ 0, B = 0 at ω = ∞."""
    omegas = [*(np.array([0.4, 1.0, 1.6]) * math.sqrt(G)), np.inf]
    res = sd.radiation_coefficients_2d_depth(_heeled_ellipse(), omegas, depth=1.5,
                                             centre=(0.1, -0.1))
    for key in ("added_mass", "damping"):
        m = res[key][:-1] if key == "damping" else res[key]
        asym = np.abs(m - m.transpose(0, 2, 1)).max(axis=(1, 2))
        assert (asym < 1e-3 * np.abs(m).max(axis=(1, 2))).all()
    assert (np.diagonal(res["damping"][:-1], axis1=1, axis2=2) > 0).all()
    assert np.all(res["damping"][-1] == 0.0)


def test_lid_removes_irregular_frequencies_at_finite_depth():
    """As in deep water (test_potential): without the lid the half cylinder at h = 1.5a shows
    spikes near ω√(a/g) ≈ 2.2, 2.5, 2.8 (second difference 9e-3 of A₃₃, measured); with it
    A(ω) is smooth (7e-4)."""
    omegas = np.linspace(2.0, 3.0, 21) * math.sqrt(G)
    nodes = _half_circle()
    curvature = {}
    for lid in (False, True):
        a = sd.radiation_coefficients_2d_depth(nodes, omegas, depth=1.5, lid=lid)["added_mass"]
        curvature[lid] = max(np.abs(np.diff(a[:, 1, 1], 2)).max(),
                             np.abs(np.diff(a[:, 0, 0], 2)).max()) / a[:, 1, 1].mean()
    assert curvature[True] < 2e-3 < curvature[False]


def test_section_reaching_the_bottom_is_refused():
    with pytest.raises(ValueError, match="bottom"):
        sd.radiation_coefficients_2d_depth(_half_circle(), [3.0], depth=0.9)
