"""What validation needs from a problem: the :class:`Model` protocol and its value types.

:func:`perturb.validation.validate` talks to problems only through :class:`Model` (no attribute
probing): ``problems.Problem`` implements it, and :class:`~perturb.validation.SystemModel`
(:mod:`perturb.validation.system_model`) makes a bare :class:`perturb.QuasilinearSystem` with
parameter values a model.
"""

from __future__ import annotations

import math
import weakref
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from typing import Protocol, runtime_checkable

import numpy as np
from attrs import field, frozen

from perturb.case import Case
from perturb.errors import bad_value
from perturb.oracle import Integrator, OrbitRoute, OrbitStatus, PeriodicOrbit, SymbolicRHS
from perturb.solution import PeriodicSolution
from perturb.system import QuasilinearSystem, Regime
from perturb.validation._quasilinear import (
    conservative_energy,
    lambdify_integrals,
    substitutions,
)
from perturb.validation.values import check_system_values

__all__ = [
    "Equations",
    "Integrals",
    "Model",
    "OrbitEstimate",
    "ShootingSetup",
    "parameter_value_of",
    "system_integrals",
]


@frozen
class Equations:
    """The original (unreduced) equations of a model, as the oracle integrates them.

    Attributes
    ----------
    rhs : callable
        ``rhs(y) -> dy/dt`` on the state of :meth:`Model.state_names`; a
        :class:`perturb.oracle.SymbolicRHS` when the equations are symbolic (heyoka and exact
        Jacobians need that).
    quasilinear : bool
        Whether the state is the quasilinear system's own ``(x..., ẋ...)`` (then the derived
        shooting set-up uses the system's amplitudes and phase coordinate).

    Examples
    --------
    >>> from perturb.validation import original_equations
    >>> from problems import get_problem
    >>> equations = original_equations(get_problem("van-der-pol").create(eps=0.1))
    >>> equations.rhs([2.0, 0.0])
    array([ 0., -2.])
    """

    rhs: Callable
    quasilinear: bool = False

    @property
    def symbolic(self) -> bool:
        return isinstance(self.rhs, SymbolicRHS)

    @classmethod
    def from_time_rhs(cls, function: Callable, *, quasilinear: bool = False) -> Equations:
        """Wrap an autonomous ``f(t, y)`` (scipy's convention) as ``rhs(y)``."""

        def rhs(y, _f=function):
            return np.asarray(_f(0.0, y), dtype=float)

        return cls(rhs, quasilinear)


@frozen
class Integrals:
    """First integrals with names: ``function(y)`` of a state of shape ``(n,)`` or ``(n, m)``.

    Parameters
    ----------
    function : callable
        ``function(y)``: the integrals' values, one row per integral (a state of shape ``(n, m)``
        gives one column per state).
    names : tuple of str
        One name per integral, in the order of the rows.

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.validation import Integrals
    >>> energy = Integrals(lambda y: np.array([0.5 * (y[0] ** 2 + y[1] ** 2)]), ("energy",))
    >>> energy.names, energy.function(np.array([1.0, 1.0]))
    (('energy',), array([1.]))
    """

    function: Callable
    names: tuple = field(converter=tuple)


@frozen
class ShootingSetup:
    """How to shoot for the true orbit (:func:`perturb.oracle.find_periodic_orbit`).

    Attributes
    ----------
    section_index : int
        Component defining the Poincaré section.
    section_value : float
    fixed_indices : tuple of int
        Components pinned (one per family parameter: a first integral's value, an amplitude).
    direction : int
        Required sign of the section component's velocity at the crossing (0: either).
    n_trivial : int or None
        Floquet multipliers expected at 1 (None: 1 + the number of first integrals).
    integrator : Integrator or None
        The shooting's integrator (None: the oracle's default, Radau on stiff systems).

    Examples
    --------
    Shoot on the section ``xdot = 0`` (component 1), crossing it in either direction:

    >>> from perturb.validation import ShootingSetup
    >>> setup = ShootingSetup(section_index=1)
    >>> setup.section_index, setup.section_value, setup.fixed_indices
    (1, 0.0, ())
    """

    section_index: int = field(converter=int)
    section_value: float = field(default=0.0, converter=float)
    fixed_indices: tuple = field(default=(), converter=lambda v: tuple(int(i) for i in v))
    direction: int = field(default=0, converter=int)
    n_trivial: int | None = None
    integrator: Integrator | None = None

    @classmethod
    def from_mapping(cls, setup: Mapping) -> ShootingSetup:
        """From the dictionary form ``{"section_index", "fixed_indices", ...}`` of earlier versions."""
        known = {"section_index", "section_value", "fixed_indices", "direction", "n_trivial"}
        known |= {"integrator"}
        unknown = sorted(set(setup) - known)
        if unknown or "section_index" not in setup:
            raise bad_value(
                "shooting_setup",
                dict(setup),
                f"give `section_index` and optionally {sorted(known - {'section_index'})}",
            )
        return cls(**dict(setup))


