"""Numerical integrators of autonomous ODEs behind one protocol.

Every integrator solves :math:`\\dot y = f(y)` with ``rhs(y) -> dy/dt`` (a numpy callable on a state
vector of shape ``(n,)``; no time argument, the systems are autonomous) and returns a
:class:`Trajectory`.  Three families are provided:

- :class:`RK4`: classical fixed-step Runge–Kutta of order 4 (the seed paper's method), pure numpy.
- :class:`Scipy`: the adaptive integrators of :mod:`scipy.integrate` (DOP853, RK45, Radau, LSODA, ...),
  with per-component absolute tolerances (see :func:`scaled_atol`).
- :class:`Heyoka`: the adaptive Taylor method of heyoka.py, in double or extended precision.  It needs
  the rhs as a :class:`~perturb.oracle.symbolic.SymbolicRHS`.

Contract of :meth:`Integrator.integrate` (all implementations):

1. Invalid input (``t_span`` not increasing, non-finite ``y0``, ``t_eval`` outside ``t_span``)
   raises :class:`perturb.errors.InvalidParameterError` naming the argument, the value and the fix.
2. A valid run that fails numerically *returns* a :class:`Trajectory` whose ``status`` is a failed
   :class:`TrajectoryStatus`, with the solver's message and the time reached, holding the output points computed before the failure.
3. Without ``t_eval`` the trajectory holds the initial and the final state only.
"""

from __future__ import annotations

import copy
import enum
import functools
import math
import threading
from collections.abc import Callable, Sequence
from typing import Any, Protocol, runtime_checkable

import attrs
import numpy as np
import scipy.integrate
from attrs import field, frozen

from perturb.errors import IntegrationError, UnknownNameError, bad_value
from perturb.oracle._settings import (
    ATOL_FLOOR_FRACTION,
    DEFAULT_HEYOKA_TOL,
    DEFAULT_RK4_STEPS_PER_UNIT,
    DEFAULT_RTOL,
    HEYOKA_COMPACT_MODE_MIN_DIM,
    MAX_STEPS,
)
from perturb.oracle.symbolic import SymbolicRHS, to_heyoka

__all__ = [
    "INTEGRATORS",
    "RK4",
    "Heyoka",
    "Integrator",
    "Scipy",
    "Trajectory",
    "TrajectoryStatus",
    "default_integrator",
    "get_integrator",
    "heyoka_available",
    "scaled_atol",
]

RHS = Callable[[np.ndarray], np.ndarray]
JAC = Callable[[np.ndarray], np.ndarray]


class TrajectoryStatus(enum.Enum):
    """How an integration ended; the values are the user-facing messages (as diffrax ``RESULTS``).

    :attr:`Trajectory.message` starts from the value and may append the solver's own detail.
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

_OK_MESSAGE = TrajectoryStatus.SUCCESS.value


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
    """

    t: np.ndarray = field(converter=_readonly, eq=attrs.cmp_using(eq=np.array_equal))
    y: np.ndarray = field(converter=_readonly, eq=attrs.cmp_using(eq=np.array_equal))
    status: TrajectoryStatus = field(
        default=TrajectoryStatus.SUCCESS, validator=attrs.validators.instance_of(TrajectoryStatus)
    )
    message: str = _OK_MESSAGE
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


