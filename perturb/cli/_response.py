"""``perturb response``: a driven problem's frequency response over a sweep of one parameter."""

from __future__ import annotations

import json
import math

from perturb.cli._errors import EXIT_OK, _UsageError
from perturb.cli._values import _check_plot_backend, _parse_order, _parse_sets


def _parse_sweep(text: str):
    """``NAME=START:STOP:N``: (name, array), or a usage error (exit 2)."""
    from perturb.errors import InvalidParameterError
    from perturb.response.model import parse_sweep

    try:
        return parse_sweep(text)
    except InvalidParameterError as exc:
        raise _UsageError(str(exc)) from None


def _parse_true(points: str | None, tol: str | None) -> tuple[int, float | None]:
    """``--true [POINTS]`` and ``--tol TOL``: (the points per curve, 0 without --true; the
    tolerance or None for the default), or a usage error (exit 2)."""
    from perturb._defaults import TRUE_CURVE_MAX_POINTS, TRUE_CURVE_POINTS

    count = 0
    if points is not None:
        if points == "default":
            count = TRUE_CURVE_POINTS
        else:
            try:
                count = int(points)
            except ValueError:
                raise _UsageError(
                    f"--true {points!r}: give the most points of each true curve, a whole "
                    f"number from 2 to {TRUE_CURVE_MAX_POINTS}"
                ) from None
            if not 2 <= count <= TRUE_CURVE_MAX_POINTS:
                raise _UsageError(
                    f"--true {count}: the most points of each true curve must be from 2 to "
                    f"{TRUE_CURVE_MAX_POINTS} (the budget's maximum)"
                )
    value = None
    if tol is not None:
        try:
            value = float(tol)
        except ValueError:
            value = math.nan
        if not (math.isfinite(value) and 0 < value < 1):
            raise _UsageError(
                f"--tol {tol!r}: give the relative difference at which the curves part, a number "
                "between 0 and 1 (e.g. 0.01)"
            )
    return count, value


def _cmd_response(args) -> int:
    from perturb.report import response_as_csv, response_as_dict, response_as_table
    from perturb.response.model import problem_response
    from problems import load_problem

    cls = load_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    order = _parse_order(args.order)
    parameter, grid = _parse_sweep(args.sweep)
    try:
        count = int(args.validate)
    except ValueError:
        raise _UsageError(f"--validate {args.validate!r}: give a whole number >= 0") from None
    if count < 0:
        raise _UsageError(f"--validate {count}: give a whole number >= 0")
    true, tol = _parse_true(args.true_curve, args.tol)
    _check_plot_backend(args.plot)
    result = problem_response(
        problem, parameter, grid, order=order, validate=count, true=true, tol=tol
    )
    if args.format == "json":
        print(json.dumps(response_as_dict(result), allow_nan=False))
    elif args.format == "csv":
        print(response_as_csv(result))
    elif args.format == "latex":
        from perturb.report import response_latex

        print(response_latex(result), end="")
    else:
        print(response_as_table(result))
    if args.plot is not None:
        from perturb.report.plots import plot_frequency_response

        plot_frequency_response(result).savefig(args.plot)
    return EXIT_OK
