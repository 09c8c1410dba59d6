"""What a worker computes for a chunk of grid points (picklable, run on Dask workers).

Each point is the problem re-created with the point's values (its own parameter checks apply:
a point it refuses is recorded with the reason, the sweep goes on). The analytic solution is
derived once per worker process and order wherever the problem allows it: symbolically in its
parameters (``solve(order, symbolic=True)`` for the rigid bodies; any problem whose parameters
are symbols of its system shares one solution through its class cache), then evaluated at every
point. With ``validate`` each point is also shot and judged by :func:`perturb.validation.validate`
— the same numbers as ``perturb validate`` at that point.
"""

from __future__ import annotations

import inspect
import math
import warnings

import numpy as np

from perturb.errors import PerturbError

__all__ = ["QUANTITIES", "VALIDATION_QUANTITIES", "evaluate_chunk", "verdict_codes"]

#: Samples per period of the amplitudes (the largest |state| over one period).
AMPLITUDE_SAMPLES = 64
#: Per point, always: the status (0 computed, 1 refused or failed: see ``reason``), ε, the
#: period and frequency of the analytic solution.
QUANTITIES = ("status", "epsilon", "period", "frequency")
#: With ``validate``: the verdict's code, its measurements, and the true orbit's largest
#: |Floquet multiplier| (excluding the trivial ones of a free orbit).
VALIDATION_QUANTITIES = (
    "verdict",
    "orbit_error",
    "period_error",
    "slope",
    "floquet_max",
    "resolution",
)
#: status codes
OK, FAILED = 0, 1


def verdict_codes() -> dict[int, str]:
    """``{code: meaning}`` of the ``verdict`` variable (the Verdict enum, in its order)."""
    from perturb.validation import Verdict

    return {i: f"{v.name}: {v.value}" for i, v in enumerate(Verdict)}


def _supports_symbolic(model) -> bool:
    try:
        return "symbolic" in inspect.signature(model.solve).parameters
    except (TypeError, ValueError):
        return False


def _symbolic_model(model):
    """The model with its solution derived symbolically in its parameters (shared by every point
    and by the ε scan of the order check), where the model offers that."""
    if not _supports_symbolic(model):
        return model
    from perturb.validation import Model

    class Symbolic(Model):
        def __init__(self, inner):
            self.inner = inner

        def __getattr__(self, name):  # anything else a report asks of the problem
            return getattr(self.inner, name)

        def solve(self, order=1):
            return self.inner.solve(order, symbolic=True)

        def with_epsilon(self, eps):
            other = self.inner.with_epsilon(eps)
            return None if other is None else Symbolic(other)

        def state_names(self):
            return self.inner.state_names()

        def state(self, solution, t):
            return self.inner.state(solution, t)

        def period(self, solution):
            return self.inner.period(solution)

        def epsilon(self):
            return self.inner.epsilon()

        def system(self):
            return self.inner.system()

        def symbol_values(self):
            return self.inner.symbol_values()

        def parameter_value(self):
            return self.inner.parameter_value()

        def label(self):
            return self.inner.label()

        def parameters_in_force(self):
            return self.inner.parameters_in_force()

        def method_options(self):
            return self.inner.method_options()

        def original_equations(self, y0=None):
            return self.inner.original_equations(y0)

        def integrals_of_motion(self, y0=None):
            return self.inner.integrals_of_motion(y0)

        def validity_estimates(self):
            return self.inner.validity_estimates()

        def true_orbit(self, solution):
            return self.inner.true_orbit(solution)

        def shooting_setup(self):
            return self.inner.shooting_setup()

        def euler_angles(self, solution, t):
            return self.inner.euler_angles(solution, t)

    return Symbolic(model)


def _point(problem, values: dict, order: int, validate: bool, names: tuple, options: dict):
    """Every quantity at one point: (dict of numbers, reason)."""
    out = {q: math.nan for q in (*QUANTITIES, *names)}
    if validate:
        out.update({q: math.nan for q in VALIDATION_QUANTITIES})
    out["status"] = FAILED
    try:
        model = _symbolic_model(problem.with_parameters(**values))
        out["epsilon"] = float(model.epsilon())
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            solution = model.solve(order)
            if not solution.success:
                return out, f"{solution.status.value}: {solution.message}"
            period = float(model.period(solution))
            t = np.linspace(0.0, period, AMPLITUDE_SAMPLES, endpoint=False)
            state = model.state(solution, t)
    except (PerturbError, ValueError, ArithmeticError) as exc:
        return out, f"{type(exc).__name__}: {exc}"
    out["period"] = period
    out["frequency"] = 2 * math.pi / period if period else math.nan
    for name in names:
        key = name[len("amplitude_") :]
        if key in state:
            out[name] = float(np.max(np.abs(np.asarray(state[key], dtype=float))))
    out["status"] = OK
    if not validate:
        return out, ""
    from perturb.validation import Verdict
    from perturb.validation import validate as judge

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            report = judge(model, order=order, **options)
    except (PerturbError, ValueError, ArithmeticError) as exc:
        out["status"] = FAILED
        return out, f"validation: {type(exc).__name__}: {exc}"
    out["verdict"] = list(Verdict).index(report.outcome)
    orbit = report.periodic_orbit
    if orbit is not None and orbit.success:
        out["orbit_error"] = float(orbit.orbit_error)
        out["period_error"] = float(orbit.period_error)
        out["resolution"] = float(orbit.resolution)
        floquet = sorted(orbit.floquet, key=lambda z: abs(z - 1))[orbit.n_trivial :]
        out["floquet_max"] = max((abs(z) for z in floquet), default=math.nan)
    if report.slope is not None:
        out["slope"] = float(report.slope.slope)
    return out, "" if report.completed else report.message


def evaluate_chunk(problem, grid, indices, order: int, validate: bool, names, options=None):
    """The quantities at the flat ``indices`` of ``grid`` (run on a worker).

    Returns
    -------
    (indices, dict of arrays, list of reasons)
    """
    options = dict(options or {})
    columns: dict[str, list] = {}
    reasons = []
    for flat in indices:
        values, reason = _point(problem, grid.point(int(flat)), order, validate, names, options)
        for key, value in values.items():
            columns.setdefault(key, []).append(value)
        reasons.append(reason)
    return (
        np.asarray(indices, dtype=np.int64),
        {k: np.asarray(v, dtype=float) for k, v in columns.items()},
        reasons,
    )
