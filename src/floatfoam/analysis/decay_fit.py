"""Least-squares fits of a free-decay record, with 95 % confidence intervals.

Two models of the deviation y = x − x_eq − b s from a (possibly drifting) mean, s = t − t₀:

* **linear** (the solution of ÿ + 2ζω_n ẏ + ω_n² y = 0):
  y(s) = e^{−ζω_n s} (C cos ω_d s + S sin ω_d s),  ω_d = ω_n √(1 − ζ²);
* **linear + quadratic damping**: ÿ + 2ζω_n ẏ + c_q |ẏ| ẏ + ω_n² y = 0, integrated numerically
  from (y₀, ẏ₀); c_q is in 1/(unit of x).

The confidence intervals come from the Gauss–Newton covariance at the optimum,
cov = s² (JᵀJ)⁻¹ with s² = Σr²/(n − p), and Student's t with n − p degrees of freedom; derived
quantities (periods) use the delta method. They assume independent residuals: on a CFD record
whose misfit is correlated in time they are optimistic (see Press et al., *Numerical Recipes*,
§15.6, for the covariance; Journée & Massie 2001, *Offshore Hydromechanics*, ch. 6, for
decay tests and the fit of a damped sinusoid).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares
from scipy.stats import t as student_t

from floatfoam.errors import InputError

_ZETA_BOUNDS = (-0.5, 0.95)  # negative allowed so that an undamped record is not biased
_ZETA_GRID = (0.0, 0.01, 0.03, 0.06, 0.1, 0.15, 0.2, 0.3, 0.45)
_SEED_SAMPLES = 4000  # the grid search only needs the shape: thin long records for speed


@dataclass
class DecayFit:
    """Result of a least-squares fit of a decay model.

    Attributes
    ----------
    model : "linear" or "linear+quadratic"
    names : parameter names, in the order of ``values`` and ``cov``
    values, cov : optimum and its covariance matrix
    t0 : time origin s = t − t0 of the model, s
    equilibrium : fixed mean x_eq when it was given (then not a parameter), else None
    residual_rms : √(Σr²/(n − p)), in the unit of x
    dof : degrees of freedom n − p
    """

    model: str
    names: list[str]
    values: np.ndarray
    cov: np.ndarray
    t0: float
    equilibrium: float | None
    residual_rms: float
    dof: int
    t_quantile: float = field(init=False)

    def __post_init__(self):
        self.t_quantile = float(student_t.ppf(0.975, max(self.dof, 1)))

    def param(self, name: str, default: float = 0.0) -> float:
        """Fitted value of a parameter (``default`` when it is not in the model)."""
        return float(self.values[self.names.index(name)]) if name in self.names else default

    def ci95(self, grad: dict[str, float]) -> float:
        """95 % half-width of a quantity with gradient ``grad`` (delta method)."""
        g = np.array([grad.get(name, 0.0) for name in self.names])
        return self.t_quantile * math.sqrt(max(float(g @ self.cov @ g), 0.0))

    def mean_level(self, time) -> np.ndarray:
        """The (drifting) mean x_eq + b (t − t0)."""
        s = np.asarray(time, dtype=float) - self.t0
        x_eq = self.param("x_eq", self.equilibrium or 0.0)
        return x_eq + self.param("drift") * s

    def evaluate(self, time) -> np.ndarray:
        """The fitted record x(t)."""
        s = np.asarray(time, dtype=float) - self.t0
        return self.mean_level(time) + _oscillation(self, s)

    @property
    def zeta(self) -> float:
        return self.param("zeta")

    @property
    def omega_n(self) -> float:
        return self.param("omega_n")

    def damped_period(self) -> tuple[float, float]:
        """T_d = 2π/(ω_n √(1 − ζ²)) and its 95 % half-width."""
        zeta, omega = self.zeta, self.omega_n
        period = 2 * math.pi / (omega * math.sqrt(1 - zeta**2))
        grad = {"omega_n": -period / omega, "zeta": period * zeta / (1 - zeta**2)}
        return period, self.ci95(grad)

    def natural_period(self) -> tuple[float, float]:
        """T_n = 2π/ω_n and its 95 % half-width."""
        period = 2 * math.pi / self.omega_n
        return period, self.ci95({"omega_n": -period / self.omega_n})

    def damping_ratio(self) -> tuple[float, float]:
        """ζ (the linear part for the quadratic model) and its 95 % half-width."""
        return self.zeta, self.ci95({"zeta": 1.0})

    def initial_amplitude(self) -> float:
        """Amplitude of the oscillation about the mean at t0."""
        if self.model == "linear":
            return math.hypot(self.param("C"), self.param("S"))
        zeta, omega = self.zeta, self.omega_n
        y0, v0 = self.param("y0"), self.param("v0")
        omega_d = omega * math.sqrt(1 - zeta**2)
        return math.hypot(y0, (v0 + zeta * omega * y0) / omega_d)

    def envelope(self, time) -> np.ndarray:
        """Linear-damping envelope A e^{−ζω_n s} of the oscillation."""
        s = np.asarray(time, dtype=float) - self.t0
        return self.initial_amplitude() * np.exp(-self.zeta * self.omega_n * s)


def _linear_oscillation(s, C, S, zeta, omega):
    omega_d = omega * math.sqrt(1 - zeta**2)
    return np.exp(-zeta * omega * s) * (C * np.cos(omega_d * s) + S * np.sin(omega_d * s))


def _quadratic_oscillation(s, y0, v0, zeta, omega, c_q):
    def rhs(_, state):
        y, v = state
        return [v, -2 * zeta * omega * v - c_q * abs(v) * v - omega**2 * y]

    span = (0.0, float(s[-1]))
    sol = solve_ivp(rhs, span, [y0, v0], method="DOP853", t_eval=s, rtol=1e-10,
                    atol=1e-12 * max(abs(y0), abs(v0) / omega, 1e-30))
    if not sol.success or sol.y.shape[1] != s.size:
        return np.full(s.size, np.nan)
    return sol.y[0]


def _oscillation(fit: DecayFit, s) -> np.ndarray:
    p = fit.param
    if fit.model == "linear":
        return _linear_oscillation(s, p("C"), p("S"), p("zeta"), p("omega_n"))
    s = np.atleast_1d(s)
    out = np.full(s.size, np.nan)  # the integrated model starts at t0: nothing before
    ahead = s >= 0
    if np.any(ahead):
        out[ahead] = _quadratic_oscillation(s[ahead], p("y0"), p("v0"), p("zeta"),
                                            p("omega_n"), p("c_q"))
    return out


def _mean_columns(s, fixed_equilibrium: bool, drift: bool) -> tuple[list[str], list]:
    names, columns = [], []
    if not fixed_equilibrium:
        names.append("x_eq")
        columns.append(np.ones_like(s))
    if drift:
        names.append("drift")
        columns.append(s)
    return names, columns


def _seed_linear(s, y, omega_guess, mean_cols):
    """Grid search over (ω_n, ζ); the linear parameters solved exactly at each node."""
    stride = max(1, s.size // _SEED_SAMPLES)
    s_thin, y_thin = s[::stride], y[::stride]
    cols_thin = [c[::stride] for c in mean_cols]
    best = None
    for omega in omega_guess * np.geomspace(0.6, 1.6, 41):
        for zeta in _ZETA_GRID:
            omega_d = omega * math.sqrt(1 - zeta**2)
            decay = np.exp(-zeta * omega * s_thin)
            basis = np.column_stack(
                cols_thin + [decay * np.cos(omega_d * s_thin), decay * np.sin(omega_d * s_thin)])
            coef, *_ = np.linalg.lstsq(basis, y_thin, rcond=None)
            ssr = float(np.sum((basis @ coef - y_thin) ** 2))
            if best is None or ssr < best[0]:
                best = (ssr, list(coef) + [zeta, omega])
    return np.array(best[1])


def _linear_jacobian(params, s, n_mean, mean_cols):
    C, S, zeta, omega = params[n_mean:]
    root = math.sqrt(1 - zeta**2)
    omega_d = omega * root
    decay = np.exp(-zeta * omega * s)
    cos, sin = np.cos(omega_d * s), np.sin(omega_d * s)
    k = C * cos + S * sin
    dk = s * (-C * sin + S * cos)  # dK/dω_d
    d_zeta = decay * (-omega * s * k - dk * omega * zeta / root)
    d_omega = decay * (-zeta * s * k + dk * root)
    return np.column_stack(mean_cols + [decay * cos, decay * sin, d_zeta, d_omega])


def _covariance(jac, residual, n_params):
    dof = residual.size - n_params
    s2 = float(residual @ residual) / max(dof, 1)
    return s2 * np.linalg.pinv(jac.T @ jac), math.sqrt(s2), dof


def fit_linear_decay(time, value, omega_guess: float, *, equilibrium: float | None = None,
                     drift: bool = False) -> DecayFit:
    """Least-squares fit of x(t) = x_eq + b s + A e^{−ζω_n s} cos(ω_d s + φ), s = t − t₀.

    Parameters
    ----------
    time, value : validated record (finite, time strictly increasing)
    omega_guess : rough angular frequency, rad/s (a grid of 0.6–1.6 times it is searched)
    equilibrium : fixed x_eq; None fits it
    drift : also fit a linear drift b of the mean

    Returns
    -------
    DecayFit with parameters x_eq (unless fixed), drift (if asked), C, S, zeta, omega_n
    (A cos φ = C, −A sin φ = S).
    """
    t0 = float(time[0])
    s = np.asarray(time, dtype=float) - t0
    y = np.asarray(value, dtype=float) - (equilibrium or 0.0)
    mean_names, mean_cols = _mean_columns(s, equilibrium is not None, drift)
    n_mean = len(mean_names)
    seed = _seed_linear(s, y, omega_guess, mean_cols)
    seed[-2] = float(np.clip(seed[-2], *_ZETA_BOUNDS))
    lower = [-np.inf] * (n_mean + 2) + [_ZETA_BOUNDS[0], 1e-3 * omega_guess]
    upper = [np.inf] * (n_mean + 2) + [_ZETA_BOUNDS[1], 1e3 * omega_guess]

    def residuals(p):
        mean = sum((c * col for c, col in zip(p[:n_mean], mean_cols, strict=True)),
                   np.zeros_like(s))
        return mean + _linear_oscillation(s, *p[n_mean:]) - y

    def jacobian(p):
        return _linear_jacobian(p, s, n_mean, mean_cols)

    result = least_squares(residuals, seed, jac=jacobian, bounds=(lower, upper), x_scale="jac",
                           xtol=1e-14, ftol=1e-14, gtol=1e-14, max_nfev=2000)
    cov, rms, dof = _covariance(result.jac, result.fun, seed.size)
    return DecayFit("linear", mean_names + ["C", "S", "zeta", "omega_n"], result.x, cov, t0,
                    equilibrium, rms, dof)


def fit_quadratic_decay(time, value, linear: DecayFit) -> DecayFit:
    """Fit ÿ + 2ζω_n ẏ + c_q |ẏ|ẏ + ω_n² y = 0 (plus the same mean model) by integrating it.

    Seeded from the linear fit ``linear`` (c_q = 0). The Jacobian is by finite differences of
    the integrated solution (DOP853, rtol 1e-10, so the differences are far above the
    integration error).
    """
    s = np.asarray(time, dtype=float) - linear.t0
    y = np.asarray(value, dtype=float) - (linear.equilibrium or 0.0)
    mean_names = [n for n in ("x_eq", "drift") if n in linear.names]
    mean_cols = [np.ones_like(s) if n == "x_eq" else s for n in mean_names]
    n_mean = len(mean_names)
    zeta, omega = linear.zeta, linear.omega_n
    C, S = linear.param("C"), linear.param("S")
    v0 = -zeta * omega * C + omega * math.sqrt(1 - zeta**2) * S
    seed = np.array([linear.param(n) for n in mean_names] + [C, v0, zeta, omega, 0.0])
    lower = [-np.inf] * (n_mean + 2) + [_ZETA_BOUNDS[0], 1e-3 * omega, -np.inf]
    upper = [np.inf] * (n_mean + 2) + [_ZETA_BOUNDS[1], 1e3 * omega, np.inf]

    def residuals(p):
        mean = sum((c * col for c, col in zip(p[:n_mean], mean_cols, strict=True)),
                   np.zeros_like(s))
        return mean + _quadratic_oscillation(s, *p[n_mean:]) - y

    result = least_squares(residuals, seed, bounds=(lower, upper), x_scale="jac",
                           diff_step=1e-6, max_nfev=200 * seed.size)
    if not np.all(np.isfinite(result.fun)):
        raise InputError("quadratic damping: the fitted equation could not be integrated over "
                         "the record; use the linear model")
    cov, rms, dof = _covariance(result.jac, result.fun, seed.size)
    return DecayFit("linear+quadratic", mean_names + ["y0", "v0", "zeta", "omega_n", "c_q"],
                    result.x, cov, linear.t0, linear.equilibrium, rms, dof)
