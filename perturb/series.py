"""Truncated power series in ε whose coefficients are trigonometric polynomials.

``TrigSeries([u0, u1, ...])`` stands for :math:`u_0(s) + \\varepsilon u_1(s) + \\dots`.  Substituting such
series for the state into a polynomial right-hand side gives the forcing of every order at once.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import sympy as sp

from perturb.trig import TrigPoly

__all__ = ["TrigSeries", "evaluate_polynomial"]


class TrigSeries:
    """A power series in ε truncated after ``len(coefficients) - 1``."""

    __slots__ = ("coefficients",)

    def __init__(self, coefficients: Sequence[TrigPoly]):
        self.coefficients = list(coefficients)

    @property
    def order(self) -> int:
        return len(self.coefficients) - 1

    @classmethod
    def constant(cls, value, order: int) -> TrigSeries:
        return cls([TrigPoly.constant(value)] + [TrigPoly() for _ in range(order)])

    def truncate(self, order: int) -> TrigSeries:
        coeffs = self.coefficients[: order + 1]
        coeffs += [TrigPoly() for _ in range(order + 1 - len(coeffs))]
        return TrigSeries(coeffs)

    def __add__(self, other: TrigSeries) -> TrigSeries:
        n = min(self.order, other.order)
        return TrigSeries([self.coefficients[k] + other.coefficients[k] for k in range(n + 1)])

    def scale(self, factor) -> TrigSeries:
        return TrigSeries([c.scale(factor) for c in self.coefficients])

    def __mul__(self, other: TrigSeries) -> TrigSeries:
        n = min(self.order, other.order)
        out = []
        for k in range(n + 1):
            acc = TrigPoly()
            for j in range(k + 1):
                a, b = self.coefficients[j], other.coefficients[k - j]
                if a.is_zero() or b.is_zero():
                    continue
                acc = acc + a * b
            out.append(acc)
        return TrigSeries(out)

    def derivative(self) -> TrigSeries:
        """Term-by-term d/ds."""
        return TrigSeries([c.derivative() for c in self.coefficients])

    def at_zero(self) -> list[sp.Expr]:
        return [c.at_zero() for c in self.coefficients]


def evaluate_polynomial(
    expr: sp.Expr, variables: Mapping[sp.Symbol, TrigSeries], order: int
) -> TrigSeries:
    """Substitute series for ``variables`` in the polynomial ``expr``, truncated at ``order``.

    Coefficients of ``expr`` may contain any other symbols (parameters); they must be polynomial in
    ``variables``.

    Raises
    ------
    sympy.PolynomialError
        If ``expr`` is not polynomial in ``variables`` (the caller falls back to numeric quadrature).
    """
    syms = [v for v in variables if expr.has(v)]
    if not syms:
        return TrigSeries.constant(sp.expand(expr), order)
    poly = sp.Poly(expr, *syms)
    if any(not c.is_polynomial(*syms) for c in poly.coeffs()):  # pragma: no cover - defensive
        raise sp.PolynomialError(f"{expr} is not polynomial in {syms}")
    powers: dict[tuple[sp.Symbol, int], TrigSeries] = {}

    def power(sym: sp.Symbol, e: int) -> TrigSeries:
        if e == 1:
            return variables[sym].truncate(order)
        key = (sym, e)
        if key not in powers:
            powers[key] = power(sym, e - 1) * variables[sym].truncate(order)
        return powers[key]

    total = TrigSeries([TrigPoly() for _ in range(order + 1)])
    for monom, coeff in poly.terms():
        term = TrigSeries.constant(coeff, order)
        for sym, e in zip(syms, monom, strict=True):
            if e:
                term = term * power(sym, e)
        total = total + term
    return total
