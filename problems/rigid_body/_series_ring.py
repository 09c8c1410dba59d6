"""Truncated power series in epsilon over sympy's sparse polynomial rings (the reduction's arithmetic).

The rigid-body reduction (:mod:`problems.rigid_body.reduction`) is a chain of substitutions, series
inversions and square roots, all truncated at a power of epsilon. Done on sympy expressions it
spends most of its time in ``subs``, ``expand`` and the conversion back from polynomials; here the
whole chain stays in one :func:`sympy.polys.rings.ring` and leaves it only at the end:

* :meth:`SeriesRing.to_expr` builds the expanded sympy expression of a ring element directly from its
  terms (the same canonical expression as ``sympy.expand(poly.as_expr())``, without the round trip),
* :meth:`SeriesRing.export` / :meth:`SeriesRing.load` turn ring elements into plain integers and back
  (what the disk cache stores: independent of sympy's ground types),
* :meth:`SeriesRing.evaluate` puts numbers in for some generators, exactly, for the numeric maps.

A ring built with ``values`` has the parameters put in *before* the reduction (their generators do
not exist): evaluation at numbers is a ring homomorphism and commutes with truncation, so the result
is the symbolic reduction evaluated at those numbers, for a fraction of the cost.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from fractions import Fraction

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.rings import PolyElement, ring

__all__ = ["INV_A", "INV_B", "SeriesRing"]

#: Ring generators standing for 1/a and 1/b (polynomial mode of the series ring).
INV_A, INV_B = sp.symbols("inv_a inv_b")

#: The terms' layout of the polynomials evaluated so far (:meth:`SeriesRing._layout`), by id (the
#: polynomial is kept beside its layout, so the id is not reused): the reductions' few series.
_LAYOUTS: dict[int, tuple] = {}

#: A ring element as plain data: exponent tuple -> (numerator, denominator) of its coefficient.
PolyData = dict[tuple[int, ...], tuple[int, int]]


class SeriesRing:
    """Polynomials in ``variables`` and the parameters, truncated in ``variables[0]`` (epsilon).

    Parameters
    ----------
    order : int
        Highest power of epsilon kept.
    variables : tuple of sympy.Symbol
        Epsilon first, then every other non-parameter generator.
    params : tuple of sympy.Symbol
        The body's parameters; ``ratios`` (a, b) among them are the moment ratios.
    ratios : tuple of sympy.Symbol
        ``(a, b)``: the parameters that appear in denominators.
    fraction_field : bool
        ``False``: a, b and their inverses ``1/a``, ``1/b`` are ring generators over QQ (fast; enough
        when the only denominators are a and b). ``True``: coefficients in QQ(a, b).
    values : mapping, optional
        Exact values (sympy Rationals) of *all* parameters, put in before anything else; the ring
        then has no parameter generators and coefficients in QQ.
    """

    def __init__(
        self,
        order: int,
        variables: tuple[sp.Symbol, ...],
        params: tuple[sp.Symbol, ...],
        ratios: tuple[sp.Symbol, sp.Symbol],
        fraction_field: bool,
        values: Mapping[sp.Symbol, sp.Rational] | None = None,
    ):
        self.order = order
        self.values = dict(values) if values else {}
        if self.values and set(self.values) != set(params):
            raise AssertionError(f"values must fix every parameter {params}, got {self.values}")
        self.ratios = ratios
        self.fraction_field = fraction_field and not self.values
        if self.values:
            extra: tuple[sp.Symbol, ...] = ()
        elif self.fraction_field:
            extra = tuple(s for s in params if s not in ratios)
        else:
            extra = (*ratios, INV_A, INV_B, *(s for s in params if s not in ratios))
        self.symbols = (*variables, *extra)
        domain = QQ.frac_field(*ratios) if self.fraction_field else QQ
        self.ring, *_ = ring(self.symbols, domain)
        self.index = {s: i for i, s in enumerate(self.symbols)}
        self._inverse_pairs = (
            ()
            if self.values or self.fraction_field
            else (
                (self.index[ratios[0]], self.index[INV_A]),
                (self.index[ratios[1]], self.index[INV_B]),
            )
        )

    # ------------------------------------------------------------------ sympy -> ring
    def __call__(self, expr) -> PolyElement:
        expr = sp.sympify(expr)
        if self.values:
            expr = expr.xreplace(self.values)
        expr = sp.expand(expr)
        if not self.fraction_field and not self.values:
            inverse = {self.ratios[0]: INV_A, self.ratios[1]: INV_B}
            expr = expr.replace(
                lambda e: e.is_Pow and e.base in inverse and e.exp.is_negative,
                lambda e: inverse[e.base] ** (-e.exp),
            )
        if not self.fraction_field:
            stray = expr.free_symbols - set(self.symbols)
            if stray or any(
                isinstance(d, sp.Pow) and d.exp.is_negative for d in sp.preorder_traversal(expr)
            ):
                raise AssertionError(f"cannot represent {expr} with inverse generators only")
        return self.ring.from_expr(expr)

    def gen(self, symbol: sp.Symbol) -> PolyElement:
        return self.ring.gens[self.index[symbol]]

    # ------------------------------------------------------------------ truncated arithmetic
    def trunc(self, poly: PolyElement) -> PolyElement:
        n = self.order
        return self.ring.from_dict({m: c for m, c in poly.items() if m[0] <= n})

    def _by_degree(self, poly: PolyElement) -> list[PolyElement | None]:
        parts: list[dict] = [{} for _ in range(self.order + 1)]
        for m, c in poly.items():
            if m[0] <= self.order:
                parts[m[0]][m] = c
        return [self.ring.from_dict(d) if d else None for d in parts]

    def mul(self, x: PolyElement, y: PolyElement) -> PolyElement:
        """Product truncated at eps**order (only the pairs of degrees that survive are multiplied)."""
        xs, ys = self._by_degree(x), self._by_degree(y)
        out = self.ring.zero
        for i, xi in enumerate(xs):
            if xi is None:
                continue
            for j in range(self.order + 1 - i):
                if ys[j] is not None:
                    out += xi * ys[j]
        return out

    def substitute(
        self, poly: PolyElement, mapping: Mapping[sp.Symbol, PolyElement]
    ) -> PolyElement:
        """Replace generators by series (truncated products)."""
        slots = [(self.index[s], v) for s, v in mapping.items()]
        powers: dict[tuple[int, int], PolyElement] = {}

        def power(i: int, value: PolyElement, e: int) -> PolyElement:
            key = (i, e)
            if key not in powers:
                powers[key] = value if e == 1 else self.mul(power(i, value, e - 1), value)
            return powers[key]

        result = self.ring.zero
        for monom, coeff in poly.items():
            rest = list(monom)
            factors = []
            for i, value in slots:
                if rest[i]:
                    factors.append(power(i, value, rest[i]))
                    rest[i] = 0
            term = self.ring.from_dict({tuple(rest): coeff})
            if term and rest[0] > self.order:
                continue
            for f in factors:
                term = self.mul(term, f)
            result += term
        return self.trunc(result)

    def _split_unit(self, s: PolyElement):
        """s = c0 * (1 + u) with c0 a constant and u = O(eps)."""
        lowest = {m: c for m, c in s.items() if m[0] == 0}
        if len(lowest) != 1 or any(next(iter(lowest))):
            raise AssertionError(f"series has no constant leading term: {s.as_expr()}")
        c0 = next(iter(lowest.values()))
        return c0, s * (1 / c0) - 1

    def inverse(self, s: PolyElement) -> PolyElement:
        c0, u = self._split_unit(s)
        out, term = self.ring.one, self.ring.one
        for _ in range(self.order):
            term = self.mul(term, -u)
            out += term
        return out * (1 / c0)

    def sqrt(self, s: PolyElement) -> PolyElement:
        c0, u = self._split_unit(s)
        if c0 != 1:
            raise AssertionError(f"sqrt of a series with leading term {c0} (expected 1)")
        out, term = self.ring.one, self.ring.one
        for n in range(1, self.order + 1):
            term = self.mul(term, u)
            out += self.ring.domain.convert(sp.binomial(sp.Rational(1, 2), n)) * term
        return out

    # ------------------------------------------------------------------ ring -> sympy
    def _merged_terms(self, poly: PolyElement) -> dict[tuple[int, ...], object]:
        """Terms with a**i * inv_a**j merged into a**(i - j) (likewise b); zero sums dropped."""
        if not self._inverse_pairs:
            return dict(poly.items())
        merged: dict[tuple[int, ...], object] = {}
        for monom, coeff in poly.items():
            m = list(monom)
            for direct, inverse in self._inverse_pairs:
                m[direct] -= m[inverse]
                m[inverse] = 0
            key = tuple(m)
            merged[key] = merged[key] + coeff if key in merged else coeff
        return {m: c for m, c in merged.items() if c}

    def to_expr(self, poly: PolyElement) -> sp.Expr:
        """The expanded sympy expression of ``poly`` (1/a and 1/b written as negative powers)."""
        if self.fraction_field:
            return sp.expand(poly.as_expr())
        symbols = self.symbols
        terms = []
        for monom, coeff in self._merged_terms(poly).items():
            factors = [symbols[i] ** e for i, e in enumerate(monom) if e]
            rational = sp.Rational(int(QQ.numer(coeff)), int(QQ.denom(coeff)))
            terms.append(sp.Mul(rational, *factors))
        return sp.Add(*terms)

    def coefficients(self, poly: PolyElement) -> tuple[sp.Expr, ...]:
        """Coefficients of eps**0 .. eps**order as expanded sympy expressions."""
        grouped: list[dict] = [{} for _ in range(self.order + 1)]
        for m, c in poly.items():
            grouped[m[0]][(0, *m[1:])] = c
        return tuple(self.to_expr(self.ring.from_dict(d)) if d else sp.S.Zero for d in grouped)

    # ------------------------------------------------------------------ plain data
    def export(self, poly: PolyElement) -> PolyData:
        """``poly`` as plain integers (only for the polynomial modes over QQ)."""
        if self.fraction_field:
            raise AssertionError("fraction-field series are not exported")
        return {m: (int(QQ.numer(c)), int(QQ.denom(c))) for m, c in poly.items()}

    def load(self, data: PolyData) -> PolyElement:
        """The inverse of :meth:`export`."""
        return self.ring.from_dict({m: QQ(p, q) for m, (p, q) in data.items()})

    # ------------------------------------------------------------------ numbers in
    def _coefficient_value(self, coeff, values: Mapping[sp.Symbol, object]) -> Fraction:
        """A coefficient as a Fraction (in QQ(a, b): a and b put in from ``values``)."""
        if not self.fraction_field:
            return Fraction(int(QQ.numer(coeff)), int(QQ.denom(coeff)))
        point = [
            (gen, QQ(Fraction(values[s]).numerator, Fraction(values[s]).denominator))
            for gen, s in zip(coeff.numer.ring.gens, self.ratios, strict=True)
        ]
        num, den = coeff.numer.evaluate(point), coeff.denom.evaluate(point)
        return Fraction(int(QQ.numer(num)), int(QQ.denom(num))) / Fraction(
            int(QQ.numer(den)), int(QQ.denom(den))
        )

    def free_generators(self, values: Mapping[sp.Symbol, object]) -> list[sp.Symbol]:
        """The generators that stay when ``values`` are put in (1/a, 1/b go with a, b)."""
        fixed = {self.index[s] for s in values if s in self.index}
        for direct, inverse in self._inverse_pairs:
            if direct in fixed:
                fixed.add(inverse)
        return [s for i, s in enumerate(self.symbols) if i not in fixed]

    def evaluate_float(
        self, poly: PolyElement, values: Mapping[sp.Symbol, Fraction], keep: Sequence[sp.Symbol]
    ) -> dict[tuple[int, ...], float]:
        """:meth:`evaluate` rounded once to float: the same numbers, computed faster.

        Each coefficient is the exact rational sum of its terms, formed over one common
        denominator in integer arithmetic (no gcd of large integers along the way) and rounded
        once by integer true division, which is correctly rounded, as ``float(Fraction)`` is; a
        coefficient that is exactly zero is dropped, as :meth:`evaluate` drops it. The terms'
        layout is kept per polynomial (a sweep evaluates the same series at many points).
        """
        if self.fraction_field:
            return {m: float(c) for m, c in self.evaluate(poly, values, keep).items()}
        slots = {self.index[s]: Fraction(v) for s, v in values.items() if s in self.index}
        for direct, inverse in self._inverse_pairs:
            if direct in slots:
                slots[inverse] = 1 / slots[direct]
        kept = tuple(self.index[s] for s in keep)
        if set(slots) | set(kept) != set(range(len(self.symbols))):
            raise AssertionError(f"evaluate needs every generator of {self.symbols}")
        order = tuple(sorted(slots))
        nums = [slots[i].numerator for i in order]
        dens = [slots[i].denominator for i in order]
        num_powers: dict[tuple[int, int], int] = {}
        den_powers: dict[tuple[int, int], int] = {}
        out: dict[tuple[int, ...], float] = {}
        for key, common, top, terms in self._layout(poly, order, kept):
            denominator = common
            for k, e in top:
                if (k, e) not in den_powers:
                    den_powers[k, e] = dens[k] ** e
                denominator *= den_powers[k, e]
            total = 0
            for term, factors in terms:
                for k, e, missing in factors:
                    if e:
                        if (k, e) not in num_powers:
                            num_powers[k, e] = nums[k] ** e
                        term *= num_powers[k, e]
                    if missing:
                        if (k, missing) not in den_powers:
                            den_powers[k, missing] = dens[k] ** missing
                        term *= den_powers[k, missing]
                total += term
            if total:
                out[key] = total / denominator
        return out

    def _layout(self, poly: PolyElement, order: tuple, kept: tuple) -> list:
        """``poly``'s terms grouped by their monomial in the kept generators: for each group its
        key, the lcm of its coefficients' denominators, the highest exponent of each evaluated
        generator, and each term as (its numerator scaled to the lcm, [(slot, exponent, top
        exponent - exponent)]) — kept per polynomial and split of the generators."""
        cache = _LAYOUTS
        entry = cache.get(id(poly))
        if entry is not None and entry[0] is poly and entry[1] == (order, kept):
            return entry[2]
        groups: dict[tuple[int, ...], list] = {}
        for monom, coeff in poly.items():
            groups.setdefault(tuple(monom[i] for i in kept), []).append(
                (int(QQ.numer(coeff)), int(QQ.denom(coeff)), tuple(monom[i] for i in order))
            )
        layout = []
        for key, terms in groups.items():
            top = [max(t[2][k] for t in terms) for k in range(len(order))]
            common = 1
            for _, q, _ in terms:
                common = common * q // math.gcd(common, q)
            scaled = []
            for p, q, exponents in terms:
                factors = tuple(
                    (k, e, top[k] - e) for k, e in enumerate(exponents) if e or top[k] - e
                )
                scaled.append((p * (common // q), factors))
            layout.append((key, common, tuple((k, e) for k, e in enumerate(top) if e), scaled))
        cache[id(poly)] = (poly, (order, kept), layout)
        return layout

    def evaluate(
        self, poly: PolyElement, values: Mapping[sp.Symbol, Fraction], keep: Sequence[sp.Symbol]
    ) -> dict[tuple[int, ...], Fraction]:
        """``poly`` with exact numbers put in for ``values``: exponents over ``keep`` -> coefficient.

        Every generator of the ring must be in ``values`` or ``keep`` (1/a and 1/b follow a and b).
        """
        slots = {self.index[s]: Fraction(v) for s, v in values.items() if s in self.index}
        for direct, inverse in self._inverse_pairs:
            if direct in slots:
                slots[inverse] = 1 / slots[direct]
        kept = [self.index[s] for s in keep]
        if set(slots) | set(kept) != set(range(len(self.symbols))):
            raise AssertionError(f"evaluate needs every generator of {self.symbols}")
        powers: dict[tuple[int, int], Fraction] = {}
        out: dict[tuple[int, ...], Fraction] = {}
        for monom, coeff in poly.items():
            value = self._coefficient_value(coeff, values)
            for i, x in slots.items():
                e = monom[i]
                if e:
                    if (i, e) not in powers:
                        powers[i, e] = x**e
                    value *= powers[i, e]
            key = tuple(monom[i] for i in kept)
            out[key] = out.get(key, 0) + value
        return {m: c for m, c in out.items() if c}
