"""The size of a polynomial system, as a message about a solver's budget reports it."""

from __future__ import annotations

import sympy as sp
from attrs import field, frozen

__all__ = ["SystemSize"]


@frozen
class SystemSize:
    """How large a polynomial system is: equations, unknowns, total degrees, terms.

    Parameters
    ----------
    n_equations, n_unknowns : int
    degrees : tuple of int
        The total degree of each equation in the unknowns.
    n_terms : int
        The number of monomials, summed over the equations.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> print(SystemSize.of([x**2 + y**2 - 1, x - y], [x, y]))
    2 equations in 2 unknowns, total degrees (2, 1) (Bezout bound 2), 5 terms
    """

    n_equations: int
    n_unknowns: int
    degrees: tuple = field(converter=tuple)
    n_terms: int

    @classmethod
    def of(cls, eqs, unknowns) -> SystemSize:
        """The size of ``eqs = 0`` in ``unknowns`` (polynomials)."""
        polys = [sp.Poly(sp.expand(e), *unknowns) for e in eqs]
        return cls(
            n_equations=len(polys),
            n_unknowns=len(unknowns),
            degrees=tuple(p.total_degree() for p in polys),
            n_terms=sum(len(p.terms()) for p in polys),
        )

    @property
    def bezout(self) -> int:
        """The product of the degrees: a bound on the number of isolated complex roots."""
        bound = 1
        for degree in sorted(self.degrees, reverse=True)[: self.n_unknowns]:
            bound *= max(degree, 1)
        return bound

    def __str__(self) -> str:
        return (
            f"{self.n_equations} equations in {self.n_unknowns} unknowns, total degrees "
            f"{self.degrees} (Bezout bound {self.bezout}), {self.n_terms} terms"
        )
