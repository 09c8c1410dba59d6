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


def _vectorized(problem, grid, indices, order: int, names):
    """A whole chunk from one symbolic solution, evaluated on arrays (None: not applicable).

    Applies when the problem takes the default path from its values to its solution — the
    solution is its system's, symbolic in the parameters, the state the quasilinear one — so
    that every point differs only in the numbers put in. Each swept value still passes the
    parameter's own check.
    """
    cls = type(problem)
    base = _problem_base(cls)
    if base is None or problem.system().excitation is not None or problem.family is not None:
        return None
    for method in ("solve", "state", "period", "symbol_values", "parameter_value", "epsilon",
                   "check_values", "with_parameters", "state_names"):  # fmt: skip
        if getattr(cls, method) is not getattr(base, method):
            return None
    system = problem.system()
    symbols = {p.name for p in system.parameters}
    if any(name not in symbols and name != "eps" for name in grid.names):
        return None
    specs = {spec.name: spec for spec in cls.parameter_specs}
    where = np.unravel_index(np.asarray(indices, dtype=np.int64), grid.shape)
    refused = {}  # (axis, value index) -> the parameter's own message
    for axis, position in zip(grid.axes, where, strict=True):
        for k in np.unique(position):
            try:
                specs[axis.name].validate(axis.values[k])
            except ValueError as exc:
                refused[axis.name, int(k)] = f"{type(exc).__name__}: {exc}"
    reasons, ok = [], np.ones(len(indices), dtype=bool)
    for j in range(len(indices)):
        why = next(
            (refused[a.name, int(pos[j])] for a, pos in zip(grid.axes, where, strict=True)
             if (a.name, int(pos[j])) in refused),
            "",
        )  # fmt: skip
        reasons.append(why)
        ok[j] = not why
    columns = {q: np.full(len(indices), np.nan) for q in (*QUANTITIES, *names)}
    columns["status"][:] = FAILED
    if not ok.any():
        return columns, reasons
    solution = problem.solve(order)
    if not solution.success:
        return None
    fixed = dict(problem.values)
    swept = {a.name: np.asarray(a.values)[pos][ok] for a, pos in zip(grid.axes, where, strict=True)}
    count = int(ok.sum())
    values = {
        name: swept[name] if name in swept else np.full(count, float(fixed[name]))
        for name in symbols
        if name in fixed or name in swept
    }
    eps = swept["eps"] if "eps" in swept else np.full(count, float(fixed["eps"]))
    parameter = 1.0 / eps if system.regime.value == "large" else eps
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        omega, cos, sin = solution.coefficients(parameter, values)
    harmonics = np.arange(cos.shape[1])
    phases = np.linspace(0.0, 2 * np.pi, AMPLITUDE_SAMPLES, endpoint=False)
    c, sn = np.cos(np.outer(harmonics, phases)), np.sin(np.outer(harmonics, phases))
    x = np.einsum("ihp,hs->isp", cos, c) + np.einsum("ihp,hs->isp", sin, sn)
    dx = np.einsum("ihp,hs->isp", sin * harmonics[:, None], c) - np.einsum(
        "ihp,hs->isp", cos * harmonics[:, None], sn
    )
    amplitude = np.concatenate((np.max(np.abs(x), axis=1), np.max(np.abs(dx), axis=1) * omega))
    good = np.flatnonzero(ok)
    columns["status"][good] = OK
    columns["epsilon"][good] = eps
    columns["period"][good] = 2 * np.pi / omega
    columns["frequency"][good] = omega
    for k, name in enumerate(names):
        columns[name][good] = amplitude[k]
    return columns, reasons


def _problem_base(cls):
    """The Problem base class in ``cls``'s hierarchy (None if it is not a Problem)."""
    for klass in cls.__mro__:
        if klass.__name__ == "Problem" and klass.__module__ == "problems.base":
            return klass
    return None


def evaluate_chunk(problem, grid, indices, order: int, validate: bool, names, options=None):
    """The quantities at the flat ``indices`` of ``grid`` (run on a worker).

    Evaluation-only chunks of a problem on the default path are computed at once on arrays
    (:func:`_vectorized`); every other point one by one.

    Returns
    -------
    (indices, dict of arrays, list of reasons)
    """
    options = dict(options or {})
    if not validate:
        fast = _vectorized(problem, grid, indices, order, names)
        if fast is not None:
            columns, reasons = fast
            return np.asarray(indices, dtype=np.int64), columns, reasons
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
