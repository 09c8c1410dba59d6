"""A case: a system, its parameter map, one point of user values and the family followed.

:class:`Case` is what every client of a problem's numbers holds — the response, a sweep, the
order scan of validation — instead of re-creating problems to learn what a parameter does:

* :attr:`Case.symbol_values`, :attr:`Case.epsilon`, :attr:`Case.parameter_value` — the point;
* :meth:`Case.at` — another point (checked by the problem's own rules, no class re-created);
* :meth:`Case.with_epsilon` — the same scaled system at another ε, solved from the map;
* :meth:`Case.columns` — many points' numbers as numpy columns; :meth:`Case.points` — many
  points checked, with the one model whose solution serves them all (a sweep's fast route);
* :meth:`Case.to_user`, :meth:`Case.user_roots` — a value found in a system symbol (a fold's σ)
  back in a user parameter; :meth:`Case.span` — the range a symbol covers along a parameter.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping

import attrs
import numpy as np
from attrs import field, frozen

from perturb._defaults import DERIVED_CACHE_SIZE, MOVED_VALUES_CACHE_ENTRIES
from perturb.cache import UNPICKLABLE, cached, digest
from perturb.case.parameters import EPSILON_KEY, ParameterMap
from perturb.case.points import CasePoints, points_of
from perturb.errors import InvalidParameterError, bad_value
from perturb.system import QuasilinearSystem, Regime

__all__ = ["Case", "CaseColumns"]


@frozen
class CaseColumns:
    """Many points of a case as columns (one entry per point).

    Attributes
    ----------
    symbols : dict of str to numpy.ndarray
        Each system symbol's value.
    epsilon : numpy.ndarray
    parameter_value : numpy.ndarray
        ε, or μ = 1/ε for a large-parameter system (the solution's own argument).

    Examples
    --------
    >>> import numpy as np
    >>> from problems import get_problem
    >>> columns = get_problem("duffing").create(eps=0.1).case().columns(
    ...     {"amplitude": np.array([0.5, 1.0, 2.0])})
    >>> columns.symbols["amplitude"].tolist(), columns.epsilon.tolist()
    ([0.5, 1.0, 2.0], [0.1, 0.1, 0.1])
    """

    symbols: dict
    epsilon: np.ndarray
    parameter_value: np.ndarray


def _no_check(values: dict) -> dict:
    return dict(values)


@functools.lru_cache(maxsize=DERIVED_CACHE_SIZE)
def _identity_map(system: QuasilinearSystem, names: tuple[str, ...]) -> ParameterMap:
    """Each system symbol the value of its name; ε the system's own parameter (1/μ if large)."""
    own = system.parameter.name
    epsilon = own if system.regime is not Regime.LARGE else f"1/{own}"
    return ParameterMap.declare(system.parameters, names, {}, epsilon=epsilon)


@frozen
class Case:
    """A system at one point of its user parameters (see the module docstring).

    Parameters
    ----------
    system : QuasilinearSystem
    map : ParameterMap
    values : mapping of str to float
        Every user parameter's value.
    family : str, optional
        The family of periodic solutions followed (None: the default one).
    check : callable, optional
        ``check(values) -> values``: the problem's own validation of a point (raises a
        ``ValueError`` subclass naming the parameter); default: none.
    model_of : callable, optional
        ``model_of(case) -> model``: the model (a :class:`~perturb.validation.Model`, e.g. a
        problem) at a case's values — the one adapter the front door gives, so that a client
        holding a case reaches the problem's own physics (its state map, its checks) at any
        point without re-creating it by hand; default: none (:attr:`model` is None).
    check_columns : callable, optional
        ``check_columns(values, grid, size) -> (errors, notes) | None``: :attr:`check` of many
        points at once (``grid``: some user parameters as arrays of length ``size``, the rest
        ``values``), each point's message and warnings exactly as checked alone (None: it cannot
        say); default: :attr:`check` at each point (:meth:`points`).
    solution_reads : callable, optional
        ``solution_reads(values) -> frozenset of str | None``: the user parameters the solution
        depends on besides the system's symbols (its method options read them), the others at
        ``values``; None (as the default, or as its answer): unknown, each point may have its
        own solution and :meth:`points` offers none.
    evaluates_directly : bool, optional
        Whether the model's state and period at every point are the solution's own
        ``evaluate`` and ``period_at`` at the point's numbers (no map of its own, no phase
        appended), so that the points sharing one solution can be evaluated in one vectorised
        call (a sweep); default: False.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, Excitation, QuasilinearSystem
    >>> from perturb.case import Case, ParameterMap
    >>> x, xdot, th, sigma, F = sp.symbols("x xdot theta sigma F")
    >>> system = QuasilinearSystem([x], [xdot], [1], [EPS * (-x**3 + F * sp.cos(th))],
    ...     parameters=[F, sigma], excitation=Excitation(phase=th, ratio=1, detuning=sigma))
    >>> mapping = ParameterMap.declare(system.parameters, ["eps", "F", "Omega"],
    ...     {"sigma": "(Omega - 1)/eps"})
    >>> case = Case(system, mapping, {"eps": 0.1, "F": 1.0, "Omega": 1.2})
    >>> round(case.symbol_values["sigma"], 12), case.epsilon
    (2.0, 0.1)
    >>> case.with_epsilon(0.05).values["Omega"]
    1.1
    >>> case.to_user("Omega", "sigma", 1.0)
    1.1
    """

    system: QuasilinearSystem
    map: ParameterMap
    values: dict = field(converter=dict)
    family: str | None = None
    check: Callable[[dict], dict] = field(default=_no_check, eq=False, repr=False)
    model_of: Callable | None = field(default=None, eq=False, repr=False)
    check_columns: Callable | None = field(default=None, eq=False, repr=False)
    solution_reads: Callable | None = field(default=None, eq=False, repr=False)
    evaluates_directly: bool = field(default=False, kw_only=True, eq=False, repr=False)
    _point: tuple = field(init=False, eq=False, repr=False)
    _model: list = field(init=False, eq=False, repr=False, factory=list)

    def __attrs_post_init__(self):
        missing = [n for n in self.map.user if n not in self.values]
        if missing:
            raise bad_value(
                "values", sorted(self.values), f"give every user parameter: {missing} missing",
                InvalidParameterError,
            )  # fmt: skip
        object.__setattr__(self, "_point", self.map.evaluate(self.values))

    @classmethod
    def of(
        cls,
        system: QuasilinearSystem,
        values: Mapping[str, float],
        *,
        family: str | None = None,
        check: Callable[[dict], dict] = _no_check,
        model_of: Callable | None = None,
        check_columns: Callable | None = None,
        solution_reads: Callable | None = None,
        evaluates_directly: bool = False,
    ) -> Case:
        """The case of a bare ``system`` at ``values``: each of its symbols the value of its
        name, ε its own parameter (``epsilon``, or ``1/mu`` in the large-parameter regime) —
        the door for a system given with numbers (a problem declares its own map instead).

        Examples
        --------
        >>> import sympy as sp
        >>> from perturb import EPS, QuasilinearSystem
        >>> from perturb.case import Case
        >>> x, v, k = sp.symbols("x v k")
        >>> system = QuasilinearSystem([x], [v], [1], [-EPS * k * x**3], parameters=[k])
        >>> case = Case.of(system, {"k": 2.0, "epsilon": 0.1})
        >>> case.symbol_values, case.epsilon, case.at(epsilon=0.2).epsilon
        ({'k': 2.0}, 0.1, 0.2)
        """
        mapping = _identity_map(system, tuple(values))
        return cls(
            system, mapping, values, family, check=check, model_of=model_of,
            check_columns=check_columns, solution_reads=solution_reads,
            evaluates_directly=evaluates_directly,
        )  # fmt: skip

    # ------------------------------------------------------------------ the point
    @property
    def symbol_values(self) -> dict[str, float]:
        """The system symbols' values at this point, by name."""
        return dict(self._point[0])

    @property
    def epsilon(self) -> float:
        """ε at this point (raises if the map does not give it)."""
        eps = self._point[1]
        if eps is None:
            raise bad_value(
                "parameter_map", "(no epsilon)",
                f"declare {EPSILON_KEY!r} in the map or give a parameter named 'eps'",
                InvalidParameterError,
            )  # fmt: skip
        return eps

    @property
    def parameter_value(self) -> float:
        """The solution's own argument: ε, or μ = 1/ε for a large-parameter system."""
        eps = self.epsilon
        return 1.0 / eps if self.system.regime is Regime.LARGE else eps

    @property
    def model(self):
        """The model at this case's values (made once by :attr:`model_of`; None without one,
        or where the model cannot be re-created at these values)."""
        if not self._model:
            self._model.append(None if self.model_of is None else self.model_of(self))
        return self._model[0]

    # ------------------------------------------------------------------ other points
    def at(self, **values) -> Case:
        """This case at other user values (the rest kept), checked by :attr:`check`."""
        unknown = sorted(set(values) - set(self.map.user))
        checked = self.check({**self.values, **values})  # a problem names its own parameters
        if unknown:
            raise bad_value(
                unknown[0], values[unknown[0]],
                f"it is not a parameter: choose from {list(self.map.user)}", InvalidParameterError,
            )  # fmt: skip
        return attrs.evolve(self, values=checked)

    def with_epsilon(self, eps: float) -> Case | None:
        """The same scaled system (every symbol kept) at ε = ``eps``, or None if no move of the
        user parameters gives it (or the move leaves their admissible range).

        The moved values are kept in the disk cache (kind ``moved-values``), keyed on the map,
        the values and ``eps``: finding them evaluates sympy expressions, which a warm run then
        does not."""
        mapping, values = self.map, self.values
        try:
            moved = cached(
                "moved-values",
                lambda: (
                    digest((mapping.user, mapping.symbols, mapping.epsilon)),
                    tuple((name, type(v).__name__, repr(v)) for name, v in values.items()),
                    type(eps).__name__,
                    repr(eps),
                ),
                lambda: mapping.with_epsilon(values, eps),
                keep=MOVED_VALUES_CACHE_ENTRIES,
            )
        except UNPICKLABLE:  # a map holding a function's own code: moved afresh, not kept
            moved = mapping.with_epsilon(values, eps)
        if moved is None:
            return None
        try:
            return attrs.evolve(self, values=self.check(moved))
        except ValueError:
            return None

    def with_family(self, family: str | None) -> Case:
        """This case following the family ``family`` (None: the default one)."""
        return attrs.evolve(self, family=family)

    def columns(self, grid: Mapping[str, np.ndarray]) -> CaseColumns:
        """Points as columns: ``grid`` gives some user parameters as arrays of one length (the
        rest are this case's values). No check is applied: the caller validates the points."""
        values = {n: grid.get(n, self.values[n]) for n in self.map.user}
        symbols, eps = self.map.columns(values)
        if eps is None:
            raise bad_value(
                "parameter_map", "(no epsilon)", f"declare {EPSILON_KEY!r} in the map",
                InvalidParameterError,
            )  # fmt: skip
        with np.errstate(divide="ignore"):
            value = 1.0 / eps if self.system.regime is Regime.LARGE else eps
        return CaseColumns(symbols, eps, value)

    def points(self, grid: Mapping[str, np.ndarray]) -> CasePoints | None:
        """Many points at once, checked (:mod:`perturb.case.points`): ``grid`` gives some user
        parameters as arrays of one length; each point's ε, symbols, message and warnings, and
        the model whose solution serves every valid point — exactly what the points give one by
        one. None where the case cannot promise that (:attr:`solution_reads` unknown or moved by
        the grid, a driven system, no ε in the map): the caller then makes each point's model."""
        return points_of(self, grid)

    # ------------------------------------------------------------------ back to the user
    def moves(self, parameter: str) -> tuple[str, ...]:
        """The system symbols (and :data:`~perturb.case.parameters.EPSILON_KEY`) that the user
        parameter ``parameter`` moves."""
        return self.map.moved_by(parameter)

    def rate(self, parameter: str) -> tuple[dict[str, float], float]:
        """How the user ``parameter`` moves the point: ``(d symbol/d parameter by name,
        d ε/d parameter)``, exact derivatives at this case's values."""
        symbols, eps = self.map.rate(parameter, self.values)
        return symbols, (0.0 if eps is None else eps)

    def is_affine_in(self, parameter: str) -> bool:
        """Whether the symbols and ε move affinely with ``parameter`` (Ω for σ = (Ω − 1)/ε)."""
        return self.map.is_affine_in(parameter)

    def to_user(self, parameter: str, name: str, value: float) -> float:
        """The value of the user ``parameter`` at which the system symbol ``name`` equals
        ``value``, the other parameters at this case's values (NaN if none)."""
        return self.map.solve_user(parameter, name, value, self.values)

    def user_roots(self, parameter: str, name: str, value: float) -> tuple[float, ...]:
        """Every value of the user ``parameter`` at which the system symbol ``name`` equals
        ``value``, the others at this case's values (increasing; a map that is not monotone in
        ``parameter`` has several)."""
        return self.map.user_roots(parameter, name, value, self.values)

    def span(self, parameter: str, name: str, low: float, high: float) -> tuple[float, float]:
        """``(min, max)`` of the system symbol ``name`` while the user ``parameter`` runs over
        [``low``, ``high``], the others at this case's values (exact, whatever the map)."""
        return self.map.span(parameter, name, low, high, self.values)
