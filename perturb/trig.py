"""Exact arithmetic on trigonometric polynomials with symbolic coefficients.

A :class:`TrigPoly` stands for

.. math:: u(s) = \\sum_{j \\ge 0} \\left(c_j \\cos js + s_j \\sin js\\right)

and products are linearised to sums (``cos a cos b = [cos(a-b) + cos(a+b)]/2`` ...).  This is what
makes the Poincaré quadratures exact and fast: sympy's ``integrate`` on products of trigonometric
functions is slow and fragile (sympy issues #29876, #12033), while the linearised form turns every
quadrature into a division per harmonic.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Mapping

import sympy as sp

__all__ = ["SympyRing", "TrigPoly"]


class SympyRing:
    """Coefficient operations on sympy expressions.

    The arithmetic of :class:`_Harmonics` is written against this small interface (``zero``,
    ``half``, ``coerce``, ``expand``, ``add``, ``has_float``) so that the engine can run it on a
    faster exact backend (:mod:`perturb.native`) with the same code.
    """

    name = "sympy"
    zero = sp.S.Zero
    half = sp.Rational(1, 2)
    coerce = staticmethod(sp.sympify)
    expand = staticmethod(sp.expand)

    @staticmethod
    def add(items):
        return sp.Add(*items)

    @staticmethod
    def has_float(value) -> bool:
        return value.has(sp.Float)


class _Harmonics:
    """A finite Fourier series in ``s``; the coefficient arithmetic is the class's ``ring``.

    Parameters
    ----------
    terms : mapping
        ``{j: (cos_coefficient, sin_coefficient)}`` for harmonics ``j >= 0``; the sine coefficient of
        ``j = 0`` is ignored.
    """

    __slots__ = ("_terms",)
    ring: type = SympyRing

    def __init__(self, terms: Mapping[int, tuple] | None = None):
        ring = self.ring
        coerce, zero = ring.coerce, ring.zero  # `!= zero`: 5x faster than `!= 0` on symengine
        clean: dict = {}
        for j, (c, s) in (terms or {}).items():
            if j < 0:
                raise ValueError(f"harmonic {j} < 0: fold negative harmonics before building")
            c, s = coerce(c), (zero if j == 0 else coerce(s))
            if c != zero or s != zero:
                clean[j] = (c, s)
        self._terms = clean

    @property
    def terms(self) -> dict:
        """``{j: (cos_coefficient, sin_coefficient)}`` (treat as read-only)."""
        return self._terms

    # ------------------------------------------------------------------ constructors
    @classmethod
    def constant(cls, value) -> TrigPoly:
        return cls({0: (value, 0)})

    @classmethod
    def harmonic(cls, j: int, cos=0, sin=0) -> TrigPoly:
        return cls({j: (cos, sin)})

    # ------------------------------------------------------------------ queries
    def is_zero(self) -> bool:
        return not self.terms

    @property
    def max_harmonic(self) -> int:
        return max(self.terms, default=0)

    def coefficient(self, j: int) -> tuple[sp.Expr, sp.Expr]:
        """``(cos, sin)`` coefficient of harmonic ``j`` (zeros if absent)."""
        zero = self.ring.zero
        return self.terms.get(j, (zero, zero))

    def at_zero(self) -> sp.Expr:
        """Value at ``s = 0``: the sum of the cosine coefficients."""
        return self.ring.add(c for c, _ in self.terms.values())

    def free_symbols(self) -> set:
        out = set()
        for c, s in self.terms.values():
            out |= c.free_symbols | s.free_symbols
        return out

    def as_expr(self, s: sp.Symbol) -> sp.Expr:
        return sp.Add(
            *(c * sp.cos(j * s) + sd * sp.sin(j * s) for j, (c, sd) in sorted(self.terms.items()))
        )

    # ------------------------------------------------------------------ algebra
    def map(self, fn: Callable[[sp.Expr], sp.Expr]) -> TrigPoly:
        """Apply ``fn`` to every coefficient (``expand``, ``subs``, ``cancel`` ...)."""
        return type(self)({j: (fn(c), fn(s)) for j, (c, s) in self.terms.items()})

    def expand(self) -> TrigPoly:
        return self.map(self.ring.expand)

    def subs(self, mapping) -> TrigPoly:
        if not mapping:
            return self
        expand = self.ring.expand
        return self.map(lambda e: expand(e.xreplace(mapping)) if e.free_symbols else e)

    def __add__(self, other: TrigPoly) -> TrigPoly:
        acc = dict(self.terms)
        for j, (c, s) in other.terms.items():
            c0, s0 = acc.get(j, (self.ring.zero, self.ring.zero))
            acc[j] = (c0 + c, s0 + s)
        return type(self)(acc)

    def __neg__(self) -> TrigPoly:
        return self.scale(-1)

    def __sub__(self, other: TrigPoly) -> TrigPoly:
        return self + (-other)

    def scale(self, factor) -> TrigPoly:
        factor = self.ring.coerce(factor)
        if factor == self.ring.zero:
            return type(self)()
        return type(self)({j: (factor * c, factor * s) for j, (c, s) in self.terms.items()})

    def __mul__(self, other: TrigPoly) -> TrigPoly:
        """Product, linearised to a sum of harmonics, coefficients expanded."""
        zero = self.ring.zero
        cos_acc: dict[int, list] = defaultdict(list)
        sin_acc: dict[int, list] = defaultdict(list)
        for i, (ci, si) in self.terms.items():
            ci_nz, si_nz = ci != zero, si != zero
            for j, (cj, sj) in other.terms.items():
                lo, hi = abs(i - j), i + j
                sign = 1 if i >= j else -1  # sin((i-j)s) = sign * sin(|i-j| s)
                cj_nz, sj_nz = cj != zero, sj != zero
                if ci_nz and cj_nz:
                    cc = ci * cj
                    cos_acc[lo].append(cc)
                    cos_acc[hi].append(cc)
                if si_nz and sj_nz:
                    ss = si * sj
                    cos_acc[lo].append(ss)
                    cos_acc[hi].append(-ss)
                if ci_nz and sj_nz:  # cos(i) sin(j) = [sin(i+j) - sin(i-j)]/2
                    cs = ci * sj
                    sin_acc[hi].append(cs)
                    sin_acc[lo].append(-sign * cs)
                if si_nz and cj_nz:  # sin(i) cos(j) = [sin(i+j) + sin(i-j)]/2
                    sc = si * cj
                    sin_acc[hi].append(sc)
                    sin_acc[lo].append(sign * sc)
        keys = set(cos_acc) | set(sin_acc)
        ring = self.ring
        half, add, expand = ring.half, ring.add, ring.expand
        return type(self)(
            {
                k: (
                    expand(half * add(cos_acc.get(k, ()))),
                    expand(half * add(sin_acc.get(k, ()))),
                )
                for k in keys
            }
        )

    def derivative(self) -> TrigPoly:
        """d/ds."""
        return type(self)({j: (j * s, -j * c) for j, (c, s) in self.terms.items() if j})

    def __repr__(self) -> str:
        if self.ring is not SympyRing:
            return f"{type(self).__name__}({self.terms})"
        return f"{type(self).__name__}({self.as_expr(sp.Symbol('s'))})"

    def __eq__(self, other) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        diff = self - other
        expand = self.ring.expand
        return all(expand(c) == 0 and expand(s) == 0 for c, s in diff.terms.values())

    __hash__ = None  # mutable-looking container semantics: not hashable


class TrigPoly(_Harmonics):
    """A finite Fourier series in ``s`` with sympy coefficients (immutable by convention).

    Parameters
    ----------
    terms : mapping
        ``{j: (cos_coefficient, sin_coefficient)}`` for harmonics ``j >= 0``; the sine coefficient of
        ``j = 0`` is ignored.
    """

    __slots__ = ("_pending",)
    ring = SympyRing

    def __init__(self, terms: Mapping[int, tuple] | None = None):
        super().__init__(terms)
        self._pending = None

    @classmethod
    def deferred(cls, terms: Mapping[int, tuple], convert: Callable) -> TrigPoly:
        """A polynomial whose coefficients are ``convert(c)`` for ``c`` in ``terms``, converted when
        first read (the engine hands back native coefficients this way: most are never read)."""
        poly = cls()
        poly._pending = (dict(terms), convert)
        return poly

    @property
    def terms(self) -> dict:
        """``{j: (cos_coefficient, sin_coefficient)}`` (treat as read-only)."""
        if self._pending is not None:
            native, convert = self._pending
            self._terms = {j: (convert(c), convert(s)) for j, (c, s) in native.items()}
            self._pending = None
        return self._terms

    def __reduce__(self):
        return (TrigPoly, (self.terms,))
