"""``perturb response``: a driven problem's frequency response over a sweep of one parameter."""

from __future__ import annotations

import json

from perturb._defaults import MAX_TIMES
from perturb.cli._errors import EXIT_OK, _UsageError
from perturb.cli._values import _parse_order, _parse_sets


def _parse_sweep(text: str):
    """``NAME=START:STOP:N`` (N >= 2, START < STOP, finite): (name, array)."""
    import numpy as np

    name, sep, spec = text.partition("=")
    parts = spec.split(":")
    if not sep or not name.strip() or len(parts) != 3:
        raise _UsageError(
            f"--sweep {text!r}: write NAME=START:STOP:N, e.g. --sweep Omega=0.9:1.2:61"
        )
    try:
        start, stop = float(parts[0]), float(parts[1])
        count = int(parts[2])
    except ValueError:
        raise _UsageError(
            f"--sweep {text!r}: START and STOP must be numbers and N a whole number"
        ) from None
    if not (np.isfinite(start) and np.isfinite(stop)):
        raise _UsageError(f"--sweep {text!r}: START and STOP must be finite")
    if not 2 <= count <= MAX_TIMES:
        raise _UsageError(f"--sweep {text!r}: N = {count} must be between 2 and {MAX_TIMES}")
    if not start < stop:
        raise _UsageError(f"--sweep {text!r}: START must be below STOP (bounds reversed?)")
    return name.strip(), np.linspace(start, stop, count)


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
    if args.plot is not None:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise _UsageError(
                "--plot needs matplotlib: pip install 'perturb[plot]', or drop --plot"
            ) from None
    result = problem_response(problem, parameter, grid, order=order, validate=count)
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
