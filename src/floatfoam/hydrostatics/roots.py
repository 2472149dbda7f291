"""Brent's method for a bracketed root of a scalar function (Brent 1973, *Algorithms for
Minimization without Derivatives*, ch. 4; the algorithm of netlib's ``zeroin``).

The same method as ``scipy.optimize.brentq``, written out because importing
``scipy.optimize`` costs about half a second per process (measured: ``python -X importtime -c
"import scipy.optimize"``), more than the whole linear theory of a closed-form body takes; the
hydrostatics that every command needs (draft, equilibrium) solve only this one-dimensional
problem.
"""

from __future__ import annotations

import math

from floatfoam.errors import InputError


def brentq(f, a: float, b: float, *, xtol: float = 2e-12, rtol: float = 4 * 2.2e-16,
           maxiter: int = 200) -> float:
    """A root of ``f`` in [a, b], where f(a) and f(b) differ in sign, to within
    ``xtol + rtol·|x|`` (the tolerance convention of ``scipy.optimize.brentq``)."""
    fa, fb = f(a), f(b)
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if math.copysign(1.0, fa) == math.copysign(1.0, fb):
        raise InputError(f"no root between {a:g} and {b:g}: f = {fa:g} and {fb:g} there")
    c, fc = a, fa
    d = e = b - a
    for _ in range(maxiter):
        if math.copysign(1.0, fb) == math.copysign(1.0, fc):
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 2.0 * rtol * abs(b) + 0.5 * xtol
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return b
        if abs(e) >= tol and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:  # secant
                p, q = 2.0 * m * s, 1.0 - s
            else:  # inverse quadratic interpolation
                q, r = fa / fc, fb / fc
                p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * m * q - abs(tol * q), abs(e * q)):
                e, d = d, p / q
            else:
                d = e = m
        else:
            d = e = m
        a, fa = b, fb
        b += d if abs(d) > tol else math.copysign(tol, m)
        fb = f(b)
    raise RuntimeError(f"Brent's method did not converge in {maxiter} iterations")