class OrbitEstimate(PeriodicOrbit):
    """A true periodic orbit found by a model's own method (its ``true_orbit(solution)``: the
    capability :class:`~perturb.validation.capabilities.OwnTrueOrbit`): a
    :class:`~perturb.oracle.PeriodicOrbit` (``found_by`` :attr:`~perturb.oracle.OrbitRoute.MODEL`)
    built from what such a finder knows.

    Parameters
    ----------
    success : bool
        Whether it was found (status ``CONVERGED``, else ``FAILED`` with ``message``).
    period : float
        Physical period.
    initial_state : array_like of float
        State on the analytic solution's section, in the order of :meth:`Model.state_names`.
    message : str
        What ran, or why it failed (e.g. no extended precision available).
    floquet : sequence of complex
        The Floquet multipliers (:attr:`~perturb.oracle.PeriodicOrbit.multipliers`).
    n_trivial : int or None
        Multipliers expected at 1 (None: validation's own count).
    trivial_multiplier_error : float
    resolution : float
        Uncertainty of the orbit relative to its amplitudes.
    integrator : str

    Examples
    --------
    What a model's own orbit finder returns (here built by hand):

    >>> from perturb.validation import OrbitEstimate
    >>> estimate = OrbitEstimate(True, 6.2871, [2.0002, 0.0], message="converged")
    >>> estimate.success, estimate.period, estimate.found_by.name
    (True, 6.2871, 'MODEL')
    """

    __slots__ = ()

    def __init__(
        self,
        success: bool,
        period: float,
        initial_state,
        message: str = "",
        floquet=(),
        n_trivial: int | None = None,
        trivial_multiplier_error: float = math.nan,
        resolution: float = 0.0,
        integrator: str = "",
    ) -> None:
        state = np.array([float(x) for x in np.ravel(initial_state)])
        size = state.size
        super().__init__(
            period=period,
            initial_state=state,
            multipliers=np.array([complex(z) for z in floquet], dtype=complex),
            monodromy=np.full((size, size), math.nan),
            residual=math.nan,
            iterations=0,
            status=OrbitStatus.CONVERGED if success else OrbitStatus.FAILED,
            message=message,
            trivial_multiplier_error=trivial_multiplier_error,
            integrator=integrator,
            n_trivial_expected=n_trivial,
            found_by=OrbitRoute.MODEL,
            resolution=resolution,
        )

    @property
    def floquet(self) -> np.ndarray:
        """:attr:`multipliers`, by the name of the constructor."""
        return self.multipliers

    @property
    def n_trivial(self) -> int | None:
        """:attr:`n_trivial_expected`, by the name of the constructor."""
        return self.n_trivial_expected


