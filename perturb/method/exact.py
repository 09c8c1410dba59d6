"""Exactness helpers of the construction: zero tests, round-off chopping, exact roots, Taylor coefficients.

The construction keeps exact input exact (sympy ``Rational``) and meets floating-point numbers only
where the user or the numeric quadrature brings them in; these helpers decide what counts as zero in
either case.
"""

from __future__ import annotations

import math

import sympy as sp

from perturb._defaults import NUMERIC_ZERO, PROBE_DIGITS, ROOT_MAX_DENOMINATOR, ROOT_RATIONAL_TOL
from perturb.native import Converter, NotNative, ring_for
from perturb.system import EPS
from perturb.trig import SympyRing, TrigPoly

__all__ = [
    "chop",
    "exact_if_close",
    "is_zero",
    "probe_values",
    "taylor_coefficient",
    "vanishes",
]


def exact_if_close(value: float) -> sp.Expr:
    """``value`` as a rational with a small denominator when it is one to round-off, else a Float."""
    rational = sp.nsimplify(value, tolerance=ROOT_RATIONAL_TOL, rational=True)
    if rational.q <= ROOT_MAX_DENOMINATOR and abs(float(rational) - value) <= ROOT_RATIONAL_TOL:
        return rational
    return sp.Float(value, 17)


def taylor_coefficient(expr: sp.Expr, k: int) -> sp.Expr:
    """Coefficient of ε^k in the Maclaurin expansion of ``expr`` (k-fold derivative at 0 over k!).

    Much faster than ``sympy.series`` on nested radicals of polynomials, the form first-integral
    constraints take.
    """
    if not expr.has(EPS):
        return sp.expand(expr) if k == 0 else sp.S.Zero
    if expr.is_polynomial(EPS):
        return sp.expand(sp.expand(expr).coeff(EPS, k))
    ring = ring_for(expr)
    if ring is not SympyRing:  # the same k-fold derivative, on the native backend
        conv = Converter(ring)
        try:
            eps, value = conv.to_native(EPS), conv.to_native(expr)
        except NotNative:
            eps = None
        if eps is not None:
            for _ in range(k):
                value = value.diff(eps)
            return conv.to_sympy(value.subs({eps: ring.zero}) / math.factorial(k))
    value = expr
    for _ in range(k):
        value = sp.diff(value, EPS)
    return sp.expand(value.subs(EPS, 0) / sp.factorial(k))


def is_zero(expr) -> bool:
    """Cheap zero test: exact for symbolic expressions, round-off tolerant for floating numbers."""
    expr = sp.sympify(expr)
    if expr.is_number and expr.has(sp.Float):
        return abs(complex(expr)) < NUMERIC_ZERO
    return expr == 0 or sp.expand(expr) == 0 or sp.cancel(expr) == 0


def vanishes(expr) -> bool:
    """Whether ``expr`` is zero: exactly when cheap, else by evaluation at a generic point.

    The generic point gives every symbol a distinct rational value in (0.5, 1) (where the
    square roots of first-integral constraints stay real); a non-zero rational function of the
    symbols that vanishes there to 30 digits would be a coincidence of measure zero.
    """
    expr = sp.sympify(expr)
    if expr == 0:
        return True
    if expr.is_number:
        return is_zero(expr)
    value = expr.evalf(PROBE_DIGITS, subs=probe_values(expr))
    try:
        magnitude = abs(complex(value))
    except TypeError:  # evaluation left symbols behind (a function sympy cannot evaluate)
        return is_zero(expr)
    return magnitude < NUMERIC_ZERO


def chop(poly: TrigPoly) -> TrigPoly:
    """Drop floating-point round-off (|c| < NUMERIC_ZERO) from the coefficients of ``poly``."""
    if poly.ring is not SympyRing:  # native coefficients: only float-free runs are native
        return poly

    def chop_one(expr: sp.Expr) -> sp.Expr:
        floats = {f: 0 for f in expr.atoms(sp.Float) if abs(f) < NUMERIC_ZERO}
        return sp.expand(expr.xreplace(floats)) if floats else expr

    return poly.map(chop_one)


def probe_values(expr: sp.Expr) -> dict:
    """Deterministic generic values in (0.5, 1) for the free symbols of ``expr``.

    Distinct rationals with unrelated denominators (so no accidental cancellation), below 1 so that
    the square roots of first-integral constraints such as sqrt(1 - gamma**2) stay real.
    """
    symbols = sorted(expr.free_symbols, key=str)
    return {s: sp.Rational(1, 2) + sp.Rational(i + 1, 2 * (len(symbols) + 1)) - sp.Rational(1, 101 + 7 * i)
            for i, s in enumerate(symbols)}  # fmt: skip
