"""Command-line interface: ``perturb list``, ``perturb solve`` (a leaf: nothing imports it).

Exit codes: 0 success, 1 a valid run whose construction or check failed (the reason is printed),
2 bad input (one line on stderr, no traceback).
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings
from collections.abc import Sequence

import numpy as np

from perturb._defaults import DEFAULT_SAMPLES
from perturb.domain import series_domain
from perturb.errors import PerturbError

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2

_EPILOG = """examples:
  perturb list
  perturb solve duffing --set eps=0.05 --set amplitude=1.2 --order 2
  perturb solve van-der-pol --order 3 --times 0,1,2,3 --format json
  perturb solve disk --euler --format json
  perturb validate duffing --set eps=0.05
  perturb reproduce paper
  perturb work-precision duffing --periods 10 --orders 3 --format csv
"""


class _UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2, no usage dump
        raise _UsageError(message)


def _add_problem_arguments(parser: argparse.ArgumentParser, *, order: bool = True) -> None:
    """PROBLEM, --set (and --order): shared by every command that builds a problem's solution."""
    parser.add_argument("problem", help="problem name (see `perturb list`)")
    parser.add_argument(
        "--set",
        dest="sets",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="set a parameter (repeatable); unset parameters take their defaults",
    )
    if order:
        parser.add_argument(
            "--order",
            default="1",
            help="highest power of the small parameter kept (integer >= 1; default 1)",
        )


def _add_format(parser: argparse.ArgumentParser, choices: list[str]) -> None:
    parser.add_argument(
        "--format", default="table", choices=choices, help="output format (default table)"
    )


def _build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="perturb",
        description="Periodic solutions of oscillating systems by Poincaré's method, checked against the true motion.",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.add_parser("list", help="list the registered problems and their parameters")
    solve = sub.add_parser(
        "solve",
        help="construct a problem's periodic solution and print its state",
        description="Construct PROBLEM's periodic solution by Poincaré's method and print the state "
        "at the requested times (default: one period, 101 samples from t = 0).",
    )
    _add_problem_arguments(solve)
    solve.add_argument(
        "--times", default=None, metavar="T1,T2,...", help="comma-separated times (physical units)"
    )
    _add_format(solve, ["table", "csv", "json"])
    solve.add_argument(
        "--euler", action="store_true", help="add the Euler angles (rigid bodies only)"
    )
    solve.add_argument(
        "--latex",
        action="store_true",
        help="also print the symbolic solution (coordinates and period) as LaTeX",
    )
    solve.add_argument(
        "--steps",
        action="store_true",
        help="also print the construction order by order (forcing, quadratures, conditions, solved)",
    )
    validate = sub.add_parser(
        "validate",
        help="check a problem's periodic solution against the true motion and give a verdict",
        description="Integrate the original equations from the analytic initial state, find the true "
        "periodic orbit by shooting, measure the errors and their slope in the expansion parameter, "
        "and say whether the analytic solution is valid.",
    )
    _add_problem_arguments(validate)
    validate.add_argument(
        "--integrator",
        default=None,
        help="rk4, dop853, rk45, radau, lsoda or heyoka (default: heyoka if installed, else dop853)",
    )
    validate.add_argument(
        "--periods",
        default="10",
        help="horizon of the trajectory comparison, in periods (default 10; information only)",
    )
    validate.add_argument(
        "--tol",
        default=None,
        help="accuracy tolerance: largest relative distance of the analytic orbit and period from "
        "the true ones (default 0.1)",
    )
    _add_format(validate, ["table", "json"])
    work = sub.add_parser(
        "work-precision",
        help="error against run time: analytic orders 1..N, RK4, scipy and heyoka",
        description="For PROBLEM over a horizon, measure the error against a reference trajectory and "
        "the wall time (median of repeated runs) of the analytic solution at orders 1..N "
        "(derivation and evaluation timed apart), RK4 at several steps, the scipy methods at "
        "several tolerances and heyoka.",
    )
    _add_problem_arguments(work, order=False)
    work.add_argument("--periods", default="10", help="horizon in periods (default 10)")
    work.add_argument("--orders", default="3", help="analytic orders 1..N (default 3)")
    work.add_argument("--repeat", default="3", help="runs per point, median reported (default 3)")
    work.add_argument(
        "--plot",
        default=None,
        metavar="FILE",
        help="also save a work-precision plot (needs matplotlib)",
    )
    _add_format(work, ["table", "csv", "json"])
    reproduce = sub.add_parser(
        "reproduce",
        help="reproduce a published paper's numbers beside the true motion",
        description="Reproduce a paper's printed constants and tables, the corrected solution and the "
        "true motion, and list its errata.",
    )
    reproduce.add_argument("paper", help="paper name (`paper`: the seed paper on the disk)")
    _add_format(reproduce, ["table", "json"])
    reproduce.add_argument(
        "--output", default=None, metavar="DIR", help="also write the report files into DIR"
    )
    return parser


