"""Exactness helpers of the construction: zero tests, round-off chopping, exact roots, Taylor coefficients.

The construction keeps exact input exact (sympy ``Rational``) and meets floating-point numbers only
where the user or the numeric quadrature brings them in; these helpers decide what counts as zero in
either case.
"""

from __future__ import annotations

import math

import sympy as sp

from perturb._defaults import (
    NUMERIC_ZERO,
    PROBE_BITS,
    PROBE_DIGITS,
    PROBE_NONZERO,
    ROOT_MAX_DENOMINATOR,
    ROOT_RATIONAL_TOL,
)
from perturb.native import Converter, NotNative, ring_for, se
from perturb.system import EPS
from perturb.trig import SympyRing, TrigPoly

__all__ = [
    "chop",
    "exact_if_close",
    "rational_form",
    "is_zero",
    "probe_values",
    "taylor_coefficient",
    "vanishes",
    "vanishes_native",
]


def exact_if_close(value: float) -> sp.Expr:
    """``value`` as a rational with a small denominator when it is one to round-off, else a Float."""
    rational = sp.nsimplify(value, tolerance=ROOT_RATIONAL_TOL, rational=True)
    if rational.q <= ROOT_MAX_DENOMINATOR and abs(float(rational) - value) <= ROOT_RATIONAL_TOL:
        return rational
    return sp.Float(value, 17)


def rational_form(expr) -> sp.Expr:
    """``expr`` with a common factor pi (the conditions' 2π-integrals) taken out, expanded.

    Examples
    --------
    >>> rational_form(sp.pi * sp.Symbol("a") / 4 - sp.pi)
    a/4 - 1
    """
    expr = sp.expand(expr)
    if expr.has(sp.pi):
        reduced = sp.expand(expr / sp.pi)
        if not reduced.has(sp.pi):
            return reduced
    return expr


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


def vanishes_native(value, conv: Converter) -> bool:
    """:func:`vanishes` of a native expression, decided on the native backend where it is clear.

    At the generic point of :func:`probe_values` the expression is evaluated exactly (rationals,
    square roots of rationals, :math:`\\pi`): zero there is :func:`vanishes`' zero. Otherwise it is
    evaluated to ``PROBE_BITS`` bits; a magnitude above ``PROBE_NONZERO`` is :func:`vanishes`'
    non-zero (its 30-digit value is that far from ``NUMERIC_ZERO``). Anything else (a pole at the
    point, a value near the threshold) is decided by :func:`vanishes` on the sympy expression.
    Converting a large expression to sympy and evaluating it there takes seconds; this, milliseconds.
    """
    if not conv.native:
        return vanishes(value)
    if value == 0:
        return True
    point = {
        conv.to_native(symbol): conv.to_native(number)
        for symbol, number in _probe_point(conv.symbols(value)).items()
    }
    number = se.expand(value.xreplace(point))
    if number == 0:
        return True
    if number.is_number:
        try:
            magnitude = abs(complex(number.evalf(PROBE_BITS, real=False)))
        except (TypeError, ValueError, RuntimeError):
            magnitude = None
        if magnitude is not None and math.isfinite(magnitude) and magnitude > PROBE_NONZERO:
            return False
    return vanishes(conv.to_sympy(value))


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
    return _probe_point(expr.free_symbols)


def _probe_point(free_symbols) -> dict:
    symbols = sorted(free_symbols, key=str)
    return {s: sp.Rational(1, 2) + sp.Rational(i + 1, 2 * (len(symbols) + 1)) - sp.Rational(1, 101 + 7 * i)
            for i, s in enumerate(symbols)}  # fmt: skip
