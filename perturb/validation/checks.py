"""The measurements of a validation, each on its own: trajectory error, integral drift, stiffness,
the one-period error along an ε scan and its slope."""

from __future__ import annotations

import math

import numpy as np

from perturb._defaults import (
    ERROR_FLOOR,
    SAMPLES_PER_PERIOD,
    SLOPE_TOLERANCE,
    STIFFNESS_THRESHOLD,
)
from perturb.errors import InvalidSystemError, PerturbError, defined_at
from perturb.oracle import SymbolicRHS, finite_difference_jacobian
from perturb.validation.model import Integrals, Model
from perturb.validation.report import InvariantDrift, SlopeFit, Stiffness
from perturb.validation.setup import amplitudes, integrator_for
from perturb.validation.truth import original_equations

__all__ = [
    "analytic_states",
    "component_errors",
    "fit_slope",
    "invariant_drift",
    "one_period_error",
    "stiffness_indicator",
]


def analytic_states(model: Model, solution, t) -> np.ndarray:
    """The analytic state at times ``t``, shape ``(n, len(t))``, in ``model.state_names()`` order."""
    state = model.state(solution, t)
    return np.array([np.asarray(state[name], dtype=float) for name in model.state_names()])


def component_errors(names, analytic: np.ndarray, numeric: np.ndarray):
    """(per-component dict, max absolute error, max error relative to each component's amplitude)."""
    amp = amplitudes(numeric)
    diff = np.abs(analytic - numeric)
    abs_err = np.max(diff, axis=1) if diff.shape[1] else np.full(len(names), np.nan)
    rel = abs_err / amp
    components = {
        name: {"abs": float(abs_err[i]), "relative": float(rel[i]), "amplitude": float(amp[i])}
        for i, name in enumerate(names)
    }
    return components, float(np.max(abs_err)), float(np.max(rel))


def stiffness_indicator(rhs, points: np.ndarray, period: float) -> Stiffness:
    """Stiffness ratio from Jacobian eigenvalues at ``points`` (shape ``(n, m)``).

    Parameters
    ----------
    rhs : callable or SymbolicRHS
    points : ndarray, shape (n, m)
        States at which the Jacobian is evaluated.
    period : float
        Period of the motion; ``2π/period`` is the floor of the oscillation rate.

    Returns
    -------
    Stiffness

    Examples
    --------
    The harmonic oscillator's eigenvalues are ±i: not stiff.

    >>> import numpy as np
    >>> from perturb.validation import stiffness_indicator
    >>> points = np.array([[1.0, 0.0, -1.0], [0.0, 1.0, 0.0]])  # three states, as columns
    >>> indicator = stiffness_indicator(lambda y: np.array([y[1], -y[0]]), points, 2 * np.pi)
    >>> indicator.stiff, round(indicator.max_real, 6), round(indicator.max_imag, 6)  # finite differences
    (False, 0.0, 1.0)
    """
    max_real, max_imag = 0.0, 0.0
    for y in np.asarray(points, dtype=float).T:
        if not np.all(np.isfinite(y)):
            continue
        jac = (
            rhs.jacobian(y) if isinstance(rhs, SymbolicRHS) else finite_difference_jacobian(rhs, y)
        )
        if not np.all(np.isfinite(jac)):
            continue
        eig = np.linalg.eigvals(jac)
        max_real = max(max_real, float(np.max(np.abs(eig.real))))
        max_imag = max(max_imag, float(np.max(np.abs(eig.imag))))
    floor = 2 * math.pi / period if period > 0 and math.isfinite(period) else 1.0
    ratio = max_real / max(max_imag, floor)
    return Stiffness(
        ratio=ratio,
        max_real=max_real,
        max_imag=max_imag,
        stiff=ratio > STIFFNESS_THRESHOLD,
        threshold=STIFFNESS_THRESHOLD,
    )


