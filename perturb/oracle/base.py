"""What every integrator of the oracle shares: the result, its status, and the template base class.

Every integrator solves :math:`\\dot y = f(y)` with ``rhs(y) -> dy/dt`` (a numpy callable on a state
vector of shape ``(n,)``; no time argument, the systems are autonomous) and returns a
:class:`Trajectory`.  The backends live one per module (:mod:`perturb.oracle.rk4`,
:mod:`perturb.oracle.scipy`, :mod:`perturb.oracle.heyoka`) behind :class:`IntegratorBase`, and are
registered by name in :mod:`perturb.oracle.registry`.
"""

from __future__ import annotations

import abc
import enum
import math
from collections.abc import Callable, Sequence
from typing import Any, Protocol, runtime_checkable

import attrs
import numpy as np
from attrs import field, frozen

from perturb.errors import IntegrationError, bad_value
from perturb.oracle._noise import integration_noise
from perturb.oracle.symbolic import SymbolicRHS

__all__ = [
    "JAC",
    "RHS",
    "Integrator",
    "IntegratorBase",
    "Run",
    "Trajectory",
    "TrajectoryStatus",
    "check_positive",
]

RHS = Callable[[np.ndarray], np.ndarray]
JAC = Callable[[np.ndarray], np.ndarray]


class TrajectoryStatus(enum.Enum):
    """How an integration ended; the values are the user-facing messages (as diffrax ``RESULTS``).

    :attr:`Trajectory.message` is the value on success, and the backend's own sentence (with the
    numbers of the run) on failure.

    Examples
    --------
    >>> import numpy as np
    >>> def oscillator(y):  # x'' + x = 0 as a first-order system
    ...     return np.array([y[1], -y[0]])
    >>> from perturb.oracle import Scipy, TrajectoryStatus
    >>> trajectory = Scipy(max_steps=5).integrate(oscillator, (0.0, 100.0), [1.0, 0.0])
    >>> trajectory.status is TrajectoryStatus.MAX_STEPS, trajectory.success
    (True, False)
    """

    SUCCESS = "The integration reached the end of the interval."
    MAX_STEPS = "The step budget `max_steps` was exhausted before the end of the interval."
    NON_FINITE = "The state became non-finite (NaN or infinity) during the integration."
    SOLVER_FAILED = "The solver failed (step size too small, singularity or no progress)."

    @property
    def success(self) -> bool:
        """True only for :attr:`SUCCESS`."""
        return self is TrajectoryStatus.SUCCESS

    @property
    def code(self) -> int:
        """The legacy integer code (0 success, negative failure, as scipy's ``OdeResult.status``).

        Kept for the JSON reports whose ``status`` key is an integer; new code compares members.
        """
        return _TRAJECTORY_CODES[self]


_TRAJECTORY_CODES = {
    TrajectoryStatus.SUCCESS: 0,
    TrajectoryStatus.MAX_STEPS: -1,
    TrajectoryStatus.NON_FINITE: -2,
    TrajectoryStatus.SOLVER_FAILED: -3,
}


def _readonly(value: Any) -> np.ndarray:
    array = np.array(value)  # a copy, so freezing it cannot affect the caller's array
    array.setflags(write=False)
    return array


