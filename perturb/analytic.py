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

import sympy as sp

from perturb.errors import InvalidSystemError

__all__ = ["maclaurin_coefficients"]


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
