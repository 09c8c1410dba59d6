"""A problem's frequency response over one of its own parameters: ``perturb response``.

:func:`problem_response` sweeps a user-facing parameter (the excitation frequency ``Omega``, a
forcing level, the detuning ``sigma``…) of a driven problem. The amplitude equations are derived
once for the problem's symbolic system, and every order-N branch is continued along the sweep
from the certified first-order census (:mod:`perturb.steady.continued`: its folds, branch
points and Neimark-Sacker points located on the order-N curves, its stability from the Floquet
multipliers along the order-N series). The backbone is the free engine's frequency of the
system's conservative, unforced part (:mod:`perturb.steady.backbone`). With ``validate`` > 0
the true orbit is shot at points of every branch chosen by arclength
(:mod:`perturb.response.truth`).

The problem gives ``case()`` (a :class:`perturb.case.Case`: every grid value is a point of it,
checked by the problem's own rules) and ``name`` (a :class:`problems.base.Problem` has both).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from attrs import field, frozen

from perturb._defaults import MAX_VALIDATE
from perturb.errors import InvalidParameterError, bad_value
from perturb.method.driven import amplitude_equations
from perturb.progress import stage
from perturb.steady.backbone import Backbone, backbone
from perturb.steady.curve import (
    FrequencyResponse,
)
from perturb.validation.capabilities import label_of

if TYPE_CHECKING:
    from perturb.oracle import PeriodicOrbit

__all__ = ["Backbone", "ProblemResponse", "TrueResponse", "problem_response"]


@frozen
class TrueResponse:
    """The true periodic orbit shot at one point of a continued response curve.

    ``amplitude`` is the analytic amplitude and ``true_amplitude`` the shot orbit's, both by
    ``measure`` (of the first resonant coordinate); ``amplitude_error`` the largest distance of
    the analytic orbit from the true one over a period, relative to the true amplitude;
    ``within_tol`` whether that is within the run's ``tol``; ``reason`` why the point was chosen
    (the largest amplitude, a side of a fold, an end, the arclength spread); ``orbit`` the true
    orbit shot (a :class:`~perturb.oracle.PeriodicOrbit`; None when the shooting failed), whose
    multipliers :attr:`multipliers_true` and :attr:`floquet_max` read; ``multipliers_analytic``
    the series' multipliers at the point.
    """

    value: float
    branch: str
    success: bool
    amplitude: float
    amplitude_error: float
    stable_true: bool | None
    stable_analytic: bool | None
    message: str
    true_amplitude: float = math.nan
    measure: str = "initial"
    within_tol: bool | None = None
    reason: str = ""
    multipliers_analytic: tuple = field(converter=tuple, factory=tuple)
    curve: int = -1
    orbit: PeriodicOrbit | None = None

    @property
    def multipliers_true(self) -> tuple:
        """The true orbit's Floquet multipliers (empty when the shooting failed)."""
        return () if self.orbit is None else tuple(complex(z) for z in self.orbit.multipliers)

    @property
    def floquet_max(self) -> float:
        """The largest modulus of :attr:`multipliers_true` (NaN when there are none)."""
        return max((abs(z) for z in self.multipliers_true), default=math.nan)


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
    true_curve : perturb.response.true_curve.TrueCurves or None
        The true periodic orbits continued from the branches (``--true``; None unless asked).
    """

    problem: str
    parameter: str
    response: FrequencyResponse
    branches: tuple = field(converter=tuple)
    backbone: Backbone | None = None
    true: tuple = field(converter=tuple, factory=tuple)
    true_curve: object = None


def parse_sweep(text: str, argument: str = "--sweep") -> tuple[str, np.ndarray]:
    """The values of ``perturb response --sweep`` and of a scene's ``[response]`` as
    ``(name, values)``: the one grammar of :func:`perturb.axis.parse_axis` (``NAME=START:STOP:N``,
    ``NAME=START:STOP:N:log``, ``NAME=V1,V2,...``), with the rules of a curve continued along it:
    2 to ``AXIS_MAX_VALUES`` values, increasing.

    Raises
    ------
    InvalidParameterError
        One line naming ``argument``, the text and the fix.

    Examples
    --------
    >>> name, values = parse_sweep("Omega=0.9:1.1:3")
    >>> name, values.tolist()
    ('Omega', [0.9, 1.0, 1.1])
    >>> parse_sweep("Omega=0.95,1.0,1.2")[1].tolist()
    [0.95, 1.0, 1.2]
    """
    from perturb._defaults import AXIS_MAX_VALUES
    from perturb.axis import parse_axis

    axis = parse_axis(text, argument)  # N checked before the values are made
    values = np.array(axis.values)

    def fail(fix: str) -> InvalidParameterError:
        return InvalidParameterError(f"{argument} {text!r}: {fix}")

    if not 2 <= values.size <= AXIS_MAX_VALUES:
        raise fail(f"N = {values.size} must be between 2 and {AXIS_MAX_VALUES}")
    if not np.all(np.diff(values) > 0):
        raise fail("START must be below STOP (bounds reversed?): give increasing values")
    return axis.name, values


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
    system.frame.require_driven(
        "problem", label_of(problem),
        "it is not driven (its system has no excitation): the frequency response is for "
        "forced, damped or parametrically excited systems; use `perturb solve`",
    )  # fmt: skip
    if parameter not in problem.values:
        from difflib import get_close_matches

        close = get_close_matches(parameter, list(problem.values), n=1)
        told = problem.case().map.set_by(parameter, "sweep")
        hint = f" ({told})" if told else f" (did you mean {close[0]!r}?)" if close else ""
        raise bad_value(
            "sweep", parameter,
            f"it is not a parameter of {label_of(problem)}: "
            f"choose from {sorted(problem.values)}{hint}",
            InvalidParameterError,
        )  # fmt: skip
    return system


def problem_response(
    problem, parameter: str, grid: Sequence[float], order: int = 1, validate: int = 0,
    measure: str = "peak", tol: float | None = None, true: int = 0, max_period: int | None = None,
) -> ProblemResponse:  # fmt: skip
    """The frequency response of a driven ``problem`` over ``grid`` values of ``parameter``.

    Every branch is the order-N one, continued from the certified first-order census through its
    folds (:mod:`perturb.steady.continued`); stability from the Floquet multipliers of the
    variational equation along the order-N series.

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
        Shoot the true orbit at this many points of each branch, spread by arclength, besides the
        largest amplitude, both sides of each fold and the ends (0: none; at most
        ``MAX_VALIDATE``).
    measure : str
        The amplitude measure the branches are named and drawn by: ``peak`` (max ``|x|``),
        ``first-harmonic`` or ``initial`` (:data:`perturb.steady.measures.MEASURES`).
    tol : float, optional
        The relative orbit error above which a shot point is marked (default ``DEFAULT_TOL``).
    true : int
        Continue the true periodic orbits from the branches, at most this many points per curve
        (0: not; :func:`perturb.response.true_curve.true_curves`), and mark where the analytic
        curve parts from them by more than ``tol`` (relative, in ``measure``); the branches born
        on them are followed too (:mod:`perturb.response.true_branches`).
    max_period : int, optional
        With ``true``: period doublings are followed while the period (in response periods)
        stays at most this (default ``MAX_PERIOD_DEFAULT``, at most ``MAX_PERIOD_CAP``).

    Returns
    -------
    ProblemResponse

    Raises
    ------
    InvalidParameterError
        A problem that is not driven, an unknown parameter, a grid of fewer than 2 increasing
        finite values, invalid parameter values at a grid point, an unknown measure, or a
        validation budget beyond ``MAX_VALIDATE``.
    """
    from perturb._defaults import DEFAULT_TOL
    from perturb.steady.continued import continued_response
    from perturb.steady.line import line_of_problem
    from perturb.steady.sampled import response_of

    system = check_request(problem, parameter)
    grid = _check_grid(parameter, grid)
    check_measure(measure)
    check_validate(validate)
    tol = DEFAULT_TOL if tol is None else check_tol(tol)
    from perturb._defaults import MAX_PERIOD_DEFAULT
    from perturb.response.true_curve import check_max_period

    max_period = check_max_period(MAX_PERIOD_DEFAULT if max_period is None else max_period)
    case = problem.case()
    for value in grid:  # the problem's own checks at every grid value (one line, exit 2)
        point = case.at(**{parameter: float(value)})
        system.frame.frequency_value(system, point.symbol_values, point.epsilon)
    told = f"response {label_of(problem)}"
    with stage(f"{told}: deriving the order-{order} amplitude equations"):
        equations = amplitude_equations(system, order)
    names = [p.name for p in system.parameters]
    line = line_of_problem(problem, parameter, names, float(grid[0]), float(grid[-1]))
    with stage(f"{told}: following every branch over {len(grid)} values of {parameter}"):
        result = continued_response(equations, order, line, grid)
    response, branch_names_ = response_of(
        result, system=label_of(problem), parameter=parameter, order=order,
        epsilon=float(case.epsilon),
        values={k: float(v) for k, v in case.values.items() if k != parameter},
        grid=grid, coordinates=equations.coordinates, measure=measure,
    )  # fmt: skip
    reference = system.coordinates[system.reference_index].name
    top = max((p.amplitude(reference, measure) for p in response.points), default=math.nan)
    with stage(f"{told}: the backbone"):
        spine = backbone(case, parameter, top, order, measure) if response.points else None
    true_points = _true_points(result, response, validate, measure, tol) if validate else ()
    curves = None
    if true:
        from perturb.response.true_curve import true_curves

        with stage(f"{told}: continuing the true periodic orbits (--true)"):
            curves = true_curves(
                problem, parameter, response, branch_names_, order, budget=true, tol=tol,
                measure=measure, max_period=max_period,
            )  # fmt: skip
        response = _refined_folds(response, curves)
    return ProblemResponse(
        label_of(problem), parameter, response, branch_names_, spine, true_points, curves
    )


def _refined_folds(response, curves):
    """The analytic folds with the true fold each one is near (``Fold.true_value``): the
    nearest fold of a true curve through the analytic branches whose max ``|x|`` agrees within
    ``FOLD_PAIRING``, within the sweep's width."""
    import attrs

    from perturb._defaults import FOLD_PAIRING

    true = [  # on the curves through the analytic branches, not those born on them
        b for c in curves.curves if c.parent is None for b in c.bifurcations if b.kind == "fold"
    ]
    width = response.grid[-1] - response.grid[0]
    folds = []
    for fold in response.folds:
        size = max(fold.peak.values(), default=math.nan)  # both carry max |x|, whatever is drawn
        near = []
        for b in true:
            other = max(b.peaks.values(), default=math.nan)
            if math.isfinite(size) and abs(other - size) > FOLD_PAIRING * max(size, 1e-300):
                continue
            if abs(b.value - fold.value) <= width:
                near.append(b)
        best = min(near, key=lambda b: abs(b.value - fold.value), default=None)
        folds.append(attrs.evolve(fold, true_value=best.value if best else math.nan))
    return attrs.evolve(response, folds=tuple(folds))


