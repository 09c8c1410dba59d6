"""A family of periodic solutions and the list of a system's families: the values
:func:`~perturb.method.families.find_families` returns.

Apart from the search (:mod:`perturb.method.families`), so that a module naming these types (a
problem's families, a report) does not load the construction with them.
"""

from __future__ import annotations

from collections.abc import Iterator

import attrs
from attrs import field, frozen

from perturb.errors import UnknownNameError
from perturb.solution import PeriodicSolution, Status

__all__ = ["CONTINUUM", "ISOLATED", "Family", "FamilyList"]

#: The two kinds of family, as reported to users.
ISOLATED, CONTINUUM = "isolated", "continuum"


@frozen
class Family:
    """One family of periodic solutions and its solution carried to the requested order.

    Parameters
    ----------
    name : str
        Stable user-facing name (see :mod:`perturb.method.family_names`).
    kind : {"isolated", "continuum"}
        ``isolated``: the amplitude equations fix every generating amplitude; ``continuum``: some
        stay free (named in ``free``), or the options fix them to a free parameter of the system.
    amplitudes : dict[str, sympy.Expr]
        The generating amplitudes that select the family: ``a_x`` (cosine amplitude of ``x``, i.e.
        x(0) at order 0), ``b_y`` (sine amplitude of ``y``); values may depend on the free ones.
    free : tuple of str
        The free amplitudes of a continuum, by their user-facing names (empty when isolated).
    solution : PeriodicSolution
        The family carried to the requested order (its ``status`` and ``message``). Free
        amplitudes are parameters of ``solution.system`` under their user-facing names.
    phase_coordinate : str
        The coordinate whose velocity vanishes at t = 0 on this family.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> from perturb import find_families
    >>> family = find_families(vdp, order=2).families[0]
    >>> family.name, family.kind, family.amplitudes
    ('limit-cycle', 'isolated', {'a_x': 2})
    """

    name: str
    kind: str = field(validator=attrs.validators.in_((ISOLATED, CONTINUUM)))
    amplitudes: dict = field(converter=dict)
    free: tuple = field(converter=tuple)
    solution: PeriodicSolution = field(eq=False, repr=False)
    phase_coordinate: str = ""

    @property
    def status(self) -> Status:
        return self.solution.status

    @property
    def message(self) -> str:
        return self.solution.message or self.solution.status.value

    @property
    def frequency(self) -> tuple:
        """Ω₀, Ω₁, … as far as they are determined."""
        return self.solution.frequency


@frozen
class FamilyList:
    """Every family of periodic solutions of a system, in canonical order (see the module notes).

    Parameters
    ----------
    system : str
        The system's name.
    order : int
        The order each family was carried to.
    family_order : int or None
        The first order whose conditions select the families (None: the options fixed every
        generating amplitude, so there is one family, the given one).
    families : tuple of Family
    why : str
        Empty, or why there is no family when the search could not list them (a driven system's
        roots not enumerated within the budget: never taken for "none").

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, PoincareMethod, QuasilinearSystem
    >>> x, xdot = sp.symbols("x xdot")
    >>> vdp = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot], name="van der Pol")
    >>> from perturb import find_families
    >>> families = find_families(vdp, order=2)
    >>> [family.name for family in families]
    ['limit-cycle']
    """

    system: str
    order: int
    family_order: int | None
    families: tuple = field(converter=tuple)
    why: str = ""

    def __iter__(self) -> Iterator[Family]:
        return iter(self.families)

    def __len__(self) -> int:
        return len(self.families)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(f.name for f in self.families)

    def get(self, name: str) -> Family:
        """The family called ``name``; :class:`UnknownNameError` listing the known names."""
        for family in self.families:
            if family.name == name:
                return family
        raise UnknownNameError(
            f"`family` = {name!r} is unknown for {self.system}: choose from {list(self.names)}"
        )
