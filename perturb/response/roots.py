"""Every real root of a zero-dimensional polynomial system with exact coefficients, certified.

The response equations of a driven system at one parameter point (exact rationals in) are put in
triangular form by a lexicographic Groebner basis. The last variable's polynomial is univariate
with rational coefficients: its real roots are **isolated** by sympy's exact interval method
(Descartes' rule / continued fractions: each interval holds exactly one root, so the count is
proved), then narrowed to :data:`ROOT_WIDTH`. Each is substituted back, variable by variable,
keeping the values every polynomial of that variable shares. Never Newton from a guess.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from perturb.algebra.rootset import RootSet, RootStatus

__all__ = ["RootSet", "RootStatus", "real_roots"]

#: Width to which each isolating interval is narrowed (relative to the root's size, or absolute
#: below 1): far below what a plot or a shooting seed needs, far above the double's spacing.
ROOT_WIDTH = 1e-13
#: A back-substituted polynomial counts as vanishing below this, relative to its coefficients.
BACK_RESIDUAL = 1e-8


def _isolated(poly: sp.Poly) -> list[float]:
    """The real roots of a univariate polynomial with rational coefficients, certified.

    The square-free part is isolated (a multiple root, such as the trivial response's, counts
    once), each interval narrowed to :data:`ROOT_WIDTH` by the exact method itself.
    """
    if poly.degree() <= 0:
        return []
    square_free = poly.sqf_part()
    bound = max(1.0, *(abs(float(c)) for c in square_free.monic().coeffs()))
    width = sp.Rational(ROOT_WIDTH) * sp.Rational(repr(min(bound, 1e6)))
    return [float((lo + hi) / 2) for (lo, hi), _ in square_free.intervals(eps=width)]


def _scale(poly: sp.Poly) -> float:
    return max(1.0, *(abs(float(c)) for c in poly.coeffs()))


def real_roots(eqs, unknowns) -> RootSet:
    """Every real root of ``eqs = 0`` (exact rational coefficients, zero-dimensional).

    Parameters
    ----------
    eqs : sequence of sympy expressions
        Polynomials in ``unknowns`` with exact rational coefficients.
    unknowns : sequence of sympy.Symbol
        The variables; the last one is eliminated to a univariate polynomial.

    Returns
    -------
    RootSet
        SOLVED (possibly with no root: then NO_REAL_ROOT), POSITIVE_DIMENSIONAL or UNDECIDED.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> found = real_roots([x**2 + y**2 - 1, x - y], [x, y])
    >>> found.status.name, len(found.roots)
    ('SOLVED', 2)
    """
    unknowns = tuple(unknowns)
    basis = sp.groebner([sp.expand(e) for e in eqs], *unknowns, order="lex")
    if list(basis.exprs) == [1]:
        return RootSet(RootStatus.NO_REAL_ROOT, (), unknowns, "no root at all (the basis is {1})")
    if not basis.is_zero_dimensional:
        return RootSet(RootStatus.POSITIVE_DIMENSIONAL, (), unknowns, str(list(basis.exprs)))
    polys = list(basis.exprs)
    found: list[dict] = []
    undecided: list[str] = []

    def descend(index: int, assignment: dict) -> None:
        if index < 0:
            found.append(dict(assignment))
            return
        var = unknowns[index]
        candidates = []
        for poly in polys:
            expr = sp.expand(poly.xreplace(assignment)) if assignment else poly
            symbols = expr.free_symbols & set(unknowns)
            if symbols == {var}:
                candidates.append(sp.Poly(expr, var))
            elif not symbols and abs(float(expr)) > BACK_RESIDUAL * max(1.0, abs(float(expr))):
                return
        if not candidates:
            undecided.append(str(var))
            return
        lowest = min(candidates, key=lambda q: q.degree())
        if not assignment:  # exact coefficients: isolate
            values = _isolated(lowest)
        else:  # coefficients from floats: the companion matrix, then every candidate checked
            coefficients = [float(c) for c in lowest.all_coeffs()]
            values = [
                z.real
                for z in np.roots(coefficients)
                if abs(z.imag) <= 1e-9 * max(1.0, abs(z))
            ]  # fmt: skip
        for value in sorted(values):
            if all(abs(float(q.eval(value))) <= BACK_RESIDUAL * _scale(q) for q in candidates):
                assignment[var] = float(value)
                descend(index - 1, assignment)
                del assignment[var]

    descend(len(unknowns) - 1, {})
    if undecided:
        return RootSet(RootStatus.UNDECIDED, found, unknowns, f"{sorted(set(undecided))} left free")
    if not found:
        return RootSet(RootStatus.NO_REAL_ROOT, (), unknowns, "every root is complex")
    return RootSet(RootStatus.SOLVED, found, unknowns)
