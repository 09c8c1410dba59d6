"""Every real root of a zero-dimensional polynomial system with exact coefficients, certified.

The response equations of a driven system at one parameter point (exact rationals in) go to the
same solver as the free systems' amplitude equations, :func:`perturb.algebra.certified_real_roots`
(issue 22): the system is cut by its factors and symmetries, each piece's real roots are isolated
(msolve with the extra ``roots``, the exact sympy route otherwise), each one in an interval or box
that holds exactly one root, so the count is proved at every coordinate. Never Newton from a guess.
"""

from __future__ import annotations

import sympy as sp

from perturb._defaults import RESPONSE_SECONDS
from perturb.algebra.certified import certified_real_roots
from perturb.algebra.msolve import msolve_binary
from perturb.algebra.rootset import RootSet, RootStatus

__all__ = ["RootSet", "RootStatus", "real_roots"]


def real_roots(
    eqs, unknowns, *, seconds: float = RESPONSE_SECONDS, floats: bool = False
) -> RootSet:
    """Every real root of ``eqs = 0`` (exact rational coefficients), each one certified.

    Parameters
    ----------
    eqs : sequence of sympy expressions
        Polynomials in ``unknowns`` with exact rational coefficients.
    unknowns : sequence of sympy.Symbol
    seconds : float, optional
        Time budget (:data:`RESPONSE_SECONDS`).
    floats : bool, optional
        The caller needs the roots as floats only (a response's points): with the extra
        ``roots`` msolve answers at once (no exact radicals tried first) and its certified boxes'
        midpoints are kept as they are.

    Returns
    -------
    RootSet
        SOLVED (``roots``: one dict of floats per root, ``exact`` and ``certificates`` beside
        them), NO_REAL_ROOT (proved), POSITIVE_DIMENSIONAL, UNDECIDED or BUDGET_EXCEEDED.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> found = real_roots([x**2 + y**2 - 1, x - y], [x, y])
    >>> found.status.name, len(found.roots)
    ('SOLVED', 2)
    """
    unknowns = list(unknowns)
    eqs = [_primitive(e, unknowns) for e in eqs]
    if floats and msolve_binary() is not None:
        return certified_real_roots(eqs, unknowns, seconds=seconds, backend="msolve", refine=False)
    return certified_real_roots(eqs, unknowns, seconds=seconds)


def _primitive(eq, unknowns):
    """``eq`` over its leading coefficient when a common constant such as pi is in every one
    (a forcing's Fourier coefficients carry it): the same roots, rational coefficients."""
    eq = sp.expand(eq)
    if not unknowns or eq == 0:
        return eq
    coefficients = sp.Poly(eq, *unknowns).coeffs()
    if all(c.is_Rational for c in coefficients):
        return eq
    return sp.expand(eq / coefficients[0])