def _parse_sets(items: Sequence[str]) -> dict[str, float]:
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name:
            raise _UsageError(f"--set {item!r}: write NAME=VALUE, e.g. --set eps=0.1")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise _UsageError(
                f"--set {item!r}: {value!r} is not a number; write NAME=VALUE with a real VALUE"
            ) from None
    return out


def _parse_order(text: str) -> int:
    try:
        order = int(text)
    except ValueError:
        raise _UsageError(f"--order {text!r} is not an integer: give an integer >= 1") from None
    if order < 1:
        raise _UsageError(f"--order {order} is invalid: give an integer >= 1")
    return order


def _parse_times(text: str | None) -> np.ndarray | None:
    if text is None:
        return None
    try:
        values = np.array([float(v) for v in text.split(",") if v.strip()], dtype=float)
    except ValueError:
        raise _UsageError(
            f"--times {text!r}: give comma-separated numbers, e.g. --times 0,0.5,1"
        ) from None
    if values.size == 0 or not np.all(np.isfinite(values)):
        raise _UsageError(f"--times {text!r}: give at least one finite time")
    return values


def _cmd_list() -> int:
    from problems import get_problem, problem_names

    for name in problem_names():
        cls = get_problem(name)
        print(f"{name:16s} {cls.summary}")
        for spec in cls.parameter_specs:
            print(f"    {spec.name:10s} default {spec.default:<12g} {spec.doc}")
    return EXIT_OK


def _cmd_solve(args) -> int:
    from problems import get_problem

    cls = get_problem(args.problem)
    overrides = _parse_sets(args.sets)
    order = _parse_order(args.order)
    times = _parse_times(args.times)
    problem = cls.create(**overrides)
    if args.euler and not hasattr(problem, "euler_angles"):
        raise _UsageError(
            f"--euler: problem {args.problem!r} has no Euler angles (rigid bodies only)"
        )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        solution = problem.solve(order)
        domain = None
        if solution.success:
            domain = series_domain(solution, problem.parameter_value(), problem.symbol_values())
    notes = [str(w.message) for w in caught]
    if not solution.success or not domain.ok:
        reason = (
            f"{solution.status.value}: {solution.message}"
            if not solution.success
            else "the series is outside its domain: " + "; ".join(domain.reasons)
        )
        if args.format == "json":
            failed = {"problem": args.problem, "status": "failed", "reason": reason}
            print(json.dumps({**failed, "warnings": notes}, allow_nan=True))
        print(f"perturb: {args.problem}: {reason}", file=sys.stderr)
        return EXIT_FAILED
    period = problem.period(solution)
    if times is None:
        times = np.linspace(0.0, period, DEFAULT_SAMPLES)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        state = problem.state(solution, times)
        extras = {"euler": problem.euler_angles(solution, times)} if args.euler else {}
    notes += [str(w.message) for w in caught if str(w.message) not in notes]
    report = problem.report_extras() if hasattr(problem, "report_extras") else {}
    payload = {
        "problem": args.problem,
        "parameters": problem.resolved_parameters(),
        "epsilon": problem.epsilon(),
        **report,
        "order": order,
        "period": period,
        "t": times.tolist(),
        "state": {k: np.asarray(v, dtype=float).tolist() for k, v in state.items()},
        **{
            k: {n: np.asarray(v, dtype=float).tolist() for n, v in d.items()}
            for k, d in extras.items()
        },
        "warnings": notes,
    }
    if args.format != "json":
        for note in notes:
            print(f"perturb: warning: {note}", file=sys.stderr)
    if args.latex:
        payload["latex"] = solution.latex()
    if args.steps:
        payload["steps"] = [str(solution.generating), *(str(step) for step in solution.steps)]
    _print(payload, args.format, [("state", state), *extras.items()])
    if args.format == "table":
        for key in ("steps", "latex"):
            if key in payload:
                text = payload[key] if isinstance(payload[key], str) else "\n".join(payload[key])
                print(f"\n# {key}\n{text}")
    return EXIT_OK