@frozen
class Trajectory:
    """Result of an integration: output times, states, and how the run ended.

    Attributes
    ----------
    t : ndarray, shape (n_t,)
        Output times (``t_eval``, or the two ends of ``t_span``), up to the time reached.
    y : ndarray, shape (n_state, n_t)
        States at ``t`` (the same layout as ``scipy.integrate.solve_ivp``).  The dtype is float64,
        or the extended type of an extended-precision heyoka run.
    status : TrajectoryStatus
        :attr:`TrajectoryStatus.SUCCESS` if the end of the interval was reached, else the failure.
    message : str
        Human-readable outcome, including the solver's own message on failure.
    t_reached : float
        The last time the integrator reached (the end of ``t_span`` on success).
    nfev : int
        Number of rhs evaluations; for heyoka the number of Taylor steps (one evaluation of the
        Taylor coefficients each).
    integrator : str
        Description of the integrator that actually ran, e.g. ``"scipy DOP853 (rtol=1e-12)"``.

    Examples
    --------
    >>> import numpy as np
    >>> def oscillator(y):  # x'' + x = 0 as a first-order system
    ...     return np.array([y[1], -y[0]])
    >>> from perturb.oracle import Scipy
    >>> trajectory = Scipy().integrate(oscillator, (0.0, np.pi), [1.0, 0.0], t_eval=[0.0, np.pi / 2, np.pi])
    >>> trajectory.success, trajectory.t.shape, trajectory.y.shape
    (True, (3,), (2, 3))
    >>> trajectory.y[0].round(9)
    array([ 1.,  0., -1.])
    """

    t: np.ndarray = field(converter=_readonly, eq=attrs.cmp_using(eq=np.array_equal))
    y: np.ndarray = field(converter=_readonly, eq=attrs.cmp_using(eq=np.array_equal))
    status: TrajectoryStatus = field(
        default=TrajectoryStatus.SUCCESS, validator=attrs.validators.instance_of(TrajectoryStatus)
    )
    message: str = TrajectoryStatus.SUCCESS.value
    t_reached: float = math.nan
    nfev: int = 0
    integrator: str = ""

    @property
    def success(self) -> bool:
        """True if the integration reached the end of the interval."""
        return self.status.success

    @property
    def y_final(self) -> np.ndarray:
        """The last state computed, shape ``(n_state,)``."""
        return self.y[:, -1]

    def raise_for_status(self) -> Trajectory:
        """Return ``self`` if successful, else raise :class:`perturb.errors.IntegrationError`."""
        if not self.success:
            raise IntegrationError(
                f"{self.integrator}: {self.message}", self.status.code, self.t_reached
            )
        return self


@frozen
class Run:
    """What a backend's :meth:`IntegratorBase._integrate_impl` hands back to the template.

    Attributes
    ----------
    t : sequence of float
        The grid points reached, a prefix of the ``grid`` passed in (all of it on success).
    states : sequence of ndarray or ndarray, shape (len(t), n)
        The state at each of them (a list of vectors, or the rows of one array).
    t_reached : float
        The last time the backend reached.
    nfev : int
        Number of rhs evaluations (Taylor steps for heyoka).
    status : TrajectoryStatus
    message : str, optional
        A sentence with the run's numbers on failure; default: the status's own message.
    """

    t: Any
    states: Any
    t_reached: float
    nfev: int
    status: TrajectoryStatus = TrajectoryStatus.SUCCESS
    message: str | None = None


@runtime_checkable
class Integrator(Protocol):
    """What the oracle needs from an integrator (structural protocol).

    Implementations are frozen value objects with a ``name`` and an :meth:`integrate` method that
    follows the contract of :class:`IntegratorBase`; subclassing it is the easy way to comply.

    Examples
    --------
    >>> from perturb.oracle import RK4, Integrator, Scipy
    >>> isinstance(RK4(), Integrator), isinstance(Scipy(), Integrator)
    (True, True)
    """

    @property
    def name(self) -> str:
        """Short description of the integrator and its settings."""
        ...

    def integrate(
        self,
        rhs: RHS,
        t_span: tuple[float, float],
        y0: Sequence[float],
        *,
        t_eval: Sequence[float] | None = None,
        jac: JAC | None = None,
    ) -> Trajectory:
        """Integrate ``y' = rhs(y)`` from ``y(t_span[0]) = y0`` up to ``t_span[1]``."""
        ...


