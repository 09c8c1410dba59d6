"""Truncated power series in ε whose coefficients are trigonometric polynomials.

``TrigSeries([u0, u1, ...])`` stands for :math:`u_0(s) + \\varepsilon u_1(s) + \\dots`.  Substituting such
series for the state into a polynomial right-hand side gives the forcing of every order at once.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping, Sequence

import sympy as sp

from perturb._lambdify import numpy_lambdify
from perturb.trig import TrigPoly

__all__ = ["TrigSeries", "evaluate_polynomial"]


class TrigSeries:
    """A power series in ε truncated after ``len(coefficients) - 1``."""

    __slots__ = ("coefficients", "poly")

    def __init__(self, coefficients: Sequence[TrigPoly], poly: type | None = None):
        self.coefficients = list(coefficients)
        # the class of the coefficients (TrigPoly, or the engine's native one): zeros are made of it
        self.poly = poly or (type(self.coefficients[0]) if self.coefficients else TrigPoly)

    @property
    def order(self) -> int:
        return len(self.coefficients) - 1

    @classmethod
    def constant(cls, value, order: int, poly: type = TrigPoly) -> TrigSeries:
        return cls([poly.constant(value)] + [poly() for _ in range(order)], poly)

    def truncate(self, order: int) -> TrigSeries:
        coeffs = self.coefficients[: order + 1]
        coeffs += [self.poly() for _ in range(order + 1 - len(coeffs))]
        return TrigSeries(coeffs, self.poly)

    def __add__(self, other: TrigSeries) -> TrigSeries:
        n = min(self.order, other.order)
        return TrigSeries(
            [self.coefficients[k] + other.coefficients[k] for k in range(n + 1)], self.poly
        )

    def scale(self, factor) -> TrigSeries:
        return TrigSeries([c.scale(factor) for c in self.coefficients], self.poly)

    def __mul__(self, other: TrigSeries) -> TrigSeries:
        n = min(self.order, other.order)
        out = []
        for k in range(n + 1):
            acc = self.poly()
            for j in range(k + 1):
                a, b = self.coefficients[j], other.coefficients[k - j]
                if a.is_zero() or b.is_zero():
                    continue
                acc = acc + a * b
            out.append(acc)
        return TrigSeries(out, self.poly)

    def derivative(self) -> TrigSeries:
        """Term-by-term d/ds."""
        return TrigSeries([c.derivative() for c in self.coefficients], self.poly)

    def at_zero(self) -> list[sp.Expr]:
        return [c.at_zero() for c in self.coefficients]


@functools.lru_cache(maxsize=256)
def _polynomial_terms(expr: sp.Expr, syms: tuple) -> tuple:
    """``Poly(expr, *syms).terms()``, cached: a system's right-hand sides are split once, not per order."""
    poly = sp.Poly(expr, *syms)
    if any(not c.is_polynomial(*syms) for c in poly.coeffs()):  # pragma: no cover - defensive
        raise sp.PolynomialError(f"{expr} is not polynomial in {syms}")
    return tuple(poly.terms())


def evaluate_polynomial(
    expr: sp.Expr,
    variables: Mapping[sp.Symbol, TrigSeries],
    order: int,
    convert: Callable | None = None,
) -> TrigSeries:
    """Substitute series for ``variables`` in the polynomial ``expr``, truncated at ``order``.

    Coefficients of ``expr`` may contain any other symbols (parameters); they must be polynomial in
    ``variables``. ``expr`` is a sympy expression; when the series have native coefficients
    (:mod:`perturb.native`), ``convert`` carries the coefficients of ``expr`` over.

    Raises
    ------
    sympy.PolynomialError
        If ``expr`` is not polynomial in ``variables`` (the caller falls back to numeric quadrature).
    """
    poly = next(iter(variables.values())).poly if variables else TrigPoly
    convert = convert or sp.sympify
    syms = [v for v in variables if expr.has(v)]
    if not syms:
        return TrigSeries.constant(convert(sp.expand(expr)), order, poly)
    terms = _polynomial_terms(expr, tuple(syms))
    powers: dict[tuple[sp.Symbol, int], TrigSeries] = {}

    def power(sym: sp.Symbol, e: int) -> TrigSeries:
        if e == 1:
            return variables[sym].truncate(order)
        key = (sym, e)
        if key not in powers:
            powers[key] = power(sym, e - 1) * variables[sym].truncate(order)
        return powers[key]

    total = TrigSeries([poly() for _ in range(order + 1)], poly)
    for monom, coeff in terms:
        term = TrigSeries.constant(convert(coeff), order, poly)
        for sym, e in zip(syms, monom, strict=True):
            if e:
                term = term * power(sym, e)
        total = total + term
    return total


