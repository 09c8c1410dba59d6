"""The classical fixed-step Runge–Kutta method of order 4 (the seed paper's method), pure numpy."""

from __future__ import annotations

import attrs
import numpy as np
from attrs import frozen

from perturb._checks import check_count
from perturb._defaults import DEFAULT_RK4_STEPS_PER_UNIT
from perturb.errors import bad_value
from perturb.oracle.base import RHS, IntegratorBase, Run, TrajectoryStatus, check_positive

__all__ = ["RK4"]


def _rk4_step(rhs: RHS, y: np.ndarray, h: float) -> np.ndarray:
    # y_{k+1} = y_k + h/6 (k1 + 2 k2 + 2 k3 + k4), classical Runge-Kutta
    k1 = rhs(y)
    k2 = rhs(y + 0.5 * h * k1)
    k3 = rhs(y + 0.5 * h * k2)
    k4 = rhs(y + h * k3)
    return y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


@frozen
class RK4(IntegratorBase):
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
    error is :math:`O(h^4)`.  ``jac`` is ignored.

    Raises
    ------
    perturb.errors.InvalidParameterError
        If both options are given, or either is not positive.

    Examples
    --------
    >>> import numpy as np
    >>> def oscillator(y):  # x'' + x = 0 as a first-order system
    ...     return np.array([y[1], -y[0]])
    >>> from perturb.oracle import RK4
    >>> trajectory = RK4(steps_per_unit=100).integrate(oscillator, (0.0, np.pi), [1.0, 0.0])
    >>> trajectory.integrator
    'rk4 (100 steps/unit)'
    >>> bool(abs(trajectory.y[0, -1] + 1) < 1e-8)  # x(pi) = -1, error O(h^4)
    True
    """

    steps_per_unit: float | None = None
    n_steps: int | None = None

    def __attrs_post_init__(self):
        if self.steps_per_unit is not None and self.n_steps is not None:
            raise bad_value(
                "n_steps", self.n_steps, "give either `steps_per_unit` or `n_steps`, not both"
            )
        if self.steps_per_unit is not None:
            check_positive("steps_per_unit", self.steps_per_unit)
        if self.n_steps is not None:
            check_count("n_steps", self.n_steps)

    @property
    def name(self) -> str:
        """Description, e.g. ``"rk4 (200 steps/unit)"``."""
        if self.n_steps is not None:
            return f"rk4 ({self.n_steps} steps)"
        return f"rk4 ({self._steps_per_unit:g} steps/unit)"

    def loosened(self, factor: float) -> RK4:
        """A copy with steps ``factor**(1/4)`` times longer (the global error is :math:`O(h^4)`)."""
        stretch = factor**0.25
        if self.n_steps is not None:
            return attrs.evolve(self, n_steps=max(1, round(self.n_steps / stretch)))
        return attrs.evolve(self, steps_per_unit=self._steps_per_unit / stretch)

    @property
    def _steps_per_unit(self) -> float:
        return DEFAULT_RK4_STEPS_PER_UNIT if self.steps_per_unit is None else self.steps_per_unit

    def _integrate_impl(self, rhs, t0, t1, y0, grid, jac) -> Run:
        y = y0.astype(float)
        h = (t1 - t0) / self.n_steps if self.n_steps is not None else 1.0 / self._steps_per_unit
        nodes = np.unique(np.concatenate(([t0, t1], grid)))
        ts, ys, nfev = [], [], 0
        if grid[0] == t0:
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
                    return Run(
                        t=ts,
                        states=ys,
                        t_reached=a + k * hk,
                        nfev=nfev,
                        status=TrajectoryStatus.NON_FINITE,
                        message=f"The state became non-finite (step size {hk:.3g}); reduce the "
                        "step or check the rhs for a singularity.",
                    )
            t = b
            if t in grid:
                ts.append(t)
                ys.append(y.copy())
        return Run(t=ts, states=ys, t_reached=t, nfev=nfev)
