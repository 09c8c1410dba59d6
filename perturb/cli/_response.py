"""``perturb response``: a driven problem's frequency response over a sweep of one parameter."""

from __future__ import annotations

import json
import sys

from perturb.cli._errors import EXIT_OK, _RunFailed, _UsageError
from perturb.cli._values import _check_plot, _parse_order, _parse_sets, _save_plot


def _parse_sweep(text: str):
    """``NAME=START:STOP:N``: (name, array), or a usage error (exit 2)."""
    from perturb.errors import InvalidParameterError
    from perturb.response.model import parse_sweep

    try:
        return parse_sweep(text)
    except InvalidParameterError as exc:
        raise _UsageError(str(exc)) from None


def args_set_names(args) -> set[str]:
    """The parameter names given with ``--set``."""
    return set(_parse_sets(args.sets))


def _check_domain(result) -> None:
    """Every steady state outside its series' domain: a failed run (``perturb solve``'s rule)."""
    points, outside = result.response.points, result.outside
    if points and all(outside):
        first = points[0]
        raise _RunFailed(
            f"the series is outside its domain at every steady state of the sweep (e.g. at "
            f"{result.parameter} = {first.value:.6g}: {outside[0]}); sweep closer to the "
            "resonance or at a smaller eps"
        )


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
    if count > len(grid):
        raise _UsageError(
            f"--validate {count}: more points than the sweep has ({len(grid)} values); give at "
            f"most {len(grid)}"
        )
    if parameter in args_set_names(args):
        raise _UsageError(
            f"--sweep {args.sweep!r}: {parameter!r} is also set with --set; sweep it or set it, "
            "not both"
        )
    from perturb.cost import check_cost, response_cost

    check_cost(response_cost(len(grid), order, count), args.yes)
    plot = _check_plot(args)
    result = problem_response(problem, parameter, grid, order=order, validate=count)
    _check_domain(result)
    if args.format != "table":  # the table shows them itself
        from perturb.report.response import flag_lines

        for line in flag_lines(result):
            print(f"perturb: warning: {line}", file=sys.stderr)
    if args.format == "json":
        print(json.dumps(response_as_dict(result), allow_nan=False))
    elif args.format == "csv":
        print(response_as_csv(result))
    elif args.format == "latex":
        from perturb.report import response_latex

        print(response_latex(result), end="")
    else:
        print(response_as_table(result))
    if plot is not None:
        from perturb.report.plots import plot_frequency_response

        _save_plot(plot_frequency_response(result), plot)
    return EXIT_OK
