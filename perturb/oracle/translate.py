"""sympy → heyoka: exact translation of a :class:`~perturb.oracle.symbolic.SymbolicRHS`'s expressions.

Done here rather than with ``heyoka.from_sympy`` because the latter refuses rationals such as 1/3
(not exact in binary) and always builds double constants, whereas reference runs in extended
precision need the constants rounded in that precision.

Powers need care.  heyoka's ``pow`` is the real power :math:`b^\\alpha = e^{\\alpha \\log b}` and
its Taylor recurrence divides by the base,

.. math:: a^{[n]} = \\frac{1}{n\\, b^{[0]}} \\sum_{j=0}^{n-1} \\bigl(n\\alpha - j(\\alpha + 1)\\bigr)
          b^{[n-j]} a^{[j]},\\qquad a = b^\\alpha,

so a float power is NaN wherever its base vanishes, even when the power itself is smooth there
(:math:`\\dot x^3` at :math:`\\dot x = 0`: a Rayleigh oscillator started at rest would fail).  Powers
are therefore translated by their exponent:

- integer :math:`n \\ge 1`: products by repeated squaring (:math:`x^5 = (x^2)^2\\, x`), whose Taylor
  recurrences are Cauchy products, exact at any base, negative ones included;
- integer :math:`n \\le -1`: :math:`1 / x^{|n|}` (singular only where the rhs itself is);
- half-integer :math:`k/2`: :math:`x^{\\lfloor k/2 \\rfloor}\\sqrt{x}` (and its reciprocal for
  :math:`k < 0`), with heyoka's ``sqrt``;
- an integer-valued float exponent (``x**2.0`` from user input) counts as the integer;
- anything else stays a real power.
"""

from __future__ import annotations

import functools
import operator
from collections.abc import Mapping
from typing import Any

import sympy as sp

from perturb.errors import bad_value

__all__ = ["to_heyoka"]

#: Digits used when a sympy number (pi, a Float, an irrational constant) is rounded to a floating
#: point type: 40 covers real128 (34 significant digits) with margin.
_CONSTANT_DIGITS = 40

#: sympy function name → heyoka function name, for the elementary functions heyoka implements.
_HEYOKA_FUNCTIONS = {
    "sin": "sin",
    "cos": "cos",
    "tan": "tan",
    "asin": "asin",
    "acos": "acos",
    "atan": "atan",
    "atan2": "atan2",
    "sinh": "sinh",
    "cosh": "cosh",
    "tanh": "tanh",
    "asinh": "asinh",
    "acosh": "acosh",
    "atanh": "atanh",
    "exp": "exp",
    "log": "log",
    "erf": "erf",
}

#: sympy functions heyoka lacks, written with ones it has (reciprocals: singular where sympy's are).
_RECIPROCALS = {"sec": "cos", "csc": "sin", "cot": "tan"}


def _constant(value: sp.Expr, fp_type: type) -> Any:
    """Round a sympy number to ``fp_type`` (float, numpy.longdouble or heyoka.real128)."""
    if isinstance(value, sp.Rational):  # integers included; p/q rounded once, in fp_type
        if fp_type is float:
            return int(value.p) / int(value.q)  # Python's int true division is correctly rounded
        return fp_type(str(value.p)) / fp_type(str(value.q))
    text = str(sp.N(value, _CONSTANT_DIGITS))
    return fp_type(text)


def _integer_power(base: Any, n: int) -> Any:
    """``base**n`` for an integer ``n >= 1`` as products, by repeated squaring."""
    result, square = None, base
    while True:
        if n & 1:
            result = square if result is None else result * square
        n >>= 1
        if not n:
            return result
        square = square * square


def _as_integer(exponent: sp.Expr) -> int | None:
    """The exponent as a Python int if it is an integer or an integer-valued Float, else None."""
    if exponent.is_Integer:
        return int(exponent)
    if exponent.is_Float and float(exponent).is_integer():
        return int(exponent)
    return None


def to_heyoka(
    expr: sp.Expr, variables: Mapping[sp.Symbol, Any], fp_type: type = float
) -> Any:  # heyoka.expression; heyoka is optional, so it is imported in the function
    """Convert a sympy expression into a heyoka expression.

    Parameters
    ----------
    expr : sympy.Expr
        Polynomial/rational combination of the variables and of the elementary functions heyoka
        implements (sin, cos, tan, their inverses, the hyperbolic functions and their inverses,
        exp, log, erf, sqrt, powers) or that are written with them (sec, csc, cot).
    variables : mapping
        sympy symbol → heyoka variable expression.
    fp_type : type, optional
        Floating point type in which numeric constants are rounded: ``float``, ``numpy.longdouble``
        or ``heyoka.real128``.

    Returns
    -------
    heyoka.expression

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``expr`` contains a function heyoka does not implement, or a non-real constant.

    Notes
    -----
    Integer and half-integer powers become products, reciprocals and square roots (see the module
    docstring), so that their Taylor coefficients are finite at a zero base.

    Examples
    --------
    >>> import heyoka as hy
    >>> import sympy as sp
    >>> from perturb.oracle import to_heyoka
    >>> x = sp.Symbol("x")
    >>> hx = hy.make_vars("x")
    >>> expression = to_heyoka(x**3 - sp.sin(x) / 2, {x: hx})
    >>> isinstance(expression, hy.expression)
    True
    """
    import heyoka as hy

    def one():
        return hy.expression(_constant(sp.Integer(1), fp_type))

    def power(base: sp.Expr, exponent: sp.Expr):
        n = _as_integer(exponent)
        if n is not None:
            if n == 0:
                return one()
            magnitude = _integer_power(conv(base), abs(n))
            return magnitude if n > 0 else one() / magnitude
        twice = _as_integer(2 * exponent) if exponent.is_Rational else None
        if twice is not None:  # half-integer k/2, k odd: x**(k//2) sqrt(x), reciprocal if k < 0
            k = abs(twice)
            root = hy.sqrt(conv(base))
            magnitude = root if k == 1 else _integer_power(conv(base), k // 2) * root
            return magnitude if twice > 0 else one() / magnitude
        return conv(base) ** conv(exponent)

    def conv(e: sp.Expr):
        if e in variables:
            return variables[e]
        if e.is_Number or e.is_NumberSymbol:
            if not e.is_real:
                raise bad_value("expr", e, "heyoka accepts only real constants")
            return hy.expression(_constant(e, fp_type))
        if isinstance(e, sp.Add):
            return hy.sum([conv(a) for a in e.args])
        if isinstance(e, sp.Mul):
            return functools.reduce(operator.mul, [conv(a) for a in e.args])
        if isinstance(e, sp.Pow):
            return power(*e.args)
        if isinstance(e, sp.Function):
            name = type(e).__name__
            if name in _RECIPROCALS:
                return one() / getattr(hy, _RECIPROCALS[name])(*[conv(a) for a in e.args])
            if name not in _HEYOKA_FUNCTIONS:
                raise bad_value(
                    "expr",
                    name,
                    f"heyoka implements only {sorted(_HEYOKA_FUNCTIONS)} and powers; rewrite the "
                    "rhs with those or use a scipy integrator",
                )
            return getattr(hy, _HEYOKA_FUNCTIONS[name])(*[conv(a) for a in e.args])
        raise bad_value("expr", e, "cannot convert this sympy object to a heyoka expression")

    return conv(sp.sympify(expr))
