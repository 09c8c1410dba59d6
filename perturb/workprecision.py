"""Error against run time for a problem: the analytic solution beside the numerical integrators.

:func:`work_precision` measures, over the same horizon and output grid,

- the analytic solution at orders ``1..N``: its error against the true motion from its own initial
  state, with the *evaluation* cost (``problem.state`` on the grid) and the *derivation* cost (the
  symbolic construction) reported as separate rows;
- RK4 at several steps per unit time, the scipy methods at several tolerances and heyoka (JIT
  compilation excluded, done once before timing): their error against a reference run.

Each point is timed as a benchmark is: one untimed warm-up run first (imports, JIT compilation,
lambdified functions and caches built on first use belong to no point), then the best of
``repeat`` runs (the least disturbed by the rest of the machine), so a curve falls monotonically
where the method converges instead of its loosest point carrying every one-time cost.  The reference is heyoka in extended precision when available
(``long double``/``real128``), else DOP853 at ``REFERENCE_RTOL``.  The error is the maximum over the
output grid and the components of ``|y - y_ref| / amplitude`` (amplitude = max ``|y_ref|`` per component).

The problem is anything validation accepts (a :class:`perturb.validation.Model`: a registered
problem, a user's Problem subclass, or a bare system through :func:`perturb.validation.as_model`).
The command line is ``perturb work-precision``; the tables are written by
:mod:`perturb.report.workprecision`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence

import numpy as np
from attrs import frozen

from perturb._defaults import (
    DEFAULT_REPEAT,
    MAX_ORDER,
    REFERENCE_RTOL,
    RK4_STEPS,
    SCIPY_TOLERANCES,
)
from perturb.cache import bypassed
from perturb.errors import bad_value
from perturb.oracle import RK4, Heyoka, Scipy, choose, heyoka_available
from perturb.progress import track
from perturb.validation import (
    AMPLITUDE_FLOOR,
    MAX_OUTPUT_SAMPLES,
    SAMPLES_PER_PERIOD,
    as_model,
)
from perturb.validation.capabilities import label_of
from perturb.validation.truth import original_equations

__all__ = ["WorkPoint", "WorkPrecision", "work_precision"]


#: The scipy methods compared (the explicit high-order one, the default one, two stiff ones).
SCIPY_METHODS = ("DOP853", "RK45", "Radau", "LSODA")


@frozen
class WorkPoint:
    """One row of the work–precision table.

    Attributes
    ----------
    method : str
        ``"analytic"``, ``"analytic derivation"``, ``"rk4"``, ``"scipy DOP853"``, ``"heyoka"``...
    setting : str
        ``"order 2"``, ``"80 steps/unit"``, ``"rtol=1e-10"``, ``"tol=eps"``.
    error : float
        Max relative error over the grid (NaN for the derivation rows and failed runs).
    seconds : float
        Best wall time of the timed runs, after one untimed warm-up run.

    Examples
    --------
    >>> from perturb.workprecision import WorkPoint
    >>> point = WorkPoint("scipy DOP853", "rtol=1e-10", 2.1e-10, 0.05)
    >>> point.method, point.error
    ('scipy DOP853', 2.1e-10)
    """

    method: str
    setting: str
    error: float
    seconds: float


@frozen
class WorkPrecision:
    """The table of :func:`work_precision` and how it was measured.

    Attributes
    ----------
    problem : str
    periods : float
    horizon : float
    reference : str
        The integrator of the reference runs.
    points : tuple of WorkPoint

    Examples
    --------
    >>> from perturb.workprecision import WorkPoint, WorkPrecision
    >>> result = WorkPrecision("duffing", 10, 60.6, "heyoka", (WorkPoint("rk4", "10 steps/unit", 2.5e-5, 0.09),))
    >>> [p.setting for p in result.points]
    ['10 steps/unit']
    """

    problem: str
    periods: float
    horizon: float
    reference: str
    points: tuple


def _best_time(fn: Callable[[], object], repeat: int):
    """The best of ``repeat`` timed calls of ``fn`` after one untimed warm-up call, and a result."""
    result = fn()  # warm-up: one-time costs (imports, compilation, first-use caches), not timed
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return min(times), result


def _relative_error(y: np.ndarray, ref: np.ndarray) -> float:
    if y.shape != ref.shape or not np.all(np.isfinite(y)):
        return math.nan
    amp = np.max(np.abs(ref), axis=1)
    amp = np.maximum(amp, AMPLITUDE_FLOOR * max(float(np.max(amp)), 1e-300))
    return float(np.max(np.abs(y - ref) / amp[:, None]))


def _derivation_seconds(model, order: int) -> float:
    """Time of the symbolic construction with the disk cache bypassed (a problem's own in-memory
    caches of intermediate objects, such as the rigid body's reduction, still count as built)."""
    start = time.perf_counter()
    with bypassed():
        model.solve(order)
    return time.perf_counter() - start


def work_precision(
    problem,
    *,
    periods: float = 10,
    orders: int | Sequence[int] = 3,
    rk4_steps: Sequence[float] = RK4_STEPS,
    scipy_methods: Sequence[str] = SCIPY_METHODS,
    tolerances: Sequence[float] = SCIPY_TOLERANCES,
    heyoka: bool = True,
    repeat: int = DEFAULT_REPEAT,
    samples_per_period: int = SAMPLES_PER_PERIOD,
) -> WorkPrecision:
    """Error against wall time of the analytic solution and of the integrators.

    Parameters
    ----------
    problem : perturb.validation.Model
        A problem (``get_problem(name).create(...)``, a user's Problem subclass) or any Model.
    periods : float, optional
        Horizon in periods of the order-1 analytic solution (> 0).
    orders : int or sequence of int, optional
        Orders of the analytic solution: ``N`` means ``1..N``, at most the engine's highest.
        Orders whose construction the problem refuses are skipped.
    rk4_steps : sequence of float, optional
        RK4 steps per unit time.
    scipy_methods, tolerances : sequences, optional
        scipy methods and their relative tolerances (every pair is run).
    heyoka : bool, optional
        Include heyoka (machine-precision Taylor) if installed and the equations are symbolic.
    repeat : int, optional
        Timed runs per point after one untimed warm-up; the best time is reported.
    samples_per_period : int, optional
        Output points per period of the error measurement.

    Returns
    -------
    WorkPrecision
        Data only: :mod:`perturb.report.workprecision` writes it as CSV (``method,setting,error,
        seconds``), JSON or a text table; :func:`perturb.report.plots.plot_work_precision` draws it.

    Raises
    ------
    perturb.errors.InvalidParameterError
        For ``periods <= 0``, ``repeat < 1``, a non-positive tolerance or step count, or an order
        < 1 or past the engine's highest (12: never cut in silence).
    perturb.SolutionFailed
        The order-1 period is not a positive number (the series outside its domain gives no
        horizon).

    Examples
    --------
    A small run (one analytic order, two RK4 step sizes, no scipy or heyoka):

    >>> from perturb.workprecision import work_precision
    >>> from problems import get_problem
    >>> result = work_precision(get_problem("duffing").create(eps=0.1), periods=2, orders=1,
    ...                         rk4_steps=(10, 20), scipy_methods=(), heyoka=False, repeat=1)
    >>> [(p.method, p.setting) for p in result.points]
    [('analytic', 'order 1'), ('analytic derivation', 'order 1'), ('rk4', '10 steps/unit'), ('rk4', '20 steps/unit')]
    >>> coarse, fine = (p.error for p in result.points if p.method == "rk4")
    >>> bool(fine < coarse)  # the finer step is the more accurate
    True
    """
    if not (isinstance(periods, int | float) and math.isfinite(periods) and periods > 0):
        raise bad_value("periods", periods, "pass a positive number of periods")
    if periods * samples_per_period > MAX_OUTPUT_SAMPLES:
        raise bad_value(
            "periods",
            periods,
            f"at most {MAX_OUTPUT_SAMPLES // samples_per_period} periods at "
            f"{samples_per_period} samples per period",
        )
    if not isinstance(repeat, int) or repeat < 1:
        raise bad_value("repeat", repeat, "pass an integer >= 1")
    for tol in tolerances:
        if not (isinstance(tol, int | float) and math.isfinite(tol) and tol > 0):
            raise bad_value("tolerances", tol, "every tolerance must be a positive number")
    for steps in rk4_steps:
        if not (isinstance(steps, int | float) and math.isfinite(steps) and steps > 0):
            raise bad_value("rk4_steps", steps, "every step count must be positive")
    order_list = list(range(1, orders + 1)) if isinstance(orders, int) else list(orders)
    if not order_list or any(not isinstance(k, int) or k < 1 for k in order_list):
        raise bad_value("orders", orders, "pass N >= 1 or a list of integers >= 1")
    if max(order_list) > MAX_ORDER:  # never cut to the engine's highest order in silence
        raise bad_value("orders", orders, f"the engine's highest order is {MAX_ORDER}")

    problem = as_model(problem)
    names = tuple(problem.state_names())
    base = problem.solve(1)
    period = problem.period(base)
    if not (math.isfinite(period) and period > 0):
        from perturb.solution import SolutionFailed

        raise SolutionFailed(
            f"the order-1 period is {period:g}, not a positive number: the series is outside "
            "its domain at these parameters and gives no horizon"
        )
    n_out = int(math.ceil(periods * samples_per_period)) + 1
    horizon = periods * period
    t = np.linspace(0.0, horizon, n_out)
    y0 = np.array([np.asarray(problem.state(base, 0.0)[n], dtype=float) for n in names])
    original = original_equations(problem, y0)
    symbolic = original.symbolic and heyoka_available()
    reference = (
        Heyoka(high_precision=True) if symbolic else choose(rtol=REFERENCE_RTOL, symbolic=False)
    )
    references: dict[bytes, np.ndarray] = {}

    def truth(start: np.ndarray) -> np.ndarray:
        key = start.tobytes()
        if key not in references:
            traj = reference.integrate(original.rhs, (0.0, horizon), start, t_eval=t)
            traj.raise_for_status()
            references[key] = np.asarray(traj.y, dtype=float)
        return references[key]

    points: list[WorkPoint] = []
    for k in track(order_list, label="work-precision: analytic orders"):
        try:
            derive = _derivation_seconds(problem, k)
            solution = problem.solve(k)
        except ValueError:
            continue
        if not solution.success:
            continue
        seconds, state = _best_time(lambda s=solution: problem.state(s, t), repeat)
        y = np.array([np.asarray(state[n], dtype=float) for n in names])
        error = _relative_error(y, truth(y[:, 0].copy()))
        points.append(WorkPoint("analytic", f"order {k}", error, seconds))
        points.append(WorkPoint("analytic derivation", f"order {k}", math.nan, derive))

    ref = truth(y0)
    runs: list[tuple[str, str, object]] = []
    runs += [("rk4", f"{s:g} steps/unit", RK4(steps_per_unit=s)) for s in rk4_steps]
    runs += [
        (f"scipy {m}", f"rtol={tol:g}", Scipy(m, rtol=tol))
        for m in scipy_methods
        for tol in tolerances
    ]
    if heyoka and symbolic:
        hy = Heyoka()
        hy.integrate(original.rhs, (0.0, min(horizon, period)), y0)  # JIT compile, not timed
        runs.append(("heyoka", "tol=eps", hy))
    for method, setting, integrator in track(runs, label="work-precision: integrators"):
        seconds, traj = _best_time(
            lambda i=integrator: i.integrate(original.rhs, (0.0, horizon), y0, t_eval=t), repeat
        )
        error = _relative_error(np.asarray(traj.y, dtype=float), ref) if traj.success else math.nan
        points.append(WorkPoint(method, setting, error, seconds))
    return WorkPrecision(
        problem=label_of(problem),
        periods=float(periods),
        horizon=horizon,
        reference=reference.name,
        points=tuple(points),
    )