@runtime_checkable
class Integrator(Protocol):
    """What the oracle needs from an integrator (structural protocol).

    Implementations are frozen value objects with a ``name`` and an :meth:`integrate` method that
    follows the contract in the module docstring.
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


# --------------------------------------------------------------------------------------------------
# input validation shared by all integrators
# --------------------------------------------------------------------------------------------------


def _check_problem(t_span, y0, t_eval):
    """Validate (t_span, y0, t_eval); return (t0, t1, y0 float array, t_eval array or None)."""
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


def _positive(name: str, value, fix: str = "pass a positive number") -> None:
    try:
        ok = bool(np.all(np.asarray(value, dtype=float) > 0))
        ok = ok and bool(np.all(np.isfinite(np.asarray(value, dtype=float))))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise bad_value(name, value, fix)


# --------------------------------------------------------------------------------------------------
# RK4
# --------------------------------------------------------------------------------------------------


def _rk4_step(rhs: RHS, y: np.ndarray, h: float) -> np.ndarray:
    # y_{k+1} = y_k + h/6 (k1 + 2 k2 + 2 k3 + k4), classical Runge-Kutta
    k1 = rhs(y)
    k2 = rhs(y + 0.5 * h * k1)
    k3 = rhs(y + 0.5 * h * k2)
    k4 = rhs(y + h * k3)
    return y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


@frozen
class RK4:
    """Classical fixed-step Runge–Kutta method of order 4.

    Parameters
    ----------
    steps_per_unit : float, optional
        Steps per unit of time; the default is used when neither option is given.
    n_steps : int, optional
        Total number of steps over ``t_span`` (exclusive with ``steps_per_unit``).

    Notes
    -----
    The step is adjusted so that every output time is hit exactly: each interval between output
    times gets ``max(1, round(length / h))`` equal steps, ``h`` being the nominal step.  The global
    error is :math:`O(h^4)`.

    Raises
    ------
    perturb.errors.InvalidParameterError
        If both options are given, or either is not positive.
    """

    steps_per_unit: float | None = None
    n_steps: int | None = None

    def __attrs_post_init__(self):
        if self.steps_per_unit is not None and self.n_steps is not None:
            raise bad_value(
                "n_steps", self.n_steps, "give either `steps_per_unit` or `n_steps`, not both"
            )
        if self.steps_per_unit is not None:
            _positive("steps_per_unit", self.steps_per_unit)
        if self.n_steps is not None:
            if not isinstance(self.n_steps, int | np.integer) or self.n_steps < 1:
                raise bad_value("n_steps", self.n_steps, "pass an integer >= 1")

    @property
    def name(self) -> str:
        """Description, e.g. ``"rk4 (200 steps/unit)"``."""
        if self.n_steps is not None:
            return f"rk4 ({self.n_steps} steps)"
        return f"rk4 ({self._steps_per_unit:g} steps/unit)"

    @property
    def _steps_per_unit(self) -> float:
        return DEFAULT_RK4_STEPS_PER_UNIT if self.steps_per_unit is None else self.steps_per_unit

    def integrate(self, rhs, t_span, y0, *, t_eval=None, jac=None) -> Trajectory:
        """Integrate with fixed steps; see :class:`Integrator`.  ``jac`` is ignored."""
        t0, t1, y, t_eval = _check_problem(t_span, y0, t_eval)
        _check_rhs(rhs, y.size)
        y = y.astype(float)
        h = (t1 - t0) / self.n_steps if self.n_steps is not None else 1.0 / self._steps_per_unit
        nodes = np.unique(np.concatenate(([t0, t1], [] if t_eval is None else t_eval)))
        wanted = nodes if t_eval is None else t_eval
        ts, ys, nfev = [], [], 0
        if wanted[0] == t0:
            ts.append(t0)
            ys.append(y.copy())
        t = t0
        for a, b in zip(nodes[:-1], nodes[1:], strict=True):
            m = max(1, round((b - a) / h))
            hk = (b - a) / m
            for k in range(m):
                y = _rk4_step(rhs, y, hk)
                nfev += 4
                if not np.all(np.isfinite(y)):
                    return Trajectory(
                        t=np.array(ts),
                        y=np.array(ys).T.reshape(y.size, len(ts)),
                        status=TrajectoryStatus.NON_FINITE,
                        message=f"The state became non-finite (step size {hk:.3g}); reduce the step "
                        "or check the rhs for a singularity.",
                        t_reached=a + k * hk,
                        nfev=nfev,
                        integrator=self.name,
                    )
            t = b
            if t in wanted:
                ts.append(t)
                ys.append(y.copy())
        return Trajectory(
            t=np.array(ts), y=np.array(ys).T, t_reached=t, nfev=nfev, integrator=self.name
        )


# --------------------------------------------------------------------------------------------------
# scipy
# --------------------------------------------------------------------------------------------------

#: scipy's OdeSolver classes by method name (these are public in scipy.integrate).
_SCIPY_METHODS = {
    "DOP853": scipy.integrate.DOP853,
    "RK45": scipy.integrate.RK45,
    "RK23": scipy.integrate.RK23,
    "Radau": scipy.integrate.Radau,
    "BDF": scipy.integrate.BDF,
    "LSODA": scipy.integrate.LSODA,
}
_IMPLICIT = {"Radau", "BDF", "LSODA"}


def scaled_atol(y_scale: Sequence[float], rtol: float = DEFAULT_RTOL) -> np.ndarray:
    """Per-component absolute tolerances ``rtol * scale_i`` for states of very different sizes.

    scipy's default ``atol = 1e-6`` (or any one scalar) is wrong by orders of magnitude when state
    components are ~1e-3 or smaller: the error control then ignores them.  This helper scales the
    absolute tolerance of each component to its typical magnitude.

    Parameters
    ----------
    y_scale : array_like, shape (n,)
        Typical magnitude of each component (e.g. the initial state or the amplitudes).  Components
        below ``ATOL_FLOOR_FRACTION`` × the largest are raised to that floor, so a component that
        starts at zero is not given a zero tolerance.
    rtol : float, optional
        Relative tolerance.

    Returns
    -------
    ndarray, shape (n,)

    Raises
    ------
    perturb.errors.InvalidParameterError
        If ``rtol`` is not positive or ``y_scale`` is not finite or all zero.

    Examples
    --------
    >>> scaled_atol([1e-3, 0.0, 2e-3], rtol=1e-10)
    array([1.e-13, 2.e-16, 2.e-13])
    """
    _positive("rtol", rtol)
    scale = np.abs(np.asarray(y_scale, dtype=float))
    if scale.ndim != 1 or not np.all(np.isfinite(scale)):
        raise bad_value("y_scale", y_scale, "pass a 1-D array of finite magnitudes")
    largest = scale.max(initial=0.0)
    if largest == 0.0:
        raise bad_value(
            "y_scale", y_scale, "all magnitudes are zero; give the typical size of each component"
        )
    return rtol * np.maximum(scale, ATOL_FLOOR_FRACTION * largest)


@frozen
class Scipy:
    """Adaptive integrators of :mod:`scipy.integrate` (DOP853 by default).

    Parameters
    ----------
    method : {'DOP853', 'RK45', 'RK23', 'Radau', 'BDF', 'LSODA'}
        The scipy ``OdeSolver``.
    rtol : float
        Relative tolerance.
    atol : float or array_like, optional
        Absolute tolerance, scalar or per component.  Default: :func:`scaled_atol` of ``y_scale``,
        or of the initial state when ``y_scale`` is not given (unit scale for a zero initial state).
    y_scale : array_like, optional
        Typical magnitude of each state component, used for the default ``atol``.
    max_steps : int
        Step budget; exceeding it returns a failed :class:`Trajectory`.

    Notes
    -----
    The solver is stepped directly (not through ``solve_ivp``) so that a failure reports the exact
    time reached.  Output at ``t_eval`` uses the solver's dense output, as ``solve_ivp`` does.  The
    implicit methods use ``jac`` if given, else the symbolic Jacobian of a
    :class:`~perturb.oracle.symbolic.SymbolicRHS`, else finite differences.
    """

    method: str = "DOP853"
    rtol: float = DEFAULT_RTOL
    atol: Any = field(default=None, eq=False)
    y_scale: Any = field(default=None, eq=False)
    max_steps: int = MAX_STEPS

    def __attrs_post_init__(self):
        if self.method not in _SCIPY_METHODS:
            raise UnknownNameError(
                f"`method` = {self.method!r} is invalid: use one of {sorted(_SCIPY_METHODS)}"
            )
        _positive("rtol", self.rtol)
        if self.atol is not None:
            _positive("atol", self.atol, "pass a positive number or array of positive numbers")
        if self.y_scale is not None:
            scaled_atol(self.y_scale, self.rtol)  # validates
        if self.max_steps < 1:
            raise bad_value("max_steps", self.max_steps, "pass an integer >= 1")

    @property
    def name(self) -> str:
        """Description, e.g. ``"scipy DOP853 (rtol=1e-12)"``."""
        return f"scipy {self.method} (rtol={self.rtol:g})"

    def _atol(self, y0: np.ndarray) -> np.ndarray | float:
        if self.atol is not None:
            atol = np.asarray(self.atol, dtype=float)
            if atol.ndim == 1 and atol.size != y0.size:
                raise bad_value(
                    "atol", self.atol, f"give a scalar or {y0.size} values, one per component"
                )
            return atol
        if self.y_scale is not None:
            if np.size(self.y_scale) != y0.size:
                raise bad_value("y_scale", self.y_scale, f"give {y0.size} values")
            return scaled_atol(self.y_scale, self.rtol)
        scale = np.abs(y0) if np.any(y0 != 0) else np.ones_like(y0)
        return scaled_atol(scale, self.rtol)

    def integrate(self, rhs, t_span, y0, *, t_eval=None, jac=None) -> Trajectory:
        """Integrate with the adaptive scipy solver; see :class:`Integrator`."""
        t0, t1, y0, t_eval = _check_problem(t_span, y0, t_eval)
        _check_rhs(rhs, y0.size)
        y0 = y0.astype(float)
        options: dict[str, Any] = {"rtol": self.rtol, "atol": self._atol(y0)}
        if self.method in _IMPLICIT:
            if jac is None and isinstance(rhs, SymbolicRHS):
                jac = rhs.jacobian
            if jac is not None:
                options["jac"] = lambda t, y: jac(y)
        solver = _SCIPY_METHODS[self.method](lambda t, y: rhs(y), t0, y0, t1, **options)

        ts: list[float] = []
        ys: list[np.ndarray] = []
        pending = [t0, t1] if t_eval is None else list(t_eval)
        i = 0
        while i < len(pending) and pending[i] <= t0:
            ts.append(t0)
            ys.append(y0.copy())
            i += 1
        status, message, n_steps = TrajectoryStatus.SUCCESS, _OK_MESSAGE, 0
        while solver.status == "running":
            if n_steps >= self.max_steps:
                status = TrajectoryStatus.MAX_STEPS
                message = (
                    f"The step budget max_steps = {self.max_steps} was exhausted; raise "
                    "`max_steps` or loosen the tolerances (the problem may be stiff)."
                )
                break
            t_before = solver.t
            solver_message = solver.step()
            n_steps += 1
            if solver.status == "failed":
                status = TrajectoryStatus.SOLVER_FAILED
                message = f"scipy {self.method} failed: {solver_message}"
                break
            if solver.t <= t_before:  # LSODA keeps "stepping" with h = 0 at a singularity
                status = TrajectoryStatus.SOLVER_FAILED
                message = (
                    f"scipy {self.method} made no progress at t = {solver.t} (step size "
                    f"{solver.step_size}): singularity or blow-up of the solution."
                )
                break
            dense = None
            while i < len(pending) and pending[i] <= solver.t:
                if pending[i] == solver.t:
                    y = solver.y.copy()
                else:
                    dense = dense if dense is not None else solver.dense_output()
                    y = dense(pending[i])
                ts.append(pending[i])
                ys.append(y)
                i += 1
            if not np.all(np.isfinite(solver.y)):
                status = TrajectoryStatus.NON_FINITE
                message = f"The state became non-finite at t = {solver.t}."
                break
        y_out = np.array(ys).T if ys else np.empty((y0.size, 0))
        return Trajectory(
            t=np.array(ts),
            y=y_out,
            status=status,
            message=message,
            t_reached=float(solver.t),
            nfev=int(solver.nfev),
            integrator=self.name,
        )


# --------------------------------------------------------------------------------------------------
# heyoka
# --------------------------------------------------------------------------------------------------


@functools.cache
def heyoka_available() -> bool:
    """True if heyoka.py can be imported."""
    try:
        import heyoka  # noqa: F401
    except ImportError:
        return False
    return True


def _fp_types() -> dict[str, type]:
    import heyoka as hy

    types: dict[str, type] = {"double": float}
    if np.finfo(np.longdouble).eps < np.finfo(np.float64).eps:  # x86 80-bit long double
        types["long double"] = np.longdouble
    if hasattr(hy, "real128"):
        types["real128"] = hy.real128
    return types


def _to_fp(values, fp: type) -> np.ndarray:
    """An array of ``values`` in the floating point type ``fp`` (float, longdouble or real128)."""
    if fp is float or fp is np.longdouble:
        return np.asarray(values, dtype=fp)
    # real128: go through the decimal string, which keeps all digits of a long double input
    return np.array([v if isinstance(v, fp) else fp(str(v)) for v in values])


@functools.lru_cache(maxsize=64)
def _compiled_taylor(rhs: SymbolicRHS, fp_name: str, tol: float | None, compact_mode: bool):
    """JIT-compile (once per rhs, precision and tolerance) a heyoka integrator for ``rhs``."""
    import heyoka as hy

    fp_type = _fp_types()[fp_name]
    variables = hy.make_vars(*[f"y{i}" for i in range(rhs.n)])
    if rhs.n == 1:
        variables = [variables]
    table = dict(zip(rhs.state, variables, strict=True))
    system = [
        (v, to_heyoka(e, table, fp_type)) for v, e in zip(variables, rhs.expressions, strict=True)
    ]
    kwargs: dict[str, Any] = {"compact_mode": compact_mode}
    if fp_type is not float:
        kwargs["fp_type"] = fp_type
    if tol is not None:
        kwargs["tol"] = fp_type(tol) if fp_type is not float else tol
    return hy.taylor_adaptive(system, _to_fp(np.zeros(rhs.n), fp_type), **kwargs)


_THREAD_STATE = threading.local()


def _thread_integrator(rhs: SymbolicRHS, fp_name: str, tol: float | None, compact_mode: bool):
    """This thread's own copy of the compiled integrator, reused across calls.

    Copying a compiled ``taylor_adaptive`` costs ~0.7 ms (its Taylor buffers): paying it once per
    thread rather than per call keeps short oracle runs within a few percent of bare heyoka. Every
    call resets the time and the state, which is all a propagation depends on.
    """
    cache = getattr(_THREAD_STATE, "integrators", None)
    if cache is None:
        cache = _THREAD_STATE.integrators = {}
    key = (rhs, fp_name, tol, compact_mode)
    if key not in cache:
        cache[key] = copy.copy(_compiled_taylor(rhs, fp_name, tol, compact_mode))
    return cache[key]


@frozen
class Heyoka:
    """Adaptive Taylor integrator of heyoka.py (``taylor_adaptive``).

    Parameters
    ----------
    tol : float, optional
        Tolerance (relative and absolute) of the Taylor method; default: the machine epsilon of the
        floating point type, heyoka's default.
    high_precision : bool
        Run in extended precision: 80-bit long double where the platform has it, else real128
        (quadruple).  Used for reference runs; the trajectory then keeps the extended dtype.
    fp_type : {'double', 'long double', 'real128'}, optional
        Explicit floating point type; overrides ``high_precision``.
    compact_mode : bool, optional
        heyoka's compact mode (faster compilation of large systems); default: on for systems with at
        least ``HEYOKA_COMPACT_MODE_MIN_DIM`` equations.
    max_steps : int
        Step budget; exceeding it returns a failed :class:`Trajectory`.

    Notes
    -----
    heyoka builds the Taylor series of the solution from the *expressions* of the rhs, so ``rhs``
    must be a :class:`~perturb.oracle.symbolic.SymbolicRHS`.  The compiled integrator is cached per
    (rhs, precision, tolerance); the first call pays the JIT compilation (~0.05 s for a 2-D system,
    about a second for a 42-equation variational system).
    """

    tol: float | None = DEFAULT_HEYOKA_TOL
    high_precision: bool = False
    fp_type: str | None = None
    compact_mode: bool | None = None
    max_steps: int = MAX_STEPS

    def __attrs_post_init__(self):
        if self.tol is not None:
            _positive("tol", self.tol)
        if self.fp_type is not None and self.fp_type not in ("double", "long double", "real128"):
            raise bad_value("fp_type", self.fp_type, "use 'double', 'long double' or 'real128'")
        if self.max_steps < 1:
            raise bad_value("max_steps", self.max_steps, "pass an integer >= 1")

    @property
    def precision(self) -> str:
        """Name of the floating point type used: ``'double'``, ``'long double'`` or ``'real128'``."""
        if self.fp_type is not None:
            return self.fp_type
        if not self.high_precision:
            return "double"
        if not heyoka_available():
            return "long double"
        types = _fp_types()
        return "long double" if "long double" in types else "real128"

    @property
    def name(self) -> str:
        """Description, e.g. ``"heyoka taylor_adaptive (double, tol=1e-15)"``."""
        tol = "eps" if self.tol is None else f"{self.tol:g}"
        return f"heyoka taylor_adaptive ({self.precision}, tol={tol})"

    def integrate(self, rhs, t_span, y0, *, t_eval=None, jac=None) -> Trajectory:
        """Integrate with the Taylor method; see :class:`Integrator`.  ``jac`` is not needed."""
        if not heyoka_available():
            raise bad_value(
                "integrator",
                "heyoka",
                "heyoka is not installed: `pip install heyoka`, or use 'dop853'",
            )
        if not isinstance(rhs, SymbolicRHS):
            raise bad_value(
                "rhs",
                rhs,
                "heyoka needs a symbolic rhs: pass perturb.oracle.SymbolicRHS(state_symbols, "
                "sympy_expressions), or use a numeric integrator such as get_integrator('dop853')",
            )
        t0, t1, y0, t_eval = _check_problem(t_span, y0, t_eval)
        _check_rhs(rhs, y0.size)
        types = _fp_types()
        if self.precision not in types:
            raise bad_value(
                "fp_type", self.precision, f"this platform/heyoka build offers {sorted(types)}"
            )
        fp = types[self.precision]
        compact = (
            rhs.n >= HEYOKA_COMPACT_MODE_MIN_DIM if self.compact_mode is None else self.compact_mode
        )
        ta = _thread_integrator(rhs, self.precision, self.tol, compact)
        ta.time = _to_fp([t0], fp)[0]
        ta.state[:] = _to_fp(y0, fp)

        import heyoka as hy

        grid = np.array([t0, t1]) if t_eval is None else t_eval
        grid_fp = _to_fp(grid, fp)
        n_steps = 0
        outcome = hy.taylor_outcome.time_limit
        if grid[0] > t0:
            outcome, _, _, n, *_ = ta.propagate_until(grid_fp[0], max_steps=self.max_steps)
            n_steps += n
        if outcome == hy.taylor_outcome.time_limit:
            t_before = ta.time
            outcome, _, _, n, _, states = ta.propagate_grid(grid_fp, max_steps=self.max_steps)
            n_steps += n
            reached = float(ta.time) if math.isfinite(float(ta.time)) else float(t_before)
            # on failure heyoka returns only the rows of the grid points it reached
            states = np.asarray(states)[: len(grid)]
            good = np.all(np.isfinite(states.astype(float)), axis=1)
            ts, ys = grid[: len(states)][good], states[good].T.reshape(y0.size, -1)
        else:
            reached = float(ta.time)
            ts, ys = grid[:0], np.empty((y0.size, 0))
        status, message = TrajectoryStatus.SUCCESS, _OK_MESSAGE
        if outcome == hy.taylor_outcome.step_limit:
            status = TrajectoryStatus.MAX_STEPS
            message = (
                f"heyoka stopped at the step budget max_steps = {self.max_steps} "
                f"({outcome}); raise `max_steps` or check the motion for blow-up."
            )
        elif outcome != hy.taylor_outcome.time_limit:
            status = (
                TrajectoryStatus.NON_FINITE
                if outcome == hy.taylor_outcome.err_nf_state
                else TrajectoryStatus.SOLVER_FAILED
            )
            message = f"heyoka stopped with outcome {outcome} (non-finite state or step size)."
        return Trajectory(
            t=ts,
            y=ys,
            status=status,
            message=message,
            t_reached=reached,
            nfev=int(n_steps),
            integrator=self.name,
        )


# --------------------------------------------------------------------------------------------------
# registry
# --------------------------------------------------------------------------------------------------

#: Integrator factories by name (lower case); ``get_integrator(name, **opts)`` calls them.
INTEGRATORS: dict[str, Callable[..., Integrator]] = {
    "rk4": RK4,
    "dop853": functools.partial(Scipy, "DOP853"),
    "rk45": functools.partial(Scipy, "RK45"),
    "radau": functools.partial(Scipy, "Radau"),
    "lsoda": functools.partial(Scipy, "LSODA"),
    "heyoka": Heyoka,
}


def get_integrator(name: str, **options: Any) -> Integrator:
    """Build an integrator from its registry name.

    Parameters
    ----------
    name : str
        One of ``INTEGRATORS`` (case-insensitive): 'rk4', 'dop853', 'rk45', 'radau', 'lsoda', 'heyoka'.
    **options
        Passed to the factory, e.g. ``rtol=1e-10`` or ``steps_per_unit=100``.

    Raises
    ------
    perturb.errors.UnknownNameError
        If ``name`` is not registered; the message lists the known names.

    Examples
    --------
    >>> get_integrator("dop853", rtol=1e-10).name
    'scipy DOP853 (rtol=1e-10)'
    """
    key = str(name).lower()
    if key not in INTEGRATORS:
        raise UnknownNameError(
            f"`name` = {name!r} is not a known integrator: use one of {sorted(INTEGRATORS)}"
        )
    return INTEGRATORS[key](**options)


def default_integrator(rhs: RHS | None = None) -> Integrator:
    """The integrator used when none is given: heyoka if importable, else scipy DOP853.

    Parameters
    ----------
    rhs : callable, optional
        The rhs to be integrated; if given and not a
        :class:`~perturb.oracle.symbolic.SymbolicRHS`, DOP853 is chosen since heyoka cannot
        integrate a plain numeric callable.

    Returns
    -------
    Integrator
        ``Heyoka()`` or ``Scipy('DOP853')``; the :class:`Trajectory` it returns names it.
    """
    if heyoka_available() and (rhs is None or isinstance(rhs, SymbolicRHS)):
        return Heyoka()
    return Scipy("DOP853")
