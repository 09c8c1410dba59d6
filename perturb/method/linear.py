"""Large linear periodicity conditions with a unique solution, solved off sympy's expression domain.

From the second order on, the corrections of the generating amplitudes and of the frequency enter the
periodicity conditions linearly, with coefficients that are large rational functions of the body's
parameters and of radicals such as :math:`\\sqrt{1-\\gamma^2}` (which first integrals bring in).
sympy's ``linsolve`` eliminates over its expression domain there (the radicals and :math:`\\pi` are
not polynomial generators it accepts), cancelling an expression tree at every step: seconds to
minutes an order. Here:

1. on symengine, every square root :math:`\\sqrt{b}` is written through a symbol :math:`S`
   (:math:`b^{p/2} = S\\,b^{(p-1)/2}`), each condition is multiplied by the least common multiple of
   its denominators (factor by factor) and checked linear;
2. its polynomial coefficients are read into sympy's sparse polynomial ring over the rationals
   (generators: the :math:`S`, the parameters, :math:`\\pi`; no sympy expression on the way) and the
   system is eliminated by Gauss-Jordan on fractions of these polynomials, :math:`S` free, every
   pivot non-zero at :math:`S = \\sqrt{b}`; fractions are cancelled after every operation, common
   monomials directly and the rest by sympy's dense gcd (its sparse one is quadratic in the number
   of terms: 19 s instead of 0.25 s on the disk's order-3 conditions);
3. each value :math:`N/D` is reduced modulo :math:`S^2 - b`, its denominator rationalised (times
   the conjugate in every :math:`S`), cancelled, converted to sympy with :math:`S = \\sqrt{b}` and
   given the canonicalisation sympy's route applies to its values (:func:`canonical_value`).

Without radicals a rational function in lowest terms is unique, so the value is the very expression
sympy's route returns. With square roots it is unique only up to the relation :math:`S^2 = b`, which
sympy's expression domain applies wherever a product happens to form :math:`S^2` along its
elimination: its result depends on that path. This route gives the unique form with a radical-free
denominator, which is sympy's whenever sympy's value has a radical-free denominator: the disk's
(orders 1-3 specialised and 2 symbolic give identical ``srepr``, see
``benchmarks/check_disk_identical.py``). Where sympy's value keeps a radical in a denominator the
forms differ, the values are equal: on random systems of 1-3 unknowns with :math:`\\sqrt{1-a^2}`
and :math:`1/\\sqrt{1-a^2}` in every coefficient, 22 of 34 were identical, all equal (reducing
without rationalising matched 30 of 34 but not the disk's :math:`\\Omega_4`). Such systems below
``LINEAR_SYMPY_MAX_TERMS`` terms never come here.

Small systems (:data:`~perturb._defaults.LINEAR_SYMPY_MAX_TERMS`), systems without a unique solution,
radicals other than square roots and the imaginary unit are left to sympy's route
(:func:`solve_unique` returns ``None``).
"""

from __future__ import annotations

from collections.abc import Iterable

import sympy as sp
from sympy.polys.rings import ring as polynomial_ring

from perturb._defaults import LINEAR_SYMPY_MAX_TERMS
from perturb.native import Converter, se

__all__ = ["canonical_value", "solve_unique"]


class _NotHere(Exception):
    """The system is not one this route takes: sympy's route solves it."""


def canonical_value(value: sp.Expr) -> sp.Expr:
    """The form sympy's linear route gives a solved value (``expand(factor_terms(cancel(v)))``,
    as :func:`perturb.method.conditions._solve_linear` writes it)."""
    return sp.expand(sp.factor_terms(sp.cancel(value)))


def _terms(value) -> tuple:
    return value.args if isinstance(value, se.Add) else (value,)


def solve_unique(eqs: list, unknowns: Iterable[sp.Symbol], conv: Converter) -> dict | None:
    """Solve the linear equations ``eqs = 0`` here when that is worth it and the solution unique.

    Parameters
    ----------
    eqs : list
        Native (symengine) expressions, expanded and non-zero.
    unknowns : iterable of sympy.Symbol
        The open unknowns of the construction; those the equations contain are solved for.
    conv : perturb.native.Converter
        The construction's converter.

    Returns
    -------
    dict or None
        ``{unknown: sympy value}`` as sympy's route returns it, or ``None`` when this route does not
        apply: the ring is not native, the system is small (at most ``LINEAR_SYMPY_MAX_TERMS``
        terms), not linear, has no unique solution, or holds a radical other than a square root.
    """
    if se is None or not conv.native or not eqs:
        return None
    if sum(len(_terms(e)) for e in eqs) <= LINEAR_SYMPY_MAX_TERMS:
        return None
    present = set().union(*(conv.symbols(e) for e in eqs)) & set(unknowns)
    names = sorted(present, key=str)
    if not names:
        return None
    symbols = [conv.to_native(u) for u in names]
    try:
        radicals = _Radicals(eqs)
        rows = [_polynomial_row(radicals.rewrite(e), symbols) for e in eqs]
        ring = _Ring(radicals, rows)
        matrix = [[ring.read(c) for c in row] for row in rows]
        values = _gauss_jordan(matrix, len(symbols), ring)
        return {
            name: canonical_value(ring.to_sympy(value, conv))
            for name, value in zip(names, values, strict=True)
        }
    except _NotHere:
        return None