def check_measure(measure: str) -> str:
    """``measure`` if it is one of :data:`perturb.steady.measures.MEASURES`, else one line."""
    from perturb.steady.measures import MEASURES

    if measure not in MEASURES:
        raise bad_value(
            "measure", measure, f"choose one of {sorted(MEASURES)}", InvalidParameterError
        )
    return measure


def check_validate(count) -> int:
    """A validation budget: a whole number from 0 to :data:`MAX_VALIDATE`, else one line."""
    if isinstance(count, bool) or not isinstance(count, int | np.integer) or count < 0:
        raise bad_value("validate", count, "give a whole number >= 0", InvalidParameterError)
    if count > MAX_VALIDATE:
        raise bad_value(
            "validate", count,
            f"at most {MAX_VALIDATE} points a branch (each is a shooting); the largest amplitude, "
            "both sides of each fold and the ends are always shot besides",
            InvalidParameterError,
        )  # fmt: skip
    return int(count)


def check_tol(tol) -> float:
    """A tolerance: a finite number > 0, else one line."""
    try:
        value = float(tol)
    except (TypeError, ValueError):
        raise bad_value("tol", tol, "give a number > 0", InvalidParameterError) from None
    if not (math.isfinite(value) and value > 0):
        raise bad_value("tol", tol, "give a finite number > 0", InvalidParameterError)
    return value


def _true_points(result, response, count, measure, tol) -> tuple[TrueResponse, ...]:
    from perturb.response.truth import shoot_along

    first = response.coordinates[0]
    out = []
    for shot in shoot_along(result, response, count, measure, tol):
        true = shot.get("true", {})
        orbit = shot.get("orbit")
        success = bool(shot["success"])
        out.append(
            TrueResponse(
                value=shot["value"],
                branch=shot["branch"],
                success=success,
                amplitude=shot["analytic"][first],
                amplitude_error=shot.get("orbit_error", math.nan),
                stable_true=_stable(orbit) if success else None,
                stable_analytic=shot["stable_analytic"],
                message=shot["message"],
                true_amplitude=true.get(first, math.nan),
                measure=measure,
                within_tol=shot.get("within_tol"),
                reason=shot["reason"],
                multipliers_analytic=shot["multipliers_analytic"],
                curve=shot["curve"],
                orbit=orbit,
            )
        )
    return tuple(out)


def _stable(orbit: PeriodicOrbit | None) -> bool:
    """All the orbit's multipliers inside the unit circle (False when there are none: NaN)."""
    multipliers = () if orbit is None else orbit.multipliers
    return max((abs(complex(z)) for z in multipliers), default=math.nan) < 1
