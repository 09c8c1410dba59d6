"""A bare :class:`perturb.QuasilinearSystem` with numbers as a model: :class:`SystemModel`, and
:func:`as_model`, the door through which :func:`perturb.validation.validate`, the sweep and the
work-precision measurement take a problem or a bare system."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from attrs import evolve, field, frozen

from perturb.case import Case
from perturb.errors import bad_value
from perturb.solution import PeriodicSolution
from perturb.system import QuasilinearSystem, Regime
from perturb.validation._quasilinear import quasilinear_state_names, state_along
from perturb.validation.frames import work_of
from perturb.validation.model import Model, identity_case
from perturb.validation.values import check_system_values

__all__ = ["SystemModel", "as_model"]


_SOLUTIONS: dict[tuple, PeriodicSolution] = {}


@frozen
class SystemModel(Model):
    """A bare :class:`perturb.QuasilinearSystem` with numbers, as a :class:`Model`.

    Parameters
    ----------
    quasilinear : QuasilinearSystem
    values : mapping
        A number for every symbol of ``quasilinear.parameters`` and for its own parameter
        (``quasilinear.parameter``, e.g. ``epsilon``), by name.
    options : mapping, optional
        Options of :class:`perturb.PoincareMethod` (``amplitudes``, ``branch``, ...).
    name : str, optional

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> x, v = sp.symbols("x v")
    >>> duffing = QuasilinearSystem([x], [v], [1], [-EPS * x**3], parameter=EPS)
    >>> SystemModel(duffing, {"epsilon": 0.1}, {"amplitudes": {"x": 1}}).epsilon()
    0.1
    """

    quasilinear: QuasilinearSystem
    values: dict = field(converter=dict)
    options: dict = field(factory=dict, converter=dict)
    name: str = ""

    def __attrs_post_init__(self):
        object.__setattr__(self, "values", check_system_values(self.quasilinear, self.values))

    def label(self) -> str:
        return self.name or self.quasilinear.name

    def system(self) -> QuasilinearSystem:
        return self.quasilinear

    def symbol_values(self) -> dict[str, float]:
        return {p.name: self.values[p.name] for p in self.quasilinear.parameters}

    def parameter_value(self) -> float:
        return self.values[self.quasilinear.parameter.name]

    def epsilon(self) -> float:
        value = self.parameter_value()
        return 1.0 / value if self.quasilinear.regime is Regime.LARGE else value

    def method_options(self) -> dict:
        return dict(self.options)

    def solve(self, order: int = 1) -> PeriodicSolution:
        work = work_of(self.quasilinear)  # one solution for all points, or a branch per point
        key = (self.quasilinear, order, repr(sorted(self.options.items(), key=str)))
        key = (*key, *work.point_key(self))
        if key not in _SOLUTIONS:
            _SOLUTIONS[key] = work.solve(self, order, self.options, self.options.get("family"))
        return _SOLUTIONS[key]

    def state_names(self) -> tuple[str, ...]:
        return quasilinear_state_names(self.quasilinear)

    def state(self, solution: PeriodicSolution, t) -> dict[str, np.ndarray]:
        return state_along(solution, t, self.parameter_value(), self.symbol_values())

    def period(self, solution: PeriodicSolution) -> float:
        return float(solution.period_at(self.parameter_value(), self.symbol_values()))

    def with_parameters(self, **values: float) -> SystemModel:
        return evolve(self, values={**self.values, **values})

    def case(self) -> Case:
        """Its values as a :class:`~perturb.case.Case` (each symbol the value of its name)."""
        direct = work_of(self.quasilinear).state_is_solution()  # a driven state adds the phase
        return identity_case(
            self, self.values, reads=lambda values: frozenset(), evaluates_directly=direct
        )

    def with_epsilon(self, eps: float) -> SystemModel:
        value = 1.0 / eps if self.quasilinear.regime is Regime.LARGE else eps
        return evolve(self, values={**self.values, self.quasilinear.parameter.name: value})


def as_model(problem, values: Mapping | None = None, options: Mapping | None = None) -> Model:
    """``problem`` as a :class:`Model` (a bare system is wrapped in :class:`SystemModel`).

    Parameters
    ----------
    problem : Model or QuasilinearSystem
        A problem (returned as it is) or a bare system.
    values : mapping, optional
        For a bare system: the value of each parameter and of ``"epsilon"`` (or ``"mu"``).
    options : mapping, optional
        For a bare system: options of :class:`perturb.PoincareMethod` (``amplitudes``, ...).

    Returns
    -------
    Model

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``problem`` is neither a model nor a system, or a value is missing.

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> from perturb.validation import as_model
    >>> x, xdot = sp.symbols("x xdot")
    >>> model = as_model(QuasilinearSystem([x], [xdot], [1], [-EPS * x**3]), values={"epsilon": 0.1},
    ...                  options={"amplitudes": {"x": 1}})
    >>> type(model).__name__, round(model.period(model.solve(1)), 6)  # 2 pi / (1 + 3 eps / 8)
    ('SystemModel', 6.056082)
    """
    if isinstance(problem, QuasilinearSystem):
        if values is None:
            raise bad_value(
                "values",
                None,
                "a bare QuasilinearSystem needs numbers: pass values={name: number} for its "
                f"parameters {[p.name for p in problem.parameters] + [problem.parameter.name]}",
            )
        if not isinstance(values, Mapping):
            raise bad_value("values", values, "pass a mapping {name: number}")
        return SystemModel(problem, values, options or {})
    if not isinstance(problem, Model):
        raise bad_value(
            "problem",
            problem,
            "pass a problems.Problem, a perturb.validation.Model or a QuasilinearSystem with "
            "values=",
        )
    if values is not None or options is not None:
        raise bad_value(
            "values", values, "values= and options= go with a bare QuasilinearSystem only"
        )
    return problem
