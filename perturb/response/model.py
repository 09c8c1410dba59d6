"""A problem's frequency response over one of its own parameters: ``perturb response``.

:func:`problem_response` sweeps a user-facing parameter (the excitation frequency ``Omega``, a
forcing level, the detuning ``sigma``…) of a driven problem. The amplitude equations are derived
once for the problem's symbolic system; at each grid value the problem is re-created (its
parameter checks apply) and every branch is found at its values (:func:`branches_at`). The folds
come exactly from the first-order equations in the system's parameter the swept one moves (σ for
Ω: :math:`\\Omega = (p/q)\\omega + \\varepsilon\\sigma`), mapped back to the swept one. The
backbone is the free engine's frequency of the unforced, undamped system, if the problem gives one
(``backbone_system``). With ``validate`` > 0 the true orbit is shot at that many points of every
branch (:func:`perturb.validation.validate` ingredients: forced shooting, Floquet multipliers).

The problem is duck-typed: ``system()``, ``symbol_values()``, ``epsilon()``, ``name`` and
``with_parameters(**values)`` (a :class:`problems.base.Problem` has them all).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb.errors import InvalidParameterError, bad_value
from perturb.method.driven import amplitude_equations
from perturb.progress import track
from perturb.response.branches import branch_names, branches_at, exact_number
from perturb.response.curve import (
    Fold,
    FrequencyResponse,
    ResponsePoint,
    _folds,
    continue_fold,
)
from perturb.response.domain import branch_domains

__all__ = ["Backbone", "ProblemResponse", "TrueResponse", "problem_response"]

#: Amplitudes of the backbone, as fractions of the largest response amplitude found (the
#: backbone is drawn through the region the response occupies).
BACKBONE_SAMPLES = 41


@frozen
class Backbone:
    """The free, undamped system's frequency against its amplitude (the response's spine).

    Attributes
    ----------
    coordinate : str
    amplitudes : tuple of float
    values : tuple of float
        The swept parameter's value at which the forced system resonates with the free motion of
        that amplitude.
    """

    coordinate: str
    amplitudes: tuple = field(converter=tuple)
    values: tuple = field(converter=tuple)


@frozen
class TrueResponse:
    """The true periodic orbit shot at one response point."""

    value: float
    branch: str
    success: bool
    amplitude: float
    amplitude_error: float
    floquet_max: float
    stable_true: bool | None
    stable_analytic: bool | None
    message: str


@frozen
class ProblemResponse:
    """A problem's frequency response (the data of ``perturb response``).

    Attributes
    ----------
    problem : str
    parameter : str
    response : FrequencyResponse
        Points and folds, in the swept parameter's values.
    branches : tuple of tuple of str
        The branch names at each point (``lower``/``middle``/``upper``…), aligned with
        ``response.points``.
    backbone : Backbone or None
    true : tuple of TrueResponse
        The shot points (empty unless asked).
    outside : tuple of str
        Aligned with ``response.points``: ``""`` where the point's series is inside its domain,
        else why not (``perturb solve``'s check, :mod:`perturb.response.domain`).
    beyond : tuple of str
        Aligned with ``response.points``: ``""``, or why the point is beyond the series'
        estimated validity.
    """

    problem: str
    parameter: str
    response: FrequencyResponse
    branches: tuple = field(converter=tuple)
    backbone: Backbone | None = None
    true: tuple = field(converter=tuple, factory=tuple)
    outside: tuple = field(converter=tuple, factory=tuple)
    beyond: tuple = field(converter=tuple, factory=tuple)


def parse_sweep(text: str, argument: str = "--sweep") -> tuple[str, np.ndarray]:
    """``NAME=START:STOP:N`` (finite bounds, START < STOP, 2 <= N <= ``MAX_TIMES``) as
    ``(name, values)``: the sweep of ``perturb response --sweep`` and of a scene's ``[response]``.

    Raises
    ------
    InvalidParameterError
        One line naming ``argument``, the text and the fix.

    Examples
    --------
    >>> name, values = parse_sweep("Omega=0.9:1.1:3")
    >>> name, values.tolist()
    ('Omega', [0.9, 1.0, 1.1])
    """
    from perturb._defaults import MAX_TIMES

    name, sep, spec = str(text).partition("=")
    parts = spec.split(":")

    def fail(fix: str) -> InvalidParameterError:
        return InvalidParameterError(f"{argument} {text!r}: {fix}")

    if not sep or not name.strip() or len(parts) != 3:
        raise fail(f"write NAME=START:STOP:N, e.g. {argument} Omega=0.9:1.2:61")
    try:
        start, stop = float(parts[0]), float(parts[1])
        count = int(parts[2])
    except ValueError:
        raise fail("START and STOP must be numbers and N a whole number") from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise fail("START and STOP must be finite")
    if not 2 <= count <= MAX_TIMES:
        raise fail(f"N = {count} must be between 2 and {MAX_TIMES}")
    if not start < stop:
        raise fail("START must be below STOP (bounds reversed?)")
    return name.strip(), np.linspace(start, stop, count)


def _check_grid(parameter: str, grid) -> np.ndarray:
    grid = np.asarray(grid, dtype=float)
    if grid.ndim != 1 or grid.size < 2:
        raise bad_value(
            "grid", grid.tolist(), "give at least 2 values (START:STOP:N with N >= 2)",
            InvalidParameterError,
        )  # fmt: skip
    if not np.all(np.isfinite(grid)):
        raise bad_value("grid", grid.tolist(), "give finite values", InvalidParameterError)
    if not np.all(np.diff(grid) > 0):
        raise bad_value(
            "grid", f"{parameter}={grid[0]:g}:{grid[-1]:g}",
            "give increasing values (START < STOP)", InvalidParameterError,
        )  # fmt: skip
    return grid


def check_request(problem, parameter: str):
    """The driven ``problem``'s system, once ``parameter`` is known to be one of its parameters.

    Raises
    ------
    InvalidParameterError
        A problem that is not driven, or an unknown parameter (the closest is suggested).
    """
    system = problem.system()
    if system.excitation is None:
        raise bad_value(
            "problem", problem.name,
            "it is not driven (its system has no excitation): the frequency response is for "
            "forced, damped or parametrically excited systems; use `perturb solve`",
            InvalidParameterError,
        )  # fmt: skip
    if parameter not in problem.values:
        from difflib import get_close_matches

        close = get_close_matches(parameter, list(problem.values), n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise bad_value(
            "sweep", parameter,
            f"it is not a parameter of {problem.name}: choose from {sorted(problem.values)}{hint}",
            InvalidParameterError,
        )  # fmt: skip
    return system


def problem_response(
    problem, parameter: str, grid: Sequence[float], order: int = 1, validate: int = 0
) -> ProblemResponse:
    """The frequency response of a driven ``problem`` over ``grid`` values of ``parameter``.

    Parameters
    ----------
    problem
        A driven problem (see the module notes).
    parameter : str
        One of the problem's parameters.
    grid : sequence of float
        At least two increasing values.
    order : int
        The state's order (>= 1).
    validate : int
        Shoot the true orbit at this many points of each branch (0: none).

    Returns
    -------
    ProblemResponse

    Raises
    ------
    InvalidParameterError
        A problem that is not driven, an unknown parameter, a grid of fewer than 2 increasing
        finite values, or invalid parameter values at a grid point.
    """
    system = check_request(problem, parameter)
    grid = _check_grid(parameter, grid)
    equations = amplitude_equations(system, order)
    points, names, failures, variants, flags = [], [], [], [], []
    for value in track(grid, label=f"response {problem.name}"):
        variant = problem.with_parameters(**{parameter: float(value)})
        variants.append(variant)
        found, why = branches_at(equations, variant.symbol_values(), variant.epsilon(), order)
        if why:
            failures.append(f"{parameter} = {value:g}: {why}")
        names.extend(branch_names(found))
        points.extend(ResponsePoint.of(float(value), branch) for branch in found)
        flags.extend(branch_domains(equations, found, variant))
    folds = _problem_folds(equations, problem, parameter, variants, grid)
    response = FrequencyResponse(
        system=problem.name,
        parameter=parameter,
        order=order,
        epsilon=float(problem.epsilon()),
        values={k: float(v) for k, v in problem.values.items() if k != parameter},
        grid=tuple(float(g) for g in grid),
        points=tuple(points),
        folds=tuple(folds),
        failures=tuple(failures),
        coordinates=equations.coordinates,
    )
    backbone = _backbone(problem, parameter, variants, grid, points, order)
    true = _shoot(problem, parameter, response, names, order, validate) if validate else ()
    return ProblemResponse(
        problem.name, parameter, response, names, backbone, true,
        outside=[f[0] for f in flags], beyond=[f[1] for f in flags],
    )  # fmt: skip


def _problem_folds(equations, problem, parameter, variants, grid) -> list[Fold]:
    """Folds in the system's parameter that ``parameter`` moves (linearly), mapped back."""
    first, last = variants[0].symbol_values(), variants[-1].symbol_values()
    moved = [k for k in first if first[k] != last[k]]
    if len(moved) != 1:
        return []
    name = moved[0]
    (symbol,) = [p for p in equations.system.parameters if p.name == name]
    a, b = float(grid[0]), float(grid[-1])
    s0, s1 = first[name], last[name]
    slope = (s1 - s0) / (b - a)
    middle = variants[len(variants) // 2].symbol_values()[name]
    mid_value = float(grid[len(grid) // 2])
    if not math.isclose(middle, s0 + slope * (mid_value - a), rel_tol=1e-9, abs_tol=1e-12):
        return []  # not a linear map: no exact folds in the swept parameter
    fixed = {
        p: exact_number(first[p.name])
        for p in equations.system.parameters
        if p.name in first and p.name != name
    }
    rows = [sp.expand(e.xreplace(fixed)) for e in equations.displacement(0)]
    low, high = sorted((s0, s1))
    out = []
    eps = float(problem.epsilon())
    for fold in _folds(rows, list(equations.amplitudes), symbol, low, high, equations):
        fold = continue_fold(fold, equations, equations.order, fixed, symbol, eps)

        def back(value):
            return a + (value - s0) / slope if slope else a

        out.append(
            Fold(back(fold.value), fold.amplitudes, fold.norms, back(fold.first_order), fold.note)
        )
    return sorted(out, key=lambda f: f.value)


def _backbone(problem, parameter, variants, grid, points, order) -> Backbone | None:
    """The free engine's frequency of the problem's unforced, undamped system, if it has one."""
    import attrs

    make = getattr(problem, "backbone_system", None)
    built = make(parameter) if make is not None and points else None
    if built is None:
        return None
    free_system, coordinate, to_parameter = built
    from perturb.method.poincare import PoincareMethod

    amplitude = sp.Symbol("backbone_amplitude", positive=True)
    free_system = attrs.evolve(free_system, parameters=(*free_system.parameters, amplitude))
    method = PoincareMethod(order=max(order, 1), amplitudes={coordinate: amplitude})
    solution = method.solve(free_system)
    if not solution.success:
        return None
    top = max(p.norm(coordinate) for p in points)
    values = {k: v for k, v in problem.symbol_values().items()}
    eps = problem.epsilon()
    amplitudes = np.linspace(0.0, 1.05 * top, BACKBONE_SAMPLES)
    frequencies = [
        2 * math.pi / float(solution.period_at(eps, {**values, amplitude.name: float(a)}))
        for a in amplitudes
    ]
    return Backbone(coordinate, tuple(amplitudes), tuple(to_parameter(w) for w in frequencies))


def _shoot(problem, parameter, response, names, order, count) -> tuple[TrueResponse, ...]:
    """Shoot the true orbit at ``count`` points of each branch."""
    from perturb.validation import as_model, state_along
    from perturb.validation.forced import forced_orbit_check

    out = []
    shots = []
    for branch_name in sorted(set(names)):
        indices = [i for i, n in enumerate(names) if n == branch_name]
        spread = np.linspace(0, len(indices) - 1, min(count, len(indices)))
        shots += [(branch_name, i) for i in sorted({indices[round(j)] for j in spread})]
    for branch_name, i in track(shots, label=f"response {problem.name}: true orbits"):
        point = response.points[i]
        variant = problem.with_parameters(**{parameter: point.value})
        solution = variant.solve(order, family=branch_name)
        model = as_model(variant)
        period = float(model.period(solution))
        y0 = np.array(
            [float(v[0]) for v in state_along(solution, [0.0], variant.parameter_value(),
                                              variant.symbol_values()).values()]
        )  # fmt: skip
        equations = model.original_equations(y0)
        check = forced_orbit_check(model, solution, equations, y0, period, None, 1e-12, False)
        largest = max((abs(z) for z in check.floquet), default=math.nan)
        amplitude = point.norm()
        out.append(
            TrueResponse(
                value=point.value,
                branch=branch_name,
                success=check.success,
                amplitude=amplitude,
                amplitude_error=check.orbit_error,
                floquet_max=largest,
                stable_true=(largest < 1) if check.success else None,
                stable_analytic=point.stable,
                message=check.message,
            )
        )
    return tuple(out)
