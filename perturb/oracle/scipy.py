"""The adaptive integrators of :mod:`scipy.integrate` (DOP853, RK45, Radau, LSODA, ...).

Per-component absolute tolerances come from :func:`scaled_atol`.  This is the only module of the
oracle that imports :mod:`scipy.integrate`, and only when an integration runs (it takes a quarter
of a second, more than a warm ``perturb validate`` integrating with heyoka spends on its work).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np
from attrs import field, frozen

from perturb._checks import check_count
from perturb._defaults import ATOL_FLOOR_FRACTION, DEFAULT_RTOL, MAX_STEPS
from perturb.errors import UnknownNameError, bad_value
from perturb.oracle.base import IntegratorBase, Run, TrajectoryStatus, check_positive
from perturb.oracle.symbolic import SymbolicRHS

__all__ = ["Scipy", "scaled_atol"]

#: The method names: each is the name of a public OdeSolver class of scipy.integrate.
_SCIPY_METHODS = ("DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA")
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
    check_positive("rtol", rtol)
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
class Scipy(IntegratorBase):
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

    Examples
    --------
    >>> import numpy as np
    >>> def oscillator(y):  # x'' + x = 0 as a first-order system
    ...     return np.array([y[1], -y[0]])
    >>> from perturb.oracle import Scipy
    >>> integrator = Scipy("RK45", rtol=1e-8)
    >>> integrator.name
    'scipy RK45 (rtol=1e-08)'
    >>> trajectory = integrator.integrate(oscillator, (0.0, 2 * np.pi), [1.0, 0.0])
    >>> bool(np.allclose(trajectory.y[:, -1], [1.0, 0.0], atol=1e-6))
    True
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
        check_positive("rtol", self.rtol)
        if self.atol is not None:
            check_positive("atol", self.atol, "pass a positive number or array of positive numbers")
        if self.y_scale is not None:
            scaled_atol(self.y_scale, self.rtol)  # validates
        check_count("max_steps", self.max_steps)

    @property
    def name(self) -> str:
        """Description, e.g. ``"scipy DOP853 (rtol=1e-12)"``."""
        return f"scipy {self.method} (rtol={self.rtol:g})"

    def loosened(self, factor: float) -> Scipy:
        """A copy with ``rtol`` and ``atol`` (given or derived) ``factor`` times larger."""
        atol = None if self.atol is None else np.asarray(self.atol, dtype=float) * factor
        return attrs.evolve(self, rtol=self.rtol * factor, atol=atol)

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

    def _integrate_impl(self, rhs, t0, t1, y0, grid, jac) -> Run:
        y0 = y0.astype(float)
        options: dict[str, Any] = {"rtol": self.rtol, "atol": self._atol(y0)}
        if self.method in _IMPLICIT:
            if jac is None and isinstance(rhs, SymbolicRHS):
                jac = rhs.jacobian
            if jac is not None:
                options["jac"] = lambda t, y: jac(y)
        import scipy.integrate  # here, not at import time: see the module's docstring

        solver_class = getattr(scipy.integrate, self.method)
        solver = solver_class(lambda t, y: rhs(y), t0, y0, t1, **options)

        ts: list[float] = []
        ys: list[np.ndarray] = []
        pending = list(grid)
        i = 0
        while i < len(pending) and pending[i] <= t0:
            ts.append(t0)
            ys.append(y0.copy())
            i += 1
        status, message, n_steps = TrajectoryStatus.SUCCESS, None, 0
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
        return Run(
            t=ts,
            states=ys,
            t_reached=float(solver.t),
            nfev=int(solver.nfev),
            status=status,
            message=message,
        )