class Model(ABC):
    """What :func:`perturb.validation.validate` needs from a problem (abstract base).

    Contract, for implementers (``problems.Problem`` fulfils it; :class:`SystemModel` adapts a
    bare system):

    1. implement :meth:`state_names`, :meth:`solve`, :meth:`state`, :meth:`period` and
       :meth:`epsilon` — the analytic solution and its physical state;
    2. implement :meth:`system` and :meth:`symbol_values` — the quasilinear system and the
       numbers for its symbols (the defaults below are derived from them); the value of the
       system's own parameter is ε, or μ = 1/ε in the large-parameter regime
       (:func:`parameter_value_of`), unless the model defines ``parameter_value()`` itself;
    3. optionally define ``original_equations(y0)`` or ``original_rhs()`` — the equations the
       model is checked against (default: the quasilinear system itself,
       :math:`\\ddot x + \\omega^2 x = \\varepsilon f` written first order) — and
       ``with_epsilon(eps)``, the same model with its own small parameter rescaled, for the
       order check (default: the model at its :meth:`case` moved to ``eps``; None where it cannot
       be re-created), each asked through :mod:`perturb.validation.truth`
       (:func:`~perturb.validation.original_equations`, :func:`~perturb.validation.original_rhs`,
       :func:`~perturb.validation.with_epsilon`);
    4. optionally override :meth:`with_parameters` (other parameter values: a sweep's points);
       the model's :meth:`case` holds its parameters in force, its other points and whether many
       of them can be evaluated at once;
    5. optionally override :meth:`method_options`;
    6. optionally define a method of :mod:`perturb.validation.capabilities`, each asked through
       one function there: ``integrals_of_motion(y0)`` (default: the system's declared
       first integrals, else its energy when the forces derive from a potential, else none),
       ``label()`` (default: the model's ``name``, else its class's: for reports), and the
       optional physics ``validity_estimates()``, ``true_orbit(solution)`` (a model-specific
       true-orbit finder for near-degenerate cases), ``shooting_setup()``,
       ``euler_angles(solution, t)`` (rigid bodies), ``report_extras()`` (what a report adds);
       a model without one has none.
       A sweep asks for ``symbolic_derivation()`` the same way
       (:class:`perturb.sweep.derive.SymbolicDerivation`).

    Examples
    --------
    A problem is a model, and so is a bare system with its parameter values:

    >>> import sympy as sp
    >>> from perturb import EPS, QuasilinearSystem
    >>> from perturb.validation import Model, as_model
    >>> from problems import get_problem
    >>> isinstance(get_problem("duffing").create(), Model)
    True
    >>> x, xdot = sp.symbols("x xdot")
    >>> system = QuasilinearSystem([x], [xdot], [1], [EPS * (1 - x**2) * xdot])
    >>> model = as_model(system, values={"epsilon": 0.1})
    >>> isinstance(model, Model), model.state_names()
    (True, ('x', 'xdot'))
    """

    __slots__ = ()

    # ------------------------------------------------------------------ required
    @abstractmethod
    def state_names(self) -> tuple[str, ...]:
        """Names of the state components, in the order of the original equations' state."""

    @abstractmethod
    def solve(self, order: int = 1) -> PeriodicSolution:
        """The analytic periodic solution of ``order``."""

    @abstractmethod
    def state(self, solution: PeriodicSolution, t) -> dict[str, np.ndarray]:
        """The physical state along ``solution`` at physical times ``t``, by name."""

    @abstractmethod
    def period(self, solution: PeriodicSolution) -> float:
        """The analytic period in physical time."""

    @abstractmethod
    def epsilon(self) -> float:
        """The value of the expansion parameter ε."""

    @abstractmethod
    def system(self) -> QuasilinearSystem:
        """The quasilinear system the solution is built for."""

    @abstractmethod
    def symbol_values(self) -> dict[str, float]:
        """Numbers for the system's parameters, by name."""

    # ------------------------------------------------------------------ with defaults
    def method_options(self) -> dict:
        """Options of :class:`perturb.PoincareMethod` (amplitudes, phase coordinate, branch)."""
        return {}

    def case(self) -> Case:
        """This model's point as a :class:`~perturb.case.Case` — the system, the map of its
        parameters, their values — whose other points (:meth:`~perturb.case.Case.at`) carry the
        model there (:attr:`~perturb.case.Case.model`). The one door through which the sweep,
        the response and the phase diagram reach a model's other points.

        Default: the system's symbols and its own parameter as the parameters, each the
        symbol of the same name; the model at another point is :meth:`with_parameters`'s.
        """
        values = {**self.symbol_values(), self.system().parameter.name: parameter_value_of(self)}
        return identity_case(self, values)

    def with_parameters(self, **values: float) -> Model | None:
        """The same model with some parameters (names of its :meth:`case`'s values) set to
        ``values`` — a point of a sweep (default: None, the model cannot be re-created).

        Raises the model's own error for values it does not accept.
        """
        return None