class _Radicals:
    """The square roots of a system, as symbols ``S`` with ``S**2 = b`` (``b`` free of radicals)."""

    def __init__(self, eqs: list):
        self.bases: dict = {}  # b -> S
        self.replace: dict = {}  # b**(p/2) -> S * b**((p - 1)/2)
        for e in eqs:
            if e.has(se.I):
                raise _NotHere
            for atom in e.atoms(se.Pow):
                base, exponent = atom.args
                if exponent.is_integer:
                    continue
                if not (isinstance(exponent, se.Rational) and (2 * exponent).is_integer):
                    raise _NotHere
                if any(not p.args[1].is_integer for p in base.atoms(se.Pow)):
                    raise _NotHere
                if base not in self.bases:
                    self.bases[base] = se.Symbol(f"_perturb_sqrt{len(self.bases)}")
                self.replace[atom] = self.bases[base] * base ** ((int(2 * exponent) - 1) // 2)

    def rewrite(self, value):
        """``value`` with every radical written through its symbol (degree one in each)."""
        return se.expand(value.xreplace(self.replace)) if self.replace else value


def _factors(value) -> dict:
    """``value`` (a denominator) as ``{base: exponent}``."""
    out: dict = {}
    for factor in value.args if isinstance(value, se.Mul) else (value,):
        base, exponent = factor.args if isinstance(factor, se.Pow) else (factor, 1)
        out[base] = out.get(base, 0) + int(exponent)
    return out


def _polynomial_row(e, symbols: list) -> list:
    """``[c_1, ..., c_n, c_0]``: ``e = sum c_i x_i + c_0`` times the lcm of its denominators."""
    parts = []
    lcm: dict = {}
    for term in _terms(e):
        num, den = term.as_numer_denom()
        factors = _factors(den)
        for base, exponent in factors.items():
            lcm[base] = max(lcm.get(base, 0), exponent)
        parts.append((num, factors))
    total = se.expand(
        se.Add(
            *(
                se.Mul(num, *(b ** (x - factors.get(b, 0)) for b, x in lcm.items()))
                for num, factors in parts
            )
        )
    )
    unknown = set(symbols)
    row = []
    for u in symbols:
        coefficient = total.diff(u)
        if coefficient.free_symbols & unknown:
            raise _NotHere  # not linear
        row.append(coefficient)
    row.append(se.expand(total.xreplace({u: 0 for u in symbols})))
    return row


class _Ring:
    """The polynomial ring (rational coefficients, lex order, the ``S`` first) of one system."""

    def __init__(self, radicals: _Radicals, rows: list):
        atoms: dict = {}
        for s in radicals.bases.values():
            atoms.setdefault(s, len(atoms))
        for entry in (*radicals.bases, *(c for row in rows for c in row)):
            for term in _terms(entry):
                for base in self._bases(term):
                    atoms.setdefault(base, len(atoms))
        self.atoms = list(atoms)
        self.index = atoms
        self.ring = polynomial_ring([f"g{i}" for i in range(len(atoms))], sp.QQ)[0]
        self.roots = [(self.index[s], self.read(b)) for b, s in radicals.bases.items()]
        self.sqrt = {s: se.sqrt(b) for b, s in radicals.bases.items()}

    @staticmethod
    def _bases(term) -> list:
        out = []
        for factor in term.args if isinstance(term, se.Mul) else (term,):
            if isinstance(factor, se.Number):
                continue
            base = factor.args[0] if isinstance(factor, se.Pow) else factor
            if isinstance(base, (se.Add, se.Mul, se.Pow)):
                raise _NotHere  # not an expanded polynomial
            out.append(base)
        return out

    def read(self, value):
        """An expanded native polynomial as a ring element."""
        coefficients: dict = {}
        width = len(self.atoms)
        for term in _terms(value):
            if term == 0:
                continue
            exponents = [0] * width
            coefficient = sp.QQ(1)
            for factor in term.args if isinstance(term, se.Mul) else (term,):
                if isinstance(factor, se.Rational):  # integers included
                    coefficient *= sp.QQ(int(factor.p), int(factor.q))
                    continue
                base, exponent = factor.args if isinstance(factor, se.Pow) else (factor, 1)
                if base not in self.index or not (isinstance(exponent, int) or exponent.is_integer):
                    raise _NotHere
                if int(exponent) < 1:
                    raise _NotHere
                exponents[self.index[base]] += int(exponent)
            key = tuple(exponents)
            coefficients[key] = coefficients.get(key, 0) + coefficient
        return self.ring.from_dict({k: c for k, c in coefficients.items() if c})

    def reduce(self, poly):
        """``poly`` with every ``S**2`` replaced by ``b`` (degree at most one in each ``S``)."""
        for i, b in self.roots:
            if all(m[i] < 2 for m in poly.keys()):
                continue
            groups: dict = {}
            for m, c in poly.items():
                q, r = divmod(m[i], 2)
                rest = (*m[:i], r, *m[i + 1 :])
                groups.setdefault(q, {})[rest] = c
            poly = self.ring.add(*(self.ring.from_dict(g) * b**q for q, g in groups.items()))
        return poly

    def cancel(self, num, den) -> tuple:
        """``num/den`` in lowest terms (a dense gcd: sympy's sparse one is quadratic in the terms)."""
        if not num:
            return num, self.ring.one
        common = [min(e) for e in zip(*num.keys(), *den.keys(), strict=True)]
        if any(common):  # the common monomial factor, at no cost
            num, den = _shift(num, common), _shift(den, common)
        if den.is_ground:
            return num.quo_ground(den.LC), self.ring.one
        if len(den) == 1:  # a monomial coprime to num
            return num, den
        gens = self.ring.symbols
        coefficient, p, q = sp.Poly.from_dict(dict(num), *gens, domain=sp.QQ).cancel(
            sp.Poly.from_dict(dict(den), *gens, domain=sp.QQ)
        )
        p = self.ring.from_dict(p.as_dict(native=True))
        return p.mul_ground(sp.QQ.from_sympy(coefficient)), self.ring.from_dict(
            q.as_dict(native=True)
        )

    def nonzero(self, value: tuple) -> bool:
        """Whether ``num/den`` is non-zero at ``S = sqrt(b)`` (its reduced numerator is)."""
        return bool(value[0]) and bool(self.reduce(value[0]))

    def to_sympy(self, value: tuple, conv: Converter) -> sp.Expr:
        """``num/den`` (``S`` free) as the sympy value with ``S = sqrt(b)``: reduced modulo
        ``S**2 - b``, the denominator rationalised, cancelled."""
        num, den = self.reduce(value[0]), self.reduce(value[1])
        if not den:
            raise _NotHere  # the denominator vanishes at S = sqrt(b)
        for i, _ in self.roots:  # rationalise: times the conjugate in S_i
            conjugate = self.ring.from_dict({m: (-c if m[i] % 2 else c) for m, c in den.items()})
            num, den = self.reduce(num * conjugate), self.reduce(den * conjugate)
        num, den = self.cancel(num, den)
        atoms = [conv.to_sympy(self.sqrt.get(a, a), expand=False) for a in self.atoms]
        return num.as_expr(*atoms) / den.as_expr(*atoms)


def _shift(poly, exponents: list):
    """``poly`` divided by the monomial with these exponents (which divides it)."""
    return poly.ring.from_dict(
        {tuple(a - b for a, b in zip(m, exponents, strict=True)): c for m, c in poly.items()}
    )


def _gauss_jordan(rows: list, n: int, ring: _Ring) -> list:
    """Gauss-Jordan on rows ``[c_1, ..., c_n, c_0]`` (``sum c_i x_i + c_0 = 0``) of fractions.

    Entries are ``(numerator, denominator)`` pairs in ``ring``, cancelled after every operation.
    Every pivot is non-zero at ``S = sqrt(b)`` (:meth:`_Ring.nonzero`), so the elimination is the
    one over the radicals' field and the solution is that system's. Returns each unknown's value;
    raises :class:`_NotHere` unless the solution is unique (singular and inconsistent systems are
    left to sympy's route and its messages).
    """
    one = ring.ring.one
    rows = [[(c, one) for c in row] for row in rows]
    pivots: list[int] = []
    for col in range(n):
        candidates = [i for i, r in enumerate(rows) if i not in pivots and ring.nonzero(r[col])]
        if not candidates:
            raise _NotHere
        p = min(
            candidates, key=lambda i: (sum(bool(c[0]) for c in rows[i]), len(rows[i][col][0]), i)
        )
        pn, pd = rows[p][col]
        rows[p] = [ring.cancel(c[0] * pd, c[1] * pn) if c[0] else c for c in rows[p]]
        for i, r in enumerate(rows):
            if i == p or not r[col][0]:
                continue
            fn, fd = r[col]
            rows[i] = [
                a
                if not b[0]
                else ring.cancel(a[0] * fd * b[1] - fn * b[0] * a[1], a[1] * fd * b[1])
                for a, b in zip(r, rows[p], strict=True)
            ]
        pivots.append(p)
    if any(rows[i][n][0] for i in range(len(rows)) if i not in pivots):
        raise _NotHere  # inconsistent
    return [(-rows[p][n][0], rows[p][n][1]) for p in pivots]