def invariant_drift(integrals: Integrals | None, y: np.ndarray) -> dict[str, InvariantDrift]:
    """Drift of each first integral along the states ``y`` (shape ``(n, m)``)."""
    if integrals is None or y.shape[1] == 0:
        return {}
    values = np.atleast_2d(np.asarray(integrals.function(y), dtype=float))
    if values.shape[-1] != y.shape[1]:  # a function of one state only: apply column by column
        values = np.array([np.asarray(integrals.function(col), dtype=float) for col in y.T]).T
    values = np.atleast_2d(values)
    where = defined_at(integrals.function)
    if values.ndim != 2 or values.shape[1] != y.shape[1]:
        raise InvalidSystemError(
            f"{where}: the function of integrals_of_motion gives values of shape "
            f"{np.shape(integrals.function(y[:, 0]))} for one state of shape ({y.shape[0]},): "
            "return one number per integral for a state (a 1-D array), or one row per integral "
            "for states side by side"
        )
    if integrals.names and len(integrals.names) != values.shape[0]:
        raise InvalidSystemError(
            f"{where}: integrals_of_motion gives {len(integrals.names)} names "
            f"{list(integrals.names)} for {values.shape[0]} integral"
            f"{'s' if values.shape[0] != 1 else ''}: give one name per integral"
        )
    names = integrals.names or tuple(f"I{i}" for i in range(values.shape[0]))
    out = {}
    for name, row in zip(names, values, strict=False):
        drift = np.abs(row - row[0])
        size = abs(row[0]) if row[0] != 0 else 1.0
        out[name] = InvariantDrift(
            name=name,
            initial=row[0],
            max_drift=float(np.max(drift)),
            relative_drift=float(np.max(drift)) / size,
            final_drift=float(drift[-1]),
        )
    return out


def one_period_error(
    model: Model, order: int, integrator, rtol: float, stiff: bool, max_steps: int | None
) -> float:
    """Max relative error of the analytic solution over one period from its initial state (NaN
    when the point cannot be measured: failed construction, unusable period, failed integration)."""
    try:
        solution = model.solve(order)
    except PerturbError:
        return math.nan
    if not solution.success:
        return math.nan
    with np.errstate(all="ignore"):
        period = float(model.period(solution))
        if not (math.isfinite(period) and period > 0):
            return math.nan
        t = np.linspace(0.0, period, SAMPLES_PER_PERIOD + 1)
        analytic = analytic_states(model, solution, t)
    if not np.all(np.isfinite(analytic)):
        return math.nan
    equations = original_equations(model, analytic[:, 0])
    solver = integrator_for(integrator, rtol, stiff, equations.symbolic, max_steps)
    traj = solver.integrate(equations.rhs, (0.0, period), analytic[:, 0], t_eval=t)
    if not traj.success:
        return math.nan
    return component_errors(model.state_names(), analytic, np.asarray(traj.y, dtype=float))[2]


def fit_slope(epsilons, errors, order: int) -> SlopeFit:
    """Slope of log(error) against log|ε| (the order check); works for either sign of ε.

    Points at the oracle's floor (:data:`ERROR_FLOOR`) are dropped.  When every measured point is
    at the floor the error is indistinguishable from zero: the check is consistent without a slope.
    """
    eps = np.asarray(epsilons, dtype=float)
    err = np.asarray(errors, dtype=float)
    finite = np.isfinite(err)
    usable = finite & (err > ERROR_FLOOR) & (eps != 0)
    notes = []
    expected = order + 1.0
    at_floor = finite & (err <= ERROR_FLOOR)
    if np.any(at_floor):
        notes.append(f"points with error <= {ERROR_FLOOR:g} (oracle accuracy) dropped")
    if np.any(~finite):
        notes.append(f"{int(np.sum(~finite))} point(s) could not be measured (NaN)")
    if usable.sum() < 2:
        if np.all(finite) and np.any(at_floor):
            notes.append("the error is at the oracle's floor: no power law is contradicted")
            return SlopeFit(math.nan, expected, eps, err, True, "; ".join(notes), SLOPE_TOLERANCE)
        notes.append("fewer than two usable points: slope not measured")
        return SlopeFit(math.nan, expected, eps, err, None, "; ".join(notes), SLOPE_TOLERANCE)
    with np.errstate(all="ignore"):
        slope = float(np.polyfit(np.log(np.abs(eps[usable])), np.log(err[usable]), 1)[0])
    if not math.isfinite(slope):
        notes.append("the fit did not give a finite slope")
        return SlopeFit(math.nan, expected, eps, err, None, "; ".join(notes), SLOPE_TOLERANCE)
    return SlopeFit(
        slope,
        expected,
        eps,
        err,
        slope >= expected - SLOPE_TOLERANCE,
        "; ".join(notes),
        SLOPE_TOLERANCE,
    )
