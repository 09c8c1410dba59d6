"""The front door of the real-root solvers: the route chosen, the budget kept, the status honest."""

from __future__ import annotations

import sympy as sp

from perturb.algebra.budget import solve_bounded
from perturb.algebra.msolve import INSTALL_HINT, msolve_binary, msolve_real_roots
from perturb.algebra.rootset import RootSet, RootStatus
from perturb.algebra.size import SystemSize
from perturb.algebra.triangular import exact_real_roots

__all__ = ["BACKENDS", "certified_real_roots"]

#: The routes: ``auto`` is msolve when the extra is installed, else the exact sympy route.
BACKENDS = ("auto", "msolve", "sympy")


def _check(eqs, unknowns) -> None:
    from perturb.errors import InvalidSystemError, bad_value

    for e in eqs:
        stray = sp.sympify(e).free_symbols - set(unknowns)
        if stray or sp.sympify(e).has(sp.Float) or not sp.sympify(e).is_polynomial(*unknowns):
            raise bad_value(
                "eqs",
                e,
                "give polynomials in the unknowns with exact rational coefficients"
                + (f" (put in values for {sorted(map(str, stray))})" if stray else ""),
                InvalidSystemError,
            )


def certified_real_roots(eqs, unknowns, *, seconds: float, backend: str = "auto") -> RootSet:
    """Every real root of ``eqs = 0``, each certified by an isolating interval, within a budget.

    Parameters
    ----------
    eqs : sequence of sympy expressions
        Polynomials in ``unknowns`` with exact rational coefficients.
    unknowns : sequence of sympy.Symbol
    seconds : float
        Time budget; when spent the status is ``BUDGET_EXCEEDED`` and the message gives the
        system's size.
    backend : {"auto", "msolve", "sympy"}
        ``msolve`` needs the extra ``roots``; ``sympy`` is the exact route of
        :mod:`perturb.algebra.triangular` (exact algebraic values).

    Returns
    -------
    RootSet

    Raises
    ------
    InvalidSystemError
        When an equation is not a polynomial with rational coefficients in ``unknowns``.
    MissingDependencyError
        ``backend="msolve"`` without the extra.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> found = certified_real_roots([x**3 - x, y - x**2], [x, y], seconds=30, backend="sympy")
    >>> found.status.name, [(r[x], r[y]) for r in found.exact]
    ('SOLVED', [(0, 0), (-1, 1), (1, 1)])
    """
    from perturb.errors import InvalidSystemError, MissingDependencyError, bad_value

    if backend not in BACKENDS:
        raise bad_value("backend", backend, f"use one of {list(BACKENDS)}", InvalidSystemError)
    unknowns = list(unknowns)
    eqs = [sp.expand(e) for e in eqs]
    _check(eqs, unknowns)
    binary = msolve_binary() if backend in ("auto", "msolve") else None
    if backend == "msolve" and binary is None:
        raise MissingDependencyError(f"`backend='msolve'` needs msolve: {INSTALL_HINT}")
    if binary is not None:
        return msolve_real_roots(eqs, unknowns, seconds, binary)
    try:
        return solve_bounded(eqs, unknowns, seconds, exact_real_roots)
    except TimeoutError:
        size = SystemSize.of(eqs, unknowns)
        return RootSet(
            RootStatus.BUDGET_EXCEEDED,
            (),
            unknowns,
            f"the exact route ran past {seconds:g} s on {size}",
            size=size,
            backend="sympy",
        )
