"""Maclaurin expansion in ε of right-hand sides whose ε dependence is analytic but not polynomial.

A right-hand side polynomial in ε has its coefficients read off directly (the fast path of
:meth:`QuasilinearSystem.expansion`). Any other dependence analytic at ε = 0 — rational functions
such as ``eps*x**2/(1 + eps)``, elementary functions such as ``sin(eps)``, removable singularities
such as ``(eps*x - sin(eps*x))/eps``, and in the large-parameter regime the same in ``1/mu`` — is
expanded by :func:`sympy.series` to exactly the order the construction needs, once per expression
and order (memoised). What has no Maclaurin series is refused with the term and the reason: a pole at
ε = 0 (``x**2/eps``), a branch point (``sqrt(eps)``, ``log(eps)``), or an essential singularity
(``exp(-1/eps)``, flat at ε = 0).
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import sympy as sp

from perturb.errors import InvalidSystemError

if TYPE_CHECKING:
    from perturb.native import Converter

__all__ = ["maclaurin_coefficients", "polynomial_coefficients"]


def polynomial_coefficients(expr: sp.Expr, eps: sp.Symbol) -> tuple[sp.Expr, ...] | None:
    """The coefficients of ``expr`` as a polynomial in ``eps``, or None when it is not one.

    ``result[k]`` multiplies ``eps**k`` (``sympy.expand``-ed, as ``Poly(expand(expr), eps)`` gives
    them) through the degree; ``(0,)`` for zero. ``expr`` is a polynomial in ``eps`` when its
    expanded terms hold ``eps`` only as non-negative integer powers; anything else (``x/(1 + eps)``,
    ``sin(eps*x)``, ``sqrt(eps)``) gives None and is left to :func:`maclaurin_coefficients`.

    The terms are sorted by their power of ``eps`` on the native backend (:mod:`perturb.native`)
    when it holds the expression exactly (no floats): a large right-hand side (the disk's: hundreds
    of terms) takes milliseconds there and about a third of a second through a sympy ``Poly``. Each
    coefficient comes back with its original symbols and is expanded by sympy, so both routes
    return the same expressions.
    """
    expr = sp.sympify(expr)
    if not expr.has(eps):
        return (sp.expand(expr),)
    # the native backend (symengine) is imported here, not with this module: a warm run that
    # reads its results from the cache never expands a right-hand side
    from perturb.native import Converter, NotNative, SympyRing, ring_for

    ring = ring_for(expr)
    if ring is not SympyRing:
        converter = Converter(ring)
        try:
            native = converter.to_native(expr)
        except NotNative:
            pass  # an object the native backend cannot hold: the sympy route below
        else:
            return _native_coefficients(native, converter.to_native(eps), converter)
    try:
        poly = sp.Poly(sp.expand(expr), eps)
    except sp.PolynomialError:
        return None
    return tuple(sp.expand(poly.coeff_monomial(eps**k)) for k in range(poly.degree() + 1))


def _native_coefficients(native, eps, converter: Converter) -> tuple[sp.Expr, ...] | None:
    """:func:`polynomial_coefficients` of a native (symengine) expression."""
    import symengine as se  # present: the converter is native

    groups: dict[int, list] = {}
    expanded = se.expand(native)
    for term in expanded.args if isinstance(expanded, se.Add) else (expanded,):
        power, rest = 0, []
        for factor in term.args if isinstance(term, se.Mul) else (term,):
            exponent = _power_of(factor, eps, se)
            if exponent is None:
                return None  # eps inside a function, a denominator or a fractional power
            power += exponent
            if not exponent:
                rest.append(factor)
        groups.setdefault(power, []).append(se.Mul(*rest))
    return tuple(
        _back(se.Add(*groups[k]), converter, se) if k in groups else sp.S.Zero
        for k in range(max(groups) + 1)
    )


def _back(value, converter: Converter, se) -> sp.Expr:
    """A native coefficient as the sympy expression ``sympy.expand`` gives.

    A sum of monomials (numbers times integer powers of symbols) is already in that form once
    converted: sympy's ``expand`` would walk it for nothing (the disk's right-hand side: 0.4 s).
    """
    expr = converter.to_sympy(value, expand=False)
    return expr if _is_monomial_sum(value, se) else sp.expand(expr)


def _is_monomial_sum(value, se) -> bool:
    for term in value.args if isinstance(value, se.Add) else (value,):
        for factor in term.args if isinstance(term, se.Mul) else (term,):
            if isinstance(factor, se.Pow):
                base, exponent = factor.args
                if not (isinstance(base, se.Symbol) and isinstance(exponent, se.Integer)):
                    return False
            elif not isinstance(factor, (se.Symbol, se.Integer, se.Rational)):
                return False
    return True


def _power_of(factor, eps, se) -> int | None:
    """The power of ``eps`` a factor of a product is (0 when free of it), None if not a power."""
    if factor == eps:
        return 1
    if isinstance(factor, se.Pow) and factor.args[0] == eps:
        exponent = factor.args[1]
        return int(exponent) if isinstance(exponent, se.Integer) and exponent > 0 else None
    return None if factor.has(eps) else 0


@functools.lru_cache(maxsize=512)
def _series_terms(expr: sp.Expr, eps: sp.Symbol, order: int) -> tuple[tuple[sp.Expr, sp.Expr], ...]:
    """The (coefficient, exponent) pairs of the series of ``expr`` below ``eps**(order + 1)``."""
    series = sp.series(expr, eps, 0, order + 1).removeO()
    return tuple(term.as_coeff_exponent(eps) for term in sp.Add.make_args(sp.expand(series)))


def maclaurin_coefficients(
    expr: sp.Expr, eps: sp.Symbol, order: int, label: str
) -> tuple[sp.Expr, ...]:
    """Coefficients of ``eps**0 .. eps**order`` in the Maclaurin series of ``expr``.

    Parameters
    ----------
    expr : sympy expression
        Analytic in ``eps`` at 0 (possibly through a removable singularity).
    eps : sympy.Symbol
        The expansion symbol.
    order : int
        The highest power kept.
    label : str
        How to name ``expr`` in an error (``rhs[0]``).

    Returns
    -------
    tuple of sympy expressions
        ``coefficients[k]`` multiplies ``eps**k`` (expanded).

    Raises
    ------
    InvalidSystemError
        When ``expr`` has no Maclaurin series in ``eps``: a pole at 0, a fractional power (branch
        point), ``log(eps)``, or a function sympy cannot expand there.
    """
    try:
        terms = _series_terms(expr, eps, order)
    except (NotImplementedError, ValueError, TypeError, sp.PoleError) as exc:
        raise _refuse(label, expr, f"sympy cannot expand it in {eps} at 0 ({exc})") from None
    coefficients = [sp.S.Zero] * (order + 1)
    for coefficient, exponent in terms:
        term = coefficient * eps**exponent
        if coefficient.has(eps):
            raise _refuse(
                label,
                expr,
                f"its term {term} is not a power of {eps} (a branch point or an essential "
                f"singularity at {eps} = 0)",
            )
        if not exponent.is_Integer:
            raise _refuse(label, expr, f"its term {term} has a branch point at {eps} = 0")
        if exponent < 0:
            raise _refuse(
                label,
                expr,
                f"its term {term} has a pole at {eps} = 0 (the lowest power of epsilon must be "
                "positive)",
            )
        if exponent <= order:
            coefficients[int(exponent)] += coefficient
    return tuple(sp.expand(c) for c in coefficients)


def _refuse(label: str, expr: sp.Expr, reason: str) -> InvalidSystemError:
    return InvalidSystemError(
        f"`{label}` = {expr} is invalid: {reason}; the right-hand side must be analytic in the "
        "expansion parameter at its limit (a Maclaurin series): rescale the variables or drop the term"
    )
