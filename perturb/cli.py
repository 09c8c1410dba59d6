"""Command-line interface: ``perturb list``, ``perturb solve`` (a leaf: nothing imports it).

Exit codes: 0 success, 1 a valid run whose construction or check failed (the reason is printed),
2 bad input (one line on stderr, no traceback). Only errors about the user's input exit 2: anything
else that goes wrong inside a run is a failed run (exit 1) with the reason on one line, never a
traceback. Options are never abbreviated (``--order`` is not ``--orders``).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
import warnings
from collections.abc import Iterator, Sequence
from pathlib import Path

from perturb._defaults import DEFAULT_SAMPLES, MAX_TIMES
from perturb.errors import PerturbError
from perturb.progress import listening

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


#: Errors about the user's input (exit 2); every other exception inside a run is a failure (exit 1).
_INPUT_ERRORS = (
    "InvalidParameterError",
    "InvalidSystemError",
    "UnknownNameError",
    "ProblemLoadError",
    "SceneError",
)


class _UsageError(Exception):
    pass


class _RunFailed(Exception):
    """A valid run that failed: exit 1 with the reason on one line."""


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)  # `--order` must never mean `--orders`
        super().__init__(*args, **kwargs)

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
        "--times",
        default=None,
        metavar="TIMES",
        help="times (physical units): T1,T2,... or START:STOP:N (N evenly spaced, both ends "
        "included) or @FILE (one value a line, or comma-separated; '#' starts a comment)",
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
        help="horizon of the trajectory comparison, in periods (default 10)",
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
        "--full",
        action="store_true",
        help="print the full tables after the summary (json output is always complete)",
    )
    reproduce.add_argument(
        "--output", default=None, metavar="DIR", help="also write the report files into DIR"
    )
    for command in sub.choices.values():
        command.add_argument(
            "--quiet",
            action="store_true",
            help="no progress bar on stderr (it is shown only on a terminal anyway)",
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


def _read_times_file(text: str) -> str:
    name = text[1:]
    if not name:
        raise _UsageError("--times '@': name a file after @, e.g. --times @times.txt")
    try:
        content = Path(name).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise _UsageError(f"--times {text!r}: cannot read {name!r} ({reason})") from None
    lines = (line.split("#", 1)[0] for line in content.splitlines())
    return ",".join(item for line in lines for item in line.split(","))


def _parse_number(flag: str, text: str, item: str) -> float:
    try:
        value = float(item)
    except ValueError:
        raise _UsageError(
            f"{flag} {text!r}: {item.strip()!r} is not a number; give T1,T2,..., START:STOP:N "
            "or @FILE"
        ) from None
    if not math.isfinite(value):
        raise _UsageError(f"{flag} {text!r}: {item.strip()!r} is not finite; give finite times")
    return value


def _parse_times(text: str | None) -> np.ndarray | None:  # noqa: F821 - numpy is imported lazily
    """``--times``: ``T1,T2,...``, ``START:STOP:N`` or ``@FILE``."""
    import numpy as np

    if text is None:
        return None
    spec = _read_times_file(text) if text.startswith("@") else text
    if ":" in spec and not text.startswith("@"):
        parts = spec.split(":")
        if len(parts) != 3:
            raise _UsageError(f"--times {text!r}: write START:STOP:N, e.g. --times 0:10:1001")
        start, stop = (_parse_number("--times", text, p) for p in parts[:2])
        try:
            count = int(parts[2])
        except ValueError:
            raise _UsageError(
                f"--times {text!r}: N = {parts[2].strip()!r} must be a whole number >= 1"
            ) from None
        if not 1 <= count <= MAX_TIMES:
            raise _UsageError(f"--times {text!r}: N must be between 1 and {MAX_TIMES}")
        with np.errstate(all="ignore"):  # an overflowing range is reported just below
            values = np.linspace(start, stop, count)
        if not np.all(np.isfinite(values)):
            raise _UsageError(f"--times {text!r}: the times overflow; give a smaller range")
        return values
    items = [v for v in spec.split(",") if v.strip()]
    if not items:
        raise _UsageError(f"--times {text!r}: give at least one time")
    if len(items) > MAX_TIMES:
        raise _UsageError(f"--times {text!r}: at most {MAX_TIMES} times")
    return np.array([_parse_number("--times", text, v) for v in items], dtype=float)


def _cmd_list() -> int:
    from problems import get_problem, problem_names

    for name in problem_names():
        cls = get_problem(name)
        print(f"{name:16s} {cls.summary}")
        for spec in cls.parameter_specs:
            print(f"    {spec.name:10s} default {spec.default:<12g} {spec.doc}")
    return EXIT_OK


def _cmd_solve(args) -> int:
    import numpy as np

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
    solution = problem.solve(order)
    if not solution.success:
        print(
            f"perturb: {args.problem}: {solution.status.value}: {solution.message}", file=sys.stderr
        )
        return EXIT_FAILED
    period = problem.period(solution)
    if times is None:
        times = np.linspace(0.0, period, DEFAULT_SAMPLES)
    state = problem.state(solution, times)
    extras = {"euler": problem.euler_angles(solution, times)} if args.euler else {}
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
    }
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
    from perturb.validation import validate
    from problems import get_problem

    cls = get_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    report = validate(
        problem,
        order=_parse_order(args.order),
        integrator=args.integrator,
        periods=_parse_positive("--periods", args.periods, float),
    )
    if args.format == "json":
        print(json.dumps(report.as_dict(), allow_nan=True))
    else:
        print(report.as_table())
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
    from problems.reproductions import get_reproduction

    reproduction = get_reproduction(args.paper)
    report = reproduction.run(output=args.output)
    if args.format == "json":
        print(json.dumps(reproduction.as_dict(report), allow_nan=True))
        return EXIT_OK
    print(reproduction.summary(report))
    if args.full:
        print()
        print(reproduction.full(report))
    return EXIT_OK


def _non_finite(value) -> bool:
    """Whether a number anywhere in a (nested) payload is NaN or infinite."""
    import numpy as np

    if isinstance(value, dict):
        return any(_non_finite(v) for v in value.values())
    if isinstance(value, list | tuple):
        return any(_non_finite(v) for v in value)
    if isinstance(value, float | np.floating):
        return not math.isfinite(value)
    if isinstance(value, np.ndarray) and value.dtype.kind in "fc":
        return not bool(np.all(np.isfinite(value)))
    return False


def _print(payload: dict, fmt: str, blocks) -> None:
    import numpy as np

    numbers = {"period": payload.get("period"), "blocks": [dict(b) for _, b in blocks]}
    if _non_finite(numbers):
        raise _RunFailed(
            "the solution is not finite at these parameters or times (NaN or inf); it is "
            "outside the domain where the series holds"
        )
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


class _ProgressBar:
    """A one-line bar on stderr, redrawn in place: ``perturb: work-precision [#####.....] 12/24``."""

    WIDTH = 30

    def __init__(self, stream):
        self.stream = stream
        self.drawn = False

    def __call__(self, label: str, done: int, total: int | None) -> None:
        if total:
            filled = self.WIDTH * done // total
            bar = f"[{'#' * filled}{'.' * (self.WIDTH - filled)}] {done}/{total}"
        else:
            bar = f"{done} done"
        self.stream.write(f"\rperturb: {label} {bar}")
        self.stream.flush()
        self.drawn = True
        if total and done >= total:
            self.close()

    def close(self) -> None:
        if self.drawn:
            self.stream.write("\n")
            self.stream.flush()
            self.drawn = False


@contextlib.contextmanager
def _progress(args) -> Iterator[None]:
    """Show progress on stderr when it is a terminal and ``--quiet`` was not given."""
    show = not getattr(args, "quiet", False) and sys.stderr.isatty()
    bar = _ProgressBar(sys.stderr) if show else None
    with listening(bar):
        try:
            yield
        finally:
            if bar is not None:
                bar.close()


_COMMANDS = {
    "list": lambda args: _cmd_list(),
    "solve": lambda args: _cmd_solve(args),
    "validate": lambda args: _cmd_validate(args),
    "reproduce": lambda args: _cmd_reproduce(args),
    "work-precision": lambda args: _cmd_work_precision(args),
}


def _is_input_error(exc: BaseException) -> bool:
    return isinstance(exc, PerturbError) and any(
        cls.__name__ in _INPUT_ERRORS for cls in type(exc).__mro__
    )


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    return text or type(exc).__name__


def _run(argv: Sequence[str] | None) -> int:
    parser = _build_parser()
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            parser.print_help()
            return EXIT_USAGE
        with _progress(args):
            return _COMMANDS[args.command](args)
    except _UsageError as exc:
        print(f"perturb: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_USAGE
    except _RunFailed as exc:
        print(f"perturb: failed: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILED
    except BrokenPipeError:
        raise
    except (OverflowError, FloatingPointError, ZeroDivisionError) as exc:
        print(
            f"perturb: failed: the computation overflowed or divided by zero at these parameters "
            f"({_one_line(exc)}); try values closer to the problem's defaults",
            file=sys.stderr,
        )
        return EXIT_FAILED
    except Exception as exc:  # noqa: BLE001 - a run never ends in a traceback
        if _is_input_error(exc):
            print(f"perturb: error: {_one_line(exc)}", file=sys.stderr)
            return EXIT_USAGE
        print(
            f"perturb: failed: internal error ({type(exc).__name__}: {_one_line(exc)}); please "
            "report it with the command line",
            file=sys.stderr,
        )
        return EXIT_FAILED


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``perturb`` command; returns the exit code.

    A closed output pipe (``perturb solve ... | head``) ends the run quietly, as other Unix tools do.
    """
    warnings.formatwarning = _format_warning
    try:
        code = _run(argv)
        sys.stdout.flush()
        return code
    except BrokenPipeError:
        # Python's advice: point stdout at devnull so the interpreter's final flush cannot fail again.
        with contextlib.suppress(OSError, ValueError):
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        return EXIT_FAILED
    except KeyboardInterrupt:  # pragma: no cover
        return 130


def run() -> None:  # pragma: no cover - console entry
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    run()