class NotNumeric(ValueError):
    """The numeric quadrature needs numbers where symbols remain."""


def _multi_indices(n: int, top: int):
    """All multi-indices of length ``n`` with total degree ``<= top``."""
    if n == 0:
        yield ()
        return
    for first in range(top + 1):
        for rest in _multi_indices(n - 1, top - first):
            yield (first, *rest)


def fourier_samples(values, trim: float) -> TrigPoly:
    """Numeric Fourier coefficients of a real 2π-periodic function sampled at N equispaced points."""
    import numpy as np

    values = np.asarray(values, dtype=float)
    n = values.size
    spectrum = np.fft.rfft(values) / n
    scale = max(float(np.max(np.abs(spectrum))), 1e-300)
    terms = {}
    for j in range(min(spectrum.size, (n + 1) // 2)):
        c = spectrum[j].real * (1 if j == 0 else 2)
        s = -spectrum[j].imag * 2 if j else 0.0
        c = c if abs(c) > trim * scale else 0.0
        s = s if abs(s) > trim * scale else 0.0
        if c or s:
            terms[j] = (sp.Float(c), sp.Float(s))
    return TrigPoly(terms)


def evaluate_analytic(
    expr: sp.Expr, variables: Mapping[sp.Symbol, TrigSeries], order: int, n_points: int, trim: float
) -> TrigSeries:
    """Numeric-quadrature fallback of :func:`evaluate_polynomial` for non-polynomial ``expr``.

    Expands ``expr`` in Taylor series about the order-0 series, :math:`f(V_0 + \\delta) =
    \\sum_\\alpha \\partial^\\alpha f(V_0)\\,\\delta^\\alpha/\\alpha!`, with each derivative's Fourier
    coefficients computed numerically (FFT on ``n_points`` samples, coefficients below ``trim`` times
    the largest dropped). The order-0 series and every parameter must be numeric.

    Raises
    ------
    NotNumeric
        If the order-0 series or the expression still contain free symbols.
    """
    import numpy as np

    from perturb.analyticity import singularity

    syms = [v for v in variables if expr.has(v)]
    stray = expr.free_symbols - set(syms)
    if stray:
        raise NotNumeric(
            f"the right-hand side is not polynomial in the state and depends on {sorted(map(str, stray))}: "
            "give numeric values for the parameters (QuasilinearSystem.with_values)"
        )
    grid = 2 * np.pi * np.arange(n_points) / n_points
    s = sp.Symbol("s")
    base, deltas = [], []
    for sym in syms:
        v0 = variables[sym].coefficients[0]
        if v0.free_symbols():
            raise NotNumeric(
                f"the right-hand side is not polynomial in {sym} and its generating solution still has "
                f"unknowns {sorted(map(str, v0.free_symbols()))}: fix the generating amplitudes "
                "(`amplitudes=`) and the parameter values"
            )
        base.append(
            np.broadcast_to(numpy_lambdify(s, v0.as_expr(s))(grid), grid.shape).astype(float)
        )
        deltas.append(TrigSeries([TrigPoly(), *variables[sym].coefficients[1:]]).truncate(order))
    reason = singularity(expr, syms, base)
    if reason is not None:
        raise NotNumeric(f"the numeric quadrature cannot expand {expr}: {reason}")
    total = TrigSeries([TrigPoly() for _ in range(order + 1)])
    for alpha in _multi_indices(len(syms), order):
        derivative = expr
        for sym, a in zip(syms, alpha, strict=True):
            if a:
                derivative = sp.diff(derivative, sym, a) / sp.factorial(a)
        if derivative == 0:
            continue
        samples = np.broadcast_to(numpy_lambdify(syms, derivative)(*base), grid.shape)
        if np.iscomplexobj(samples) or not np.all(np.isfinite(samples)):  # the safety net
            raise NotNumeric(
                f"the numeric quadrature cannot expand {expr}: its derivative {derivative} is not "
                "finite and real along the generating solution (a singularity on the orbit)"
            )
        coeff = fourier_samples(samples, trim)
        term = TrigSeries([coeff] + [TrigPoly() for _ in range(order)])
        for delta, a in zip(deltas, alpha, strict=True):
            for _ in range(a):
                term = term * delta
        total = total + term
    return total
