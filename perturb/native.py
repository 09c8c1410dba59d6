"""The coefficient backend of the construction: symengine when installed, sympy otherwise.

The Poincaré construction spends nearly all of its time multiplying and expanding the exact
coefficients of trigonometric polynomials (rational numbers, parameters, the unknowns of the
periodicity conditions). symengine does this 100-1000 times faster than sympy on the same
expressions and is exact (integers and rationals of arbitrary size), so the engine keeps its
coefficients in symengine throughout a run and meets sympy only at the edges: the system it is given,
the conditions handed to the solvers (:mod:`perturb.method.conditions`) and the results it returns
(:class:`~perturb.trig.TrigPoly` with sympy coefficients, converted when first read).

A :class:`Converter` carries the symbols across: symengine symbols have a name only, so the sympy
symbol of every name is remembered (with its assumptions: ``Symbol("kappa", positive=True)`` comes
back as itself), and two sympy symbols that share a name get distinct names on the native side.

``PERTURB_BACKEND=sympy`` forces the sympy backend (for comparison and benchmarks); a run whose
inputs hold floating-point numbers also uses sympy, so that its float arithmetic is the one it always
was (see :func:`ring_for`).
"""

from __future__ import annotations

import os
from collections.abc import Iterable

import sympy as sp

from perturb.trig import SympyRing, TrigPoly, _Harmonics

__all__ = ["BACKEND", "Converter", "NativeTrigPoly", "NotNative", "ring_for"]

try:  # pragma: no branch - which branch runs depends on the installation
    import symengine as se
except ImportError:  # pragma: no cover - exercised where symengine is absent
    se = None

#: Name of the native backend in use: "symengine", or "sympy" when symengine is absent or
#: ``PERTURB_BACKEND=sympy`` asks for it.
BACKEND = (
    "symengine" if se is not None and os.environ.get("PERTURB_BACKEND") != "sympy" else "sympy"
)


class NotNative(Exception):
    """An expression the native backend cannot hold (e.g. sympy's ``CRootOf``): redo in sympy."""


class SymengineRing:
    """Coefficient operations on symengine expressions (the interface of :class:`SympyRing`)."""

    name = "symengine"
    zero = se.Integer(0) if se is not None else None
    half = se.Rational(1, 2) if se is not None else None

    @staticmethod
    def coerce(value):
        return se.sympify(value)

    @staticmethod
    def expand(value):
        return se.expand(value)

    @staticmethod
    def add(items: Iterable):
        return se.Add(*items)

    @staticmethod
    def has_float(value) -> bool:
        return bool(value.atoms(se.RealNumber))


class NativeTrigPoly(_Harmonics):
    """:class:`~perturb.trig.TrigPoly`'s arithmetic on native (symengine) coefficients.

    Internal to the engine: coefficients must already be native (see :class:`Converter`).
    """

    __slots__ = ()
    ring = SymengineRing


class Converter:
    """Carries expressions between sympy and the native backend for one construction.

    Parameters
    ----------
    ring : class
        :class:`SymengineRing` or :class:`~perturb.trig.SympyRing` (then both directions are the
        identity).
    """

    def __init__(self, ring):
        self.ring = ring
        self.poly = NativeTrigPoly if ring is SymengineRing else TrigPoly
        self._names: dict[sp.Symbol, str] = {}  # sympy symbol -> its native name
        self._back: dict[str, sp.Symbol] = {}  # native name -> sympy symbol
        self._rename: dict[sp.Symbol, sp.Symbol] = {}  # sympy symbol -> plain symbol of its name
        self._restore: dict[sp.Symbol, sp.Symbol] = {}  # plain symbol -> the sympy symbol

    @property
    def native(self) -> bool:
        return self.ring is SymengineRing

    def _register(self, symbol: sp.Symbol) -> None:
        name = symbol.name
        if name in self._back:  # another sympy symbol has this name: give this one its own
            serial = 1
            while f"{name}__{serial}" in self._back:
                serial += 1
            name = f"{name}__{serial}"
        self._names[symbol] = name
        self._back[name] = symbol
        plain = sp.Symbol(name)
        if plain != symbol:
            self._rename[symbol] = plain
            self._restore[plain] = symbol

    def to_native(self, expr):
        """A sympy expression (or number) as a native one."""
        if not self.native:
            return sp.sympify(expr)
        expr = sp.sympify(expr)
        symbols = expr.free_symbols
        for symbol in symbols:
            if symbol not in self._names:
                self._register(symbol)
        rename = {s: self._rename[s] for s in symbols if s in self._rename}
        if rename:
            expr = expr.xreplace(rename)
        try:
            return se.sympify(expr)
        except (se.SympifyError, TypeError, ValueError, RuntimeError) as exc:
            raise NotNative(str(exc)) from None

    def to_sympy(self, value, expand: bool = True) -> sp.Expr:
        """A native expression as the sympy expression with the original symbols.

        Expanded by sympy unless ``expand`` is false (then as symengine holds it).
        """
        if not self.native:
            return value
        expr = sp.sympify(value)
        if expand and not expr.is_Atom:
            # sympy's expanded form (symengine keeps products in denominators): what the engine
            # always returned, and what sympy users expect to print
            expr = sp.expand(expr)
        if self._restore:
            restore = {s: self._restore[s] for s in expr.free_symbols if s in self._restore}
            if restore:
                expr = expr.xreplace(restore)
        return expr

    def symbols(self, value) -> set:
        """The free symbols of a native expression, as the original sympy symbols."""
        if not self.native:
            return value.free_symbols
        return {self._back[s.name] for s in value.free_symbols}

    def poly_symbols(self, poly) -> set:
        """:meth:`symbols` of every coefficient of a native trigonometric polynomial."""
        out = set()
        for c, s in poly.terms.values():
            out |= self.symbols(c) | self.symbols(s)
        return out

    def native_poly(self, poly: TrigPoly):
        """A sympy :class:`TrigPoly` as a native one."""
        if not self.native:
            return poly
        return NativeTrigPoly(
            {j: (self.to_native(c), self.to_native(s)) for j, (c, s) in poly.terms.items()}
        )

    def trig(self, poly) -> TrigPoly:
        """A native trigonometric polynomial as a sympy :class:`TrigPoly` (converted when read)."""
        if not self.native:
            return poly
        return TrigPoly.deferred(poly.terms, self.to_sympy)

    def mapping(self, mapping: dict) -> dict:
        """``{sympy symbol: sympy value}`` as ``{native symbol: native value}``."""
        return {self.to_native(k): self.to_native(v) for k, v in mapping.items()}


def ring_for(*exprs) -> type:
    """The ring a construction on these inputs runs in.

    symengine (when available) unless an input holds a floating-point number: float arithmetic
    stays sympy's (mpmath, at the Float's precision) so that such runs give exactly what they always
    gave.
    """
    if BACKEND != "symengine":
        return SympyRing
    for expr in exprs:
        if isinstance(expr, sp.Basic) and expr.has(sp.Float):
            return SympyRing
    return SymengineRing
