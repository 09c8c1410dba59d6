"""``perturb response``: a driven problem's frequency response over a sweep of one parameter."""

from __future__ import annotations

import math
import sys

from perturb.cli._errors import EXIT_OK, _RunFailed, _tell, _UsageError
from perturb.cli._order import order_of
from perturb.cli._output import _emit
from perturb.cli._values import _check_plot, _parse_sets, _save_plot


def _parse_sweep(text: str):
    """``NAME=START:STOP:N``: (name, array), or a usage error (exit 2)."""
    from perturb.errors import InvalidParameterError
    from perturb.response.model import parse_sweep

    try:
        return parse_sweep(text)
    except InvalidParameterError as exc:
        raise _UsageError(str(exc)) from None


def _count_sweep(text: str) -> int:
    """The number of values of ``--sweep``, counted from its text (none is made), or a usage
    error (exit 2)."""
    from perturb.axis import axis_size
    from perturb.errors import InvalidParameterError

    try:
        return axis_size(text, "--sweep")
    except InvalidParameterError as exc:
        raise _UsageError(str(exc)) from None


def _parse_true(points: str | None) -> int:
    """``--true [POINTS]``: the most points of each true curve (0 without --true), or a usage
    error (exit 2)."""
    from perturb._defaults import TRUE_CURVE_MAX_POINTS, TRUE_CURVE_POINTS

    if points is None:
        return 0
    if points == "default":
        return TRUE_CURVE_POINTS
    try:
        count = int(points)
    except ValueError:
        raise _UsageError(
            f"--true {points!r}: give the most points of each true curve, a whole number from 2 "
            f"to {TRUE_CURVE_MAX_POINTS}"
        ) from None
    if not 2 <= count <= TRUE_CURVE_MAX_POINTS:
        raise _UsageError(
            f"--true {count}: the most points of each true curve must be from 2 to "
            f"{TRUE_CURVE_MAX_POINTS} (the budget's maximum)"
        )
    return count


def _parse_max_period(text: str | None, true: int) -> int | None:
    """``--max-period K``: a whole number from 1 to ``MAX_PERIOD_CAP``, with ``--true`` only."""
    from perturb._defaults import MAX_PERIOD_CAP

    if text is None:
        return None
    try:
        value = int(text)
    except ValueError:
        raise _UsageError(
            f"--max-period {text!r}: give a whole number from 1 to {MAX_PERIOD_CAP}"
        ) from None
    if not 1 <= value <= MAX_PERIOD_CAP:
        raise _UsageError(
            f"--max-period {value}: give a whole number from 1 (no period doubling followed) to "
            f"{MAX_PERIOD_CAP} (the cap: a cascade's later steps are closer than their location's "
            "tolerance)"
        )
    if not true:
        raise _UsageError(
            f"--max-period {value}: it bounds the period doublings of the true curves; add --true"
        )
    return value


def _check_domain(result) -> None:
    """Every steady state outside its series' domain: a failed run (``perturb solve``'s rule)."""
    points = result.response.points
    if not points:
        why = "; ".join(result.response.failures[:2]) if result.response.failures else ""
        grid = result.response.grid
        raise _RunFailed(
            f"no steady state was found at any value of the sweep ({result.parameter} from "
            f"{grid[0]:g} to {grid[-1]:g}){': ' + why if why else ''}; sweep closer to the "
            "resonance, at a smaller forcing or eps"
        )
    if not any(p.series_ok for p in points):
        first = points[0]
        raise _RunFailed(
            f"the series is outside its domain at every steady state of the sweep (e.g. at "
            f"{result.parameter} = {first.value:.6g}: {first.note}); sweep closer to the "
            "resonance or at a smaller eps"
        )


def _cmd_response(args) -> int:
    from perturb._defaults import MAX_VALIDATE
    from perturb.response.model import problem_response
    from problems import load_problem

    cls = load_problem(args.problem)
    overrides = _parse_sets(args.sets)
    problem = cls.create(**overrides)
    order = order_of(args.order, problem)
    values = _count_sweep(args.sweep)
    try:
        count = int(args.validate)
    except ValueError:
        raise _UsageError(f"--validate {args.validate!r}: give a whole number >= 0") from None
    if count < 0:
        raise _UsageError(f"--validate {count}: give a whole number >= 0")
    if count > MAX_VALIDATE:
        raise _UsageError(
            f"--validate {count}: at most {MAX_VALIDATE} points a branch (each is a shooting; the "
            "largest amplitude, both sides of each fold and the ends are shot besides)"
        )
    tol = None
    if args.tol is not None:
        try:
            tol = float(args.tol)
        except ValueError:
            raise _UsageError(f"--tol {args.tol!r}: give a number > 0, e.g. --tol 0.01") from None
        if not (math.isfinite(tol) and tol > 0):
            raise _UsageError(f"--tol {args.tol}: give a finite number > 0, e.g. --tol 0.01")
    true = _parse_true(args.true_curve)
    max_period = _parse_max_period(args.max_period, true)
    from perturb.cost import check_cost, modes_of, response_cost

    cost = response_cost(values, order, count, true, modes_of(problem))
    check_cost(cost, args.yes)  # counted from the text: no value is made before
    parameter, grid = _parse_sweep(args.sweep)
    if parameter in overrides:
        raise _UsageError(
            f"--sweep {args.sweep!r}: {parameter!r} is also set with --set; sweep it or set it, "
            "not both"
        )
    plot = _check_plot(args)
    _tell(cost)
    result = problem_response(
        problem, parameter, grid, order=order, validate=count, measure=args.measure, tol=tol,
        true=true, max_period=max_period,
    )  # fmt: skip
    _check_domain(result)
    if args.format != "table":  # the table shows them itself
        from perturb.report.response import flag_lines

        for line in flag_lines(result):
            print(f"perturb: warning: {line}", file=sys.stderr)
    _emit("response", args.format, result)
    if plot is not None:
        from perturb.report.plots import plot_frequency_response

        _save_plot(plot_frequency_response(result), plot, args.force)
    return EXIT_OK
