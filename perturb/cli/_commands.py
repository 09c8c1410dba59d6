"""The commands: each builds what it was asked for and prints it."""

from __future__ import annotations

import math
import sys
import warnings

import numpy as np

from perturb._defaults import DEFAULT_SAMPLES
from perturb.cache import held_warnings
from perturb.cli._errors import EXIT_FAILED, EXIT_OK, _RunFailed, _tell, _UsageError
from perturb.cli._order import order_of
from perturb.cli._output import _emit
from perturb.cli._values import (
    _check_plot,
    _parse_output,
    _parse_positive,
    _parse_sets,
    _parse_times,
    _save_plot,
)
from perturb.domain import series_domain
from perturb.report.formats import keeps_warnings


def _cmd_list(args=None) -> int:
    from perturb.errors import ProblemLoadError
    from problems import get_problem, problem_names

    fmt = getattr(args, "format", "table")
    entries = []
    for name in problem_names():
        try:
            cls = get_problem(name)
        except ProblemLoadError as exc:  # a broken installed package: say so, list the others
            print(f"perturb: warning: {exc}", file=sys.stderr)
            continue
        entries.append((name, cls.summary, cls.parameter_specs))
    _emit("problems", fmt, entries)
    return EXIT_OK


def _cmd_solve(args) -> int:
    from perturb.validation.capabilities import has_euler_angles, report_extras
    from perturb.validation.model import parameter_value_of
    from problems import load_problem

    cls = load_problem(args.problem)
    overrides = _parse_sets(args.sets)
    problem = cls.create(**overrides)
    order = order_of(args.order, problem)
    times = _parse_times(args.times)
    problem = _select_family(problem, args.family, order)
    if args.euler and not has_euler_angles(problem):
        raise _UsageError(
            f"--euler: problem {args.problem!r} has no Euler angles (rigid bodies only)"
        )
    with held_warnings(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        solution = problem.solve(order)
        domain = None
        if solution.success:
            domain = series_domain(solution, parameter_value_of(problem), problem.symbol_values())
    notes = [str(w.message) for w in caught]
    if not solution.success or not domain.ok:
        reason = (
            f"{solution.status.value}: {solution.message}"
            if not solution.success
            else "the series is outside its domain: " + "; ".join(domain.reasons)
        )
        failed = {"problem": args.problem, "status": "failed", "reason": reason}
        _emit("failure", args.format, {**failed, "warnings": notes})
        print(f"perturb: {args.problem}: {reason}", file=sys.stderr)
        return EXIT_FAILED
    period = problem.period(solution)
    if times is None:
        times = np.linspace(0.0, period, DEFAULT_SAMPLES)
    with held_warnings(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        state = problem.state(solution, times)
        extras = {"euler": problem.euler_angles(solution, times)} if args.euler else {}
    notes += [str(w.message) for w in caught if str(w.message) not in notes]
    report = report_extras(problem)
    payload = {
        "problem": args.problem,
        "parameters": problem.case().values,
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
    if not keeps_warnings(args.format):
        for note in notes:
            print(f"perturb: warning: {note}", file=sys.stderr)
    if args.latex:
        payload["latex"] = solution.latex()
    if args.steps:
        payload["steps"] = [str(solution.generating), *(str(step) for step in solution.steps)]
    from perturb.report.state import StateOutput

    blocks = [("state", state), *extras.items()]
    _check_finite(payload, blocks)
    _emit("solution", args.format, StateOutput(payload, blocks, solution))
    return EXIT_OK


def _cmd_validate(args) -> int:
    from perturb.validation import DEFAULT_TOL, validate
    from problems import load_problem

    cls = load_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    order = order_of(args.order, problem)
    problem = _select_family(problem, args.family, order)
    tol = DEFAULT_TOL if args.tol is None else _parse_positive("--tol", args.tol, float)
    report = validate(
        problem,
        order=order,
        integrator=args.integrator,
        periods=_parse_positive("--periods", args.periods, float),
        tol=tol,
    )
    _emit("validation", args.format, report)
    if not report.completed:  # the report is printed; the reason goes to stderr too
        reason = " ".join(str(report.message or report.verdict).split())
        print(f"perturb: {args.problem}: the validation did not complete: {reason}",
              file=sys.stderr)  # fmt: skip
        return EXIT_FAILED
    return EXIT_OK


def _cmd_work_precision(args) -> int:
    from perturb._defaults import MAX_ORDER, SCENE_MAX_REPEAT
    from perturb.cost import check_cost, work_precision_cost
    from perturb.validation.model import parameter_value_of
    from perturb.workprecision import work_precision
    from problems import load_problem

    cls = load_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    periods = _parse_positive("--periods", args.periods, float)
    orders = _parse_positive("--orders", args.orders, int)
    if orders > MAX_ORDER:  # never cut to the engine's highest order in silence
        raise _UsageError(
            f"--orders {orders}: the engine's highest order is {MAX_ORDER}; give at most "
            f"{MAX_ORDER}"
        )
    repeat = _parse_positive("--repeat", args.repeat, int)
    if repeat > SCENE_MAX_REPEAT:
        raise _UsageError(
            f"--repeat {repeat}: at most {SCENE_MAX_REPEAT} timed runs a point (the best of more "
            "buys no accuracy and multiplies the run time)"
        )
    cost = work_precision_cost(periods, orders, repeat)
    check_cost(cost, args.yes)
    plot = _check_plot(args)
    solution = problem.solve(1)  # the horizon is periods of it: inside its domain, or refused
    domain = series_domain(solution, parameter_value_of(problem), problem.symbol_values())
    if not solution.success or not domain.ok:
        reason = (
            f"{solution.status.value}: {solution.message}"
            if not solution.success
            else "the series is outside its domain, so its period gives no horizon: "
            + "; ".join(domain.reasons)
        )
        _emit(
            "failure", args.format, {"problem": args.problem, "status": "failed", "reason": reason}
        )
        raise _RunFailed(reason)
    _tell(cost)
    result = work_precision(problem, periods=periods, orders=orders, repeat=repeat)
    _emit("work-precision", args.format, result)
    if plot is not None:
        from perturb.report.plots import plot_work_precision

        _save_plot(plot_work_precision(result), plot, args.force)
    return EXIT_OK


def _cmd_reproduce(args) -> int:
    from problems.reproductions import get_reproduction

    reproduction = get_reproduction(args.paper)
    report = reproduction.run(output=_parse_output("--output", args.output))
    from perturb.report.formats import Reproduced

    _emit("reproduction", args.format, Reproduced(reproduction, report, bool(args.full)))
    return EXIT_OK


def _select_family(problem, name: str | None, order: int):
    """The problem following family ``name`` (checked now: an unknown name exits 2 with the list)."""
    if name is None:
        return problem
    from perturb.validation.frames import work_of

    families = problem.families(order)
    if name not in families.names and work_of(problem.system()).family_elsewhere(name):
        return (
            problem.case().with_family(name).model
        )  # a driven branch elsewhere: exit 1, with those here
    families.get(name)
    return problem.case().with_family(name).model


def _cmd_families(args) -> int:
    from perturb.report.families import FamiliesOutput
    from problems import load_problem

    cls = load_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    order = order_of(args.order, problem)
    families = problem.families(order)
    flags = _driven_marks(problem, order, families, [_family_domain(problem, f) for f in families])
    values = _values_of(problem)
    _emit("families", args.format, FamiliesOutput(families, args.problem, flags, values))
    if not len(families):
        why = families.why or "the amplitude equations have only the trivial root"
        print(f"perturb: {args.problem}: no family of periodic solutions: {why}", file=sys.stderr)
        return EXIT_FAILED
    built = [(f, o) for f, (o, _) in zip(families, flags, strict=True) if f.solution.success]
    if built and all(outside for _, outside in built):
        print(
            f"perturb: {args.problem}: the series of every family is outside its domain at "
            f"these values (e.g. {built[0][0].name}: {built[0][1]})",
            file=sys.stderr,
        )
        return EXIT_FAILED
    return EXIT_OK


def _driven_marks(problem, order: int, families, flags: list) -> list:
    """A driven problem's ``(outside, beyond)`` flags with the response's marks of each branch
    (:func:`perturb.report.marks.point_mark`: outside the domain, beyond the validity, a
    stability within the series' error of 1), so that ``families`` says of a branch what
    ``response`` marks and ``validate`` measures."""
    from perturb.validation.frames import work_of

    if not work_of(problem.system()).families_are_steady_states:
        return flags
    from perturb.report.marks import PointMark, point_mark, relative_error
    from perturb.response import steady_state_of

    steady = steady_state_of(problem, order)
    points = dict(zip(steady.names, steady.points, strict=True))
    out = []
    for family, (outside, beyond) in zip(families, flags, strict=True):
        point = points.get(family.name)
        mark = point_mark(point) if point is not None else PointMark.NONE
        if mark is PointMark.OUTSIDE and not outside:
            outside = mark.value + (f": {point.note}" if point.note else "")
        elif mark in (PointMark.BEYOND, PointMark.UNCERTAIN) and not beyond:
            beyond = (
                f"{mark.value}: its own estimate of its error is {relative_error(point):.2g} of "
                "the amplitude, so its amplitudes and stability are not certain; check it with "
                f"`perturb validate --family {family.name}`"
            )
        out.append((outside, beyond))
    return out


def _values_of(problem) -> dict:
    """The problem's values by symbol name, with ``epsilon`` (the expansion's small parameter:
    1/mu in the large-parameter regime), to put a family's frequency in numbers."""
    from perturb.system import Regime
    from perturb.validation.model import parameter_value_of

    value = float(parameter_value_of(problem))
    large = problem.system().regime is Regime.LARGE
    return {**problem.symbol_values(), "epsilon": 1.0 / value if large else value}


def _family_domain(problem, family) -> tuple[str, str]:
    """``(outside, beyond)`` of one family at the problem's values (``perturb solve``'s check)."""
    from perturb.validation.model import parameter_value_of

    own = {p.name for p in problem.system().parameters}
    if not family.solution.success or any(
        p.name not in own for p in family.solution.system.parameters
    ):  # a continuum in an amplitude the problem does not fix: no values to check it at
        return "", ""
    with held_warnings(), warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        try:
            check = series_domain(
                family.solution, parameter_value_of(problem), problem.symbol_values()
            )
        except (ArithmeticError, ValueError, TypeError) as exc:
            return f"the series cannot be evaluated at these values ({exc})", ""
    return "; ".join(check.reasons), check.validity_note()


def _non_finite(value) -> bool:
    """Whether a number anywhere in a (nested) payload is NaN or infinite."""
    if isinstance(value, dict):
        return any(_non_finite(v) for v in value.values())
    if isinstance(value, list | tuple):
        return any(_non_finite(v) for v in value)
    if isinstance(value, float | np.floating):
        return not math.isfinite(value)
    if isinstance(value, np.ndarray) and value.dtype.kind in "fc":
        return not bool(np.all(np.isfinite(value)))
    return False


def _check_finite(payload: dict, blocks) -> None:
    """A state with a NaN or an infinity is a failed run (exit 1), never a table of nonsense."""
    numbers = {"period": payload.get("period"), "blocks": [dict(b) for _, b in blocks]}
    if _non_finite(numbers):
        raise _RunFailed(
            "the solution is not finite at these parameters or times (NaN or inf); it is "
            "outside the domain where the series holds"
        )