def _cmd_validate(args) -> int:
    from perturb.report import validation_as_dict, validation_as_table
    from perturb.validation import DEFAULT_TOL, validate
    from problems import get_problem

    cls = get_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    tol = DEFAULT_TOL if args.tol is None else _parse_positive("--tol", args.tol, float)
    report = validate(
        problem,
        order=_parse_order(args.order),
        integrator=args.integrator,
        periods=_parse_positive("--periods", args.periods, float),
        tol=tol,
    )
    if args.format == "json":
        print(json.dumps(validation_as_dict(report), allow_nan=True))
    else:
        print(validation_as_table(report))
    return EXIT_OK if report.completed else EXIT_FAILED


def _parse_positive(flag: str, text: str, kind=float):
    try:
        value = kind(text)
    except ValueError:
        raise _UsageError(
            f"{flag} {text!r} is not a number: give a positive {kind.__name__}"
        ) from None
    if not value > 0 or value != value or value == float("inf"):
        raise _UsageError(f"{flag} {text!r} is invalid: give a finite value > 0")
    return value


def _cmd_work_precision(args) -> int:
    from perturb.workprecision import work_precision
    from problems import get_problem

    cls = get_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    periods = _parse_positive("--periods", args.periods, float)
    orders = _parse_positive("--orders", args.orders, int)
    repeat = _parse_positive("--repeat", args.repeat, int)
    if args.plot is not None:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise _UsageError(
                "--plot needs matplotlib: pip install 'perturb[plot]', or drop --plot"
            ) from None
    result = work_precision(problem, periods=periods, orders=orders, repeat=repeat)
    if args.format == "json":
        print(json.dumps(result.as_dict(), allow_nan=True))
    elif args.format == "csv":
        print(result.as_csv())
    else:
        print(result.as_table())
    if args.plot is not None:
        result.plot().savefig(args.plot)
    return EXIT_OK


def _cmd_reproduce(args) -> int:
    from problems.rigid_body.paper import reproduce

    report = reproduce(args.paper, output=args.output)
    if args.format == "json":
        print(json.dumps(report.as_dict(), allow_nan=True))
    else:
        print(report.as_table())
    return EXIT_OK


def _print(payload: dict, fmt: str, blocks) -> None:
    if fmt == "json":
        print(json.dumps(payload, allow_nan=True))
        return
    columns = {"t": np.asarray(payload["t"])}
    for _, block in blocks:
        columns.update({k: np.asarray(v, dtype=float) for k, v in block.items()})
    names = list(columns)
    if fmt == "csv":
        print(",".join(names))
        for row in zip(*columns.values(), strict=True):
            print(",".join(repr(float(v)) for v in row))
        return
    head = f"# {payload['problem']}  order {payload['order']}  epsilon {payload['epsilon']:.6g}  period {payload['period']:.12g}"
    params = "  ".join(f"{k}={v:g}" for k, v in payload["parameters"].items())
    print(head)
    print(f"# {params}")
    print("".join(f"{n:>20s}" for n in names))
    for row in zip(*columns.values(), strict=True):
        print("".join(f"{float(v):20.12g}" for v in row))


def _format_warning(message, category, filename, lineno, line=None) -> str:
    """Warnings on one line, as the CLI's errors are: ``perturb: warning: ...``."""
    return f"perturb: warning: {message}\n"


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``perturb`` command; returns the exit code."""
    warnings.formatwarning = _format_warning
    parser = _build_parser()
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            parser.print_help()
            return EXIT_USAGE
        if args.command == "list":
            return _cmd_list()
        if args.command == "solve":
            return _cmd_solve(args)
        if args.command == "validate":
            return _cmd_validate(args)
        if args.command == "reproduce":
            return _cmd_reproduce(args)
        if args.command == "work-precision":
            return _cmd_work_precision(args)
        raise _UsageError(f"unknown command {args.command!r}")  # pragma: no cover
    except _UsageError as exc:
        print(f"perturb: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except (PerturbError, ValueError) as exc:
        print(f"perturb: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:  # pragma: no cover
        return 130


def run() -> None:  # pragma: no cover - console entry
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    run()
