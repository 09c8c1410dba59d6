"""What a real-root search returns: the roots, each certified, and a status that says what happened."""

from __future__ import annotations

import enum

from attrs import field, frozen

from perturb._defaults import NUMBER_DIGITS

__all__ = ["NUMBER_DIGITS", "RootSet", "RootStatus"]


class RootStatus(enum.Enum):
    """How the root search ended; the values are the messages.

    Examples
    --------
    >>> RootStatus.NO_REAL_ROOT.success, RootStatus.BUDGET_EXCEEDED.success
    (True, False)
    """

    SOLVED = "every real root was isolated (the count is proved by exact interval arithmetic)"
    NO_REAL_ROOT = "the system has no real root (proved: no isolating interval exists)"
    POSITIVE_DIMENSIONAL = (
        "the system has a continuum of roots: its Groebner basis is not zero-dimensional"
    )
    UNDECIDED = "the roots could not be enumerated (a variable is left free by the basis)"
    BUDGET_EXCEEDED = "the solver ran out of its time budget before it could decide"

    @property
    def success(self) -> bool:
        return self in (RootStatus.SOLVED, RootStatus.NO_REAL_ROOT)


@frozen
class RootSet:
    """The real roots of a polynomial system.

    Attributes
    ----------
    status : RootStatus
    roots : tuple of dict
        ``{unknown: float}`` per real root.
    unknowns : tuple of sympy.Symbol
    message : str
    exact : tuple of dict
        ``{unknown: exact algebraic number}`` per root, in the order of ``roots`` (rationals,
        radicals, or polynomials in a ``CRootOf``): the values known exactly (a root msolve
        isolated in a box has ``{}`` unless it is rational).
    approximations : tuple of dict
        ``{unknown: rational}`` per root inside its certificate (msolve's box: the midpoint,
        within 2**-128 of the root), for the values not in ``exact``.
    certificates : tuple of str
        Per root, the isolating interval that proves it (one root of a named univariate
        polynomial, or msolve's box), in the order of ``roots``.
    backend : str
        The route that answered: ``"sympy"`` or ``"msolve"``.
    dimension : int or None
        The dimension of the complex solution set (0: finitely many roots; -1: none) when known.
    free : tuple of sympy.Symbol
        For a positive-dimensional set: unknowns that stay free on its largest part.
    continua : tuple of (int or None, tuple, str)
        Per positive-dimensional piece: its dimension, the unknowns free on it and the cuts that
        lead to it (``roots`` then holds the isolated roots of the other pieces).
    size : object
        The :class:`~perturb.algebra.size.SystemSize` of the system that was solved.
    """

    status: RootStatus
    roots: tuple = field(converter=tuple)
    unknowns: tuple = field(converter=tuple)
    message: str = ""
    exact: tuple = field(default=(), converter=tuple)
    approximations: tuple = field(default=(), converter=tuple)
    certificates: tuple = field(default=(), converter=tuple)
    backend: str = "sympy"
    dimension: int | None = None
    free: tuple = field(default=(), converter=tuple)
    size: object = None
    continua: tuple = field(default=(), converter=tuple)

    def describe_continua(self) -> str:
        """The continua in words, e.g. ``"dimension 1, free [b] (on a**2 + b**2 - 1 = 0)"``."""
        return "; ".join(
            f"dimension {'?' if d is None else d}, free {list(map(str, free))}"
            + (f" (on {path})" if path else "")
            for d, free, path in self.continua
        )

    def numbers(self, digits: int = NUMBER_DIGITS) -> list[dict]:
        """Per root, ``{unknown: sympy number}``: exact where it is a rational or a radical, else
        a Float of ``digits`` digits (a ``CRootOf`` evaluated, or msolve's box midpoint), or of
        more where the root was refined to its size (:func:`~perturb.algebra.msolve._refined`).

        Examples
        --------
        >>> import sympy as sp
        >>> x = sp.Symbol("x")
        >>> found = RootSet(RootStatus.SOLVED, [{x: 2.0}], [x], exact=[{x: sp.Integer(2)}])
        >>> found.numbers()
        [{x: 2}]
        """
        import sympy as sp

        out = []
        for index, floats in enumerate(self.roots):
            exact = self.exact[index] if self.exact else {}
            approx = self.approximations[index] if self.approximations else {}
            root = {}
            for u in self.unknowns:
                value = exact.get(u)
                if value is not None and not value.has(sp.CRootOf):
                    root[u] = value
                elif value is not None:
                    root[u] = sp.Float(sp.N(value, digits), digits)
                else:  # a refined Float keeps its own (larger) precision
                    value = approx.get(u, floats[u])
                    root[u] = value if isinstance(value, sp.Float) else sp.Float(value, digits)
            out.append(root)
        return out