class IntegratorBase(abc.ABC):
    """Base class of the oracle's integrators (abstract; a template, as scipy's ``OdeSolver``).

    The public :meth:`integrate` validates the input, builds the output grid, calls the backend's
    :meth:`_integrate_impl` and assembles the :class:`Trajectory`.  Its contract, for callers:

    1. Invalid input (``t_span`` not increasing, non-finite ``y0``, ``t_eval`` outside ``t_span``, an
       rhs of the wrong kind or size) raises :class:`perturb.errors.InvalidParameterError` naming
       the argument, the value and the fix.
    2. A valid run that fails numerically *returns* a :class:`Trajectory` whose ``status`` is a
       failed :class:`TrajectoryStatus`, with the solver's message and the time reached, holding
       the output points computed before the failure.
    3. Without ``t_eval`` the trajectory holds the initial and the final state only.

    To add an integrator (one new module and one line in ``registry.INTEGRATORS``):

    1. Subclass this class with an attrs ``@frozen`` value object whose fields are the settings,
       validated in ``__attrs_post_init__`` with :func:`check_positive` / ``bad_value``.
    2. Implement the property ``name``: a short description with the settings that matter, e.g.
       ``"scipy DOP853 (rtol=1e-12)"``; it is copied into every :class:`Trajectory`.
    3. Implement ``_integrate_impl(rhs, t0, t1, y0, grid, jac) -> Run``.  It receives a validated
       problem: ``t0 < t1`` finite, ``y0`` a finite 1-D array (not yet cast to float, so that an
       extended-precision backend keeps its digits), ``grid`` the strictly increasing output times
       in ``[t0, t1]``.  It returns the states at the grid points reached, in order.  It never
       raises for a numerical failure: it stops and returns a failed ``status`` with a message.
    4. Optionally override ``_accept_rhs(rhs)`` to refuse, before anything else, an rhs the backend
       cannot take (heyoka needs a :class:`~perturb.oracle.symbolic.SymbolicRHS`).
    5. Register a factory in :data:`perturb.oracle.registry.INTEGRATORS`, and in
       :func:`perturb.oracle.registry.choose` if it takes ``rtol``/``max_steps``.
    6. Optionally override :meth:`loosened` (a copy whose error is ``factor`` times larger): the
       shooting uses it to measure its own noise floor a posteriori.

    Examples
    --------
    A forward-Euler integrator in a few lines (the template validates the input and assembles the
    trajectory; ``_integrate_impl`` only steps):

    >>> from attrs import frozen
    >>> from perturb.oracle import IntegratorBase
    >>> from perturb.oracle.base import Run
    >>> @frozen
    ... class Euler(IntegratorBase):
    ...     steps: int = 1000
    ...     @property
    ...     def name(self):
    ...         return f"forward Euler ({self.steps} steps)"
    ...     def _integrate_impl(self, rhs, t0, t1, y0, grid, jac):
    ...         y, h, states = np.asarray(y0, float), (t1 - t0) / self.steps, []
    ...         for k in range(self.steps + 1):
    ...             if any(np.isclose(t0 + k * h, grid)):
    ...                 states.append(y.copy())
    ...             y = y + h * rhs(y)
    ...         return Run(t=list(grid), states=states, t_reached=t1, nfev=self.steps)
    >>> import numpy as np
    >>> def oscillator(y):  # x'' + x = 0 as a first-order system
    ...     return np.array([y[1], -y[0]])
    >>> trajectory = Euler().integrate(oscillator, (0.0, 1.0), [1.0, 0.0])
    >>> trajectory.integrator, trajectory.y.shape
    ('forward Euler (1000 steps)', (2, 2))
    >>> bool(abs(trajectory.y[0, -1] - np.cos(1.0)) < 1e-3)  # first order: error ~ h
    True
    """

    __slots__ = ()

    @property
    @abc.abstractmethod
    def name(self) -> str:
        """Short description of the integrator and its settings."""

    def integrate(
        self,
        rhs: RHS,
        t_span: tuple[float, float],
        y0: Sequence[float],
        *,
        t_eval: Sequence[float] | None = None,
        jac: JAC | None = None,
    ) -> Trajectory:
        """Integrate ``y' = rhs(y)`` from ``y(t_span[0]) = y0`` up to ``t_span[1]``.

        Parameters
        ----------
        rhs : callable or SymbolicRHS
            ``rhs(y) -> dy/dt``.
        t_span : (float, float)
            Start and end time, ``t_span[0] < t_span[1]``.
        y0 : array_like, shape (n,)
            Initial state.
        t_eval : array_like, optional
            Strictly increasing output times inside ``t_span``; default: its two ends.
        jac : callable, optional
            ``jac(y) -> (n, n)``, used by the implicit methods; others ignore it.

        Returns
        -------
        Trajectory
            Also on a numerical failure (see the class docstring).

        Raises
        ------
        perturb.errors.InvalidParameterError
            For invalid input.
        """
        self._accept_rhs(rhs)
        t0, t1, y0_array, t_eval_array = _check_problem(t_span, y0, t_eval)
        _check_rhs(rhs, y0_array.size)
        grid = np.array([t0, t1]) if t_eval_array is None else t_eval_array
        run = self._integrate_impl(rhs, t0, t1, y0_array, grid, jac)
        n, n_t = y0_array.size, len(run.t)
        y = np.asarray(run.states).T.reshape(n, n_t) if n_t else np.empty((n, 0))
        y = integration_noise(y, run.t, t0, y0_array, self.name)  # off unless PERTURB_TEST_NOISE
        return Trajectory(
            t=np.asarray(run.t, dtype=float),
            y=y,
            status=run.status,
            message=run.status.value if run.message is None else run.message,
            t_reached=run.t_reached,
            nfev=int(run.nfev),
            integrator=self.name,
        )

    def loosened(self, factor: float) -> IntegratorBase | None:
        """A copy of this integrator whose error is about ``factor`` times larger, or None.

        Comparing a result with the loosened integrator's measures the error of this one a
        posteriori: for a method whose error is proportional to its tolerance,
        :math:`|y_{loose} - y| \approx (factor - 1)\\,|e|`.  None (the default) when the backend
        has no such setting.
        """
        return None

    def _accept_rhs(self, rhs: RHS) -> None:  # noqa: B027 (an optional hook, empty by default)
        """Refuse an rhs this backend cannot integrate (hook; accepts everything by default)."""

    @abc.abstractmethod
    def _integrate_impl(
        self, rhs: RHS, t0: float, t1: float, y0: np.ndarray, grid: np.ndarray, jac: JAC | None
    ) -> Run:
        """Integrate a validated problem and return the states at the grid points reached."""


