"""Symbolic right-hand sides: one sympy description, numeric callables and heyoka expressions from it.

A :class:`SymbolicRHS` is an autonomous vector field :math:`\\dot y = f(y)` written as sympy expressions
in an ordered tuple of state symbols.  It is *callable* like any numeric rhs (``rhs(y) -> dy/dt``), so
every integrator accepts it; the Taylor integrator (heyoka) needs it, because it differentiates the
expressions itself; the sympy → heyoka translation is :func:`perturb.oracle.translate.to_heyoka`.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from functools import cached_property
from typing import Any

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import DERIVED_CACHE_SIZE
from perturb._lambdify import numpy_lambdify
from perturb.cache import cached
from perturb.errors import bad_value

__all__ = ["SymbolicRHS"]


def _as_symbols(values) -> tuple[sp.Symbol, ...]:
    return tuple(sp.sympify(v) if not isinstance(v, str) else sp.Symbol(v) for v in values)


def _as_exprs(values) -> tuple[sp.Expr, ...]:
    return tuple(sp.sympify(v) for v in values)


@frozen(cache_hash=True)  # hashed on every heyoka call (the compiled-integrator cache key)
class SymbolicRHS:
    """An autonomous vector field :math:`\\dot y = f(y)` given by sympy expressions.

    Parameters
    ----------
    state : sequence of sympy.Symbol
        The state symbols, in the order of the state vector.
    expressions : sequence of sympy.Expr
        :math:`f_i(y)`, one per state symbol.  Only the state symbols may occur: substitute parameter
        values first (``expr.subs(values)``).

    Raises
    ------
    perturb.errors.InvalidParameterError
        If the lengths differ, a state entry is not a symbol, symbols repeat, or an expression depends
        on a symbol that is not a state symbol.

    Examples
    --------
    >>> import sympy as sp
    >>> x, v = sp.symbols("x v")
    >>> duffing = SymbolicRHS((x, v), (v, -x - x**3))
    >>> duffing([1.0, 0.0])
    array([ 0., -2.])
    """

    state: tuple[sp.Symbol, ...] = field(converter=_as_symbols)
    expressions: tuple[sp.Expr, ...] = field(converter=_as_exprs)

    def __attrs_post_init__(self):
        if len(self.state) != len(self.expressions):
            raise bad_value(
                "expressions",
                f"{len(self.expressions)} expressions",
                f"give one expression per state symbol ({len(self.state)} state symbols)",
            )
        if len(self.state) == 0:
            raise bad_value("state", self.state, "give at least one state symbol")
        for s in self.state:
            if not isinstance(s, sp.Symbol):
                raise bad_value("state", s, "state entries must be sympy Symbols")
        if len(set(self.state)) != len(self.state):
            raise bad_value("state", self.state, "state symbols must be distinct")
        stray = set().union(*(e.free_symbols for e in self.expressions)) - set(self.state)
        if stray:
            names = ", ".join(sorted(map(str, stray)))
            raise bad_value(
                "expressions",
                names,
                "the rhs may depend on the state symbols only; substitute parameter values "
                "first, e.g. [e.subs(values) for e in expressions]",
            )

    @property
    def n(self) -> int:
        """Dimension of the state."""
        return len(self.state)

    @cached_property
    def _numeric(self) -> Callable[..., Any]:
        return _derived(self, "numeric")

    def cache_parts(self) -> tuple:
        """The disk-cache key of what is derived from this field: its exact state and expressions.

        Returns
        -------
        tuple
            The ``srepr`` of the state symbols and of the expressions (build it only when the
            cache is in use: :func:`perturb.cache.cached` takes this method itself).  Built once
            per field; the variational field read back from the cache carries it.
        """
        return self._parts

    @cached_property
    def _parts(self) -> tuple:
        return (tuple(map(sp.srepr, self.state)), tuple(map(sp.srepr, self.expressions)))

    @cached_property
    def jacobian_expressions(self) -> sp.Matrix:
        """The symbolic Jacobian :math:`\\partial f_i / \\partial y_j` (n × n sympy Matrix).

        Kept in memory and on disk (:func:`perturb.cache.cached`, kind ``jacobian``).
        """
        return _derived(self, "jacobian_expressions")

    def _derive_jacobian(self) -> sp.Matrix:
        return sp.Matrix(self.expressions).jacobian(sp.Matrix(self.state))

    @cached_property
    def _numeric_jacobian(self) -> Callable[..., Any]:
        return _derived(self, "numeric_jacobian")

    def __call__(self, y: Sequence[float]) -> np.ndarray:
        """Evaluate :math:`f(y)` for one state vector ``y`` of shape ``(n,)``."""
        return np.array(self._numeric(*y), dtype=float).reshape(self.n)

    def jacobian(self, y: Sequence[float]) -> np.ndarray:
        """Evaluate the Jacobian at one state vector; shape ``(n, n)``."""
        return np.array(self._numeric_jacobian(*y), dtype=float).reshape(self.n, self.n)

    @cached_property
    def variational(self) -> SymbolicRHS:
        """The state augmented with the first-order variational equations.

        The augmented state is ``(y, Phi.ravel())`` with ``Phi`` the n × n state-transition matrix
        stored row-major, and :math:`\\dot\\Phi = J(y)\\,\\Phi`.  Integrating from ``Phi = I`` over a
        period gives the monodromy matrix.  Kept in memory and on disk (kind ``variational``;
        the Jacobian's symbols ``Phi`` are :class:`sympy.Dummy`, read back as the same dummies).
        """
        return _derived(self, "variational")

    def _derive_variational(self) -> tuple[tuple, tuple, tuple]:
        """The variational field's state, expressions and :meth:`cache_parts` (kept with them:
        its own derivations, the compiled integrator among them, are keyed on them)."""
        n = self.n
        phi = sp.Matrix(n, n, lambda i, j: sp.Dummy(f"Phi{i}_{j}"))
        phi_dot = self.jacobian_expressions * phi
        derived = SymbolicRHS(self.state + tuple(phi), self.expressions + tuple(phi_dot))
        return derived.state, derived.expressions, derived.cache_parts()


@functools.lru_cache(maxsize=DERIVED_CACHE_SIZE)
def _derived_objects(rhs: SymbolicRHS) -> dict:
    return {}


def _derived(rhs: SymbolicRHS, what: str):
    """The object ``what`` derived from ``rhs``: the numeric functions (``numeric``,
    ``numeric_jacobian``) are shared by every equal field (the same lambdified code, so the
    same numbers); the symbolic Jacobian and variational equations are this object's own, read
    from the disk cache for a new object as before."""
    if what not in ("numeric", "numeric_jacobian"):
        return _derive(rhs, what)
    store = _derived_objects(rhs)
    if what not in store:
        store[what] = _derive(rhs, what)
    return store[what]


def _derive(rhs: SymbolicRHS, what: str):
    if what == "numeric":
        return numpy_lambdify(rhs.state, list(rhs.expressions), cse=True)
    if what == "jacobian_expressions":
        return cached("jacobian", rhs.cache_parts, rhs._derive_jacobian)
    if what == "numeric_jacobian":
        return numpy_lambdify(rhs.state, rhs.jacobian_expressions, cse=True)
    state, expressions, parts = cached("variational", rhs.cache_parts, rhs._derive_variational)
    derived = SymbolicRHS(state, expressions)
    object.__setattr__(derived, "_parts", parts)  # its key, computed where it was derived
    return derived