def _substitutions(model, y0) -> dict | None:
    return substitutions(model.system(), model.symbol_values(), parameter_value_of(model), y0)


def system_integrals(model, y0: np.ndarray | None = None) -> Integrals | None:
    """The first integrals of ``model``'s quasilinear system, named: its declared ones
    (``I0, I1, ...``), else its energy when the forces derive from a potential, else None —
    what :func:`perturb.validation.capabilities.integrals_of_motion` gives a model without
    integrals of its own.

    Parameters
    ----------
    model : Model
    y0 : array_like, optional
        The initial state, needed only by systems whose equations contain initial values.

    Returns
    -------
    Integrals or None

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.validation.model import system_integrals
    >>> from problems import get_problem
    >>> energy = system_integrals(get_problem("duffing").create(eps=0.1))
    >>> energy.names, energy.function(np.array([1.0, 0.0]))  # x²/2 + eps x⁴/4
    (('energy',), array([0.525]))
    """
    subs = _substitutions(model, y0)
    if subs is None:
        return None
    system = model.system()
    exprs = [h.subs(subs) for h in system.first_integrals]
    names = tuple(f"I{i}" for i in range(len(exprs)))
    if not exprs:
        energy = conservative_energy(system, subs)
        if energy is None:
            return None
        exprs, names = [energy], ("energy",)
    return Integrals(lambdify_integrals(system.state_symbols, exprs), names)


@runtime_checkable
class OwnParameterValue(Protocol):
    """A model that computes the value of its system's own parameter itself (a bare system's
    given ``mu``, a problem file of earlier versions overriding ``parameter_value``)."""

    def parameter_value(self) -> float: ...


#: Whether a model class defines its own ``parameter_value()`` (:class:`OwnParameterValue`), by
#: class (held weakly: a class a user makes and drops is not kept alive by it).
_OWN_PARAMETER_VALUE: weakref.WeakKeyDictionary[type, bool] = weakref.WeakKeyDictionary()


def parameter_value_of(model) -> float:
    """The value the model's solution takes for its system's own parameter: ε, or μ = 1/ε in
    the large-parameter regime — the model's own ``parameter_value()`` where it defines one
    (:class:`OwnParameterValue`).

    Parameters
    ----------
    model : Model

    Returns
    -------
    float

    Examples
    --------
    >>> from perturb.validation.model import parameter_value_of
    >>> from problems import get_problem
    >>> parameter_value_of(get_problem("duffing").create(eps=0.1))
    0.1
    """
    kind = type(model)
    own = _OWN_PARAMETER_VALUE.get(kind)
    if own is None:  # asked once per class: a protocol's isinstance costs tens of microseconds
        own = _OWN_PARAMETER_VALUE[kind] = isinstance(model, OwnParameterValue)
    if own:
        return model.parameter_value()
    eps = model.epsilon()
    return 1.0 / eps if model.system().regime is Regime.LARGE else eps


def identity_case(
    model: Model,
    values: Mapping[str, float],
    reads: Callable | None = None,
    *,
    evaluates_directly: bool = False,
) -> Case:
    """The case of a model whose parameters are its system's symbols (the adapter at the door:
    another point's model is the model's own :meth:`Model.with_parameters`; ``reads``: the
    parameters its solution reads, None if unknown; ``evaluates_directly``: see
    :attr:`perturb.case.Case.evaluates_directly`)."""
    system = model.system()

    def check(point):
        return check_system_values(system, point)

    def check_columns(base, grid, size):  # only a number that is not finite is refused
        finite = np.all([np.isfinite(c) for c in grid.values()], axis=0)
        errors = [""] * size
        for i in np.flatnonzero(~finite):  # the point's own message
            try:
                check({**base, **{n: c[i] for n, c in grid.items()}})
            except ValueError as exc:
                errors[i] = str(exc)
        return errors, [""] * size

    return Case.of(
        system, values, check=check, model_of=lambda case: model.with_parameters(**case.values),
        check_columns=check_columns, solution_reads=reads, evaluates_directly=evaluates_directly,
    )  # fmt: skip