# --------------------------------------------------------------------------------------------------
# input validation shared by all integrators
# --------------------------------------------------------------------------------------------------


def _check_problem(t_span, y0, t_eval):
    """Validate (t_span, y0, t_eval); return (t0, t1, y0 array, t_eval array or None)."""
    try:
        t0, t1 = (float(v) for v in t_span)
    except (TypeError, ValueError):
        raise bad_value("t_span", t_span, "pass a pair of numbers (t_start, t_end)") from None
    if not (math.isfinite(t0) and math.isfinite(t1)) or t1 <= t0:
        raise bad_value(
            "t_span", t_span, "the end must be finite and greater than the start (forward in time)"
        )
    y0_array = np.asarray(y0)
    if y0_array.dtype == object or y0_array.dtype.kind not in "iuf":
        try:
            y0_array = y0_array.astype(float)
        except (TypeError, ValueError):
            raise bad_value("y0", y0, "pass a 1-D array of real numbers") from None
    if y0_array.ndim != 1 or y0_array.size == 0:
        raise bad_value("y0", y0, "pass a non-empty 1-D state vector")
    if not np.all(np.isfinite(y0_array.astype(float))):
        raise bad_value("y0", y0, "every initial state component must be finite (no NaN/inf)")
    if t_eval is not None:
        t_eval = np.asarray(t_eval, dtype=float)
        if t_eval.ndim != 1 or t_eval.size == 0:
            raise bad_value("t_eval", t_eval, "pass a non-empty 1-D array of times")
        if np.any(np.diff(t_eval) <= 0):
            raise bad_value("t_eval", t_eval, "output times must be strictly increasing")
        if t_eval[0] < t0 or t_eval[-1] > t1:
            raise bad_value(
                "t_eval",
                f"[{t_eval[0]}, ..., {t_eval[-1]}]",
                f"output times must lie inside t_span = ({t0}, {t1})",
            )
    return t0, t1, y0_array, t_eval


def _check_rhs(rhs, n: int) -> None:
    if not callable(rhs):
        raise bad_value("rhs", rhs, "pass a callable rhs(y) -> dy/dt or a SymbolicRHS")
    if isinstance(rhs, SymbolicRHS) and rhs.n != n:
        raise bad_value("y0", f"{n} components", f"the symbolic rhs has {rhs.n} state variables")


def check_positive(name: str, value, fix: str = "pass a positive number") -> None:
    """Raise ``bad_value(name, value, fix)`` unless ``value`` (scalar or array) is finite and > 0."""
    try:
        ok = bool(np.all(np.asarray(value, dtype=float) > 0))
        ok = ok and bool(np.all(np.isfinite(np.asarray(value, dtype=float))))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise bad_value(name, value, fix)
