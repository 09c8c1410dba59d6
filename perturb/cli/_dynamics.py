"""``perturb basins``, ``perturb transient``, ``perturb ramp``: where the motion goes
(:mod:`perturb.dynamics`). The parsers are added by :func:`add_dynamics_commands`; the commands
import the engine only when they run."""

from __future__ import annotations

import math
import sys

from perturb.cli._errors import EXIT_FAILED, EXIT_OK, _RunFailed, _UsageError
from perturb.cli._order import order_of
from perturb.cli._output import _emit
from perturb.cli._values import _check_plot, _parse_positive, _parse_sets, _save_plot

#: Exit code of an interrupted run (128 + SIGINT, as shells report it).
EXIT_INTERRUPTED = 130


# ---------------------------------------------------------------------------------- parsers
def add_dynamics_commands(sub, add_problem_arguments, add_format) -> None:
    """Add the three commands to the subparsers ``sub``."""
    basins = sub.add_parser(
        "basins",
        help="a driven problem's basins of attraction: where each initial state goes",
        description="Classify every initial state of a grid over two coordinates of the state "
        "(or --samples N random states in a box) by where its true motion goes: the stable "
        "steady states of the series, each proved by shooting, captured on the stroboscopic "
        "section at the drive phase --phase; a periodic orbit found on the way; no convergence "
        "within --periods. Prints the attractors and the basin fractions with their sampling "
        "error; --plot draws the map with the attractors, the saddle and the slow flow's "
        "separatrix; --output writes a resumable Zarr store (needs perturb[sweep]).",
    )
    add_problem_arguments(basins)
    basins.add_argument(
        "--grid", dest="grids", action="append", default=[], metavar="NAME=START:STOP:N",
        help="a coordinate of the state and its values (twice: horizontal, then vertical); with "
        "--samples, NAME=LOW:HIGH of each sampled coordinate",
    )  # fmt: skip
    basins.add_argument("--phase", default="0", help="the drive phase of the section (radians)")
    basins.add_argument(
        "--periods", default=None, metavar="CAP",
        help="the most drive periods a state is followed (default 1000)",
    )  # fmt: skip
    basins.add_argument(
        "--samples", default=None, metavar="N",
        help="N random initial states in the box of --grid (a basin-stability estimate, any "
        "number of coordinates) instead of the grid",
    )  # fmt: skip
    basins.add_argument(
        "--ensemble", default=None, choices=["heyoka", "numpy"],
        help="the ensemble integrator (default heyoka when installed, else numpy)",
    )  # fmt: skip
    basins.add_argument("--workers", default=None,
                        help="worker processes of a local Dask cluster (0: this process)")  # fmt: skip
    basins.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="an existing Dask scheduler, tcp://HOST:PORT")  # fmt: skip
    basins.add_argument("--output", default=None, metavar="STORE",
                        help="the Zarr store written chunk by chunk")  # fmt: skip
    basins.add_argument("--resume", action="store_true",
                        help="continue the study in the store --output (the same command)")  # fmt: skip
    basins.add_argument("--chunk-points", default=None, metavar="N",
                        help="initial states per task and per chunk of the store")  # fmt: skip
    basins.add_argument("--plot", default=None, metavar="FILE",
                        help="also save the basin map (needs matplotlib)")  # fmt: skip
    basins.add_argument("--yes", action="store_true",
                        help="confirm a request past the cost rule (points, hours of work)")  # fmt: skip
    add_format(basins, "basins")

    transient = sub.add_parser(
        "transient",
        help="a driven problem's transient from one state, beside the slow flow's prediction",
        description="Integrate the true motion from the state --from for --periods drive "
        "periods, and beside it the slow flow (the amplitude equations as ODEs in slow time: "
        "--order 1 averaging, higher orders the displacement function of the method): the "
        "envelope and phase of both, which steady state the motion settles on and after how "
        "long.",
    )
    add_problem_arguments(transient)
    transient.add_argument("--from", dest="start", default=None, metavar="NAME=VALUE,...",
                           help="the initial state (unnamed coordinates 0), e.g. x=0.5,xdot=0")  # fmt: skip
    transient.add_argument("--periods", default=None, metavar="P",
                           help="drive periods to follow (a whole number >= 1)")  # fmt: skip
    transient.add_argument("--phase", default="0", help="the drive phase at t = 0 (radians)")
    transient.add_argument("--yes", action="store_true",
                           help="confirm a request estimated at more than an hour of work")  # fmt: skip
    transient.add_argument("--plot", default=None, metavar="FILE",
                           help="also save the transient (needs matplotlib)")  # fmt: skip
    add_format(transient, "transient")

    ramp = sub.add_parser(
        "ramp",
        help="a slow ramp of the drive frequency: the jumps up and down beside the folds",
        description="Ramp the drive frequency (a parameter that sets it: Omega, sigma) linearly "
        "in time from START to STOP at --rate, the phase the integral of the frequency, and set "
        "each measured jump beside the fold of the response curve where the branch ends; "
        "several rates (--rate R1,R2,...) show how the jump moves toward the fold as the rate "
        "goes to zero.",
    )
    add_problem_arguments(ramp)
    ramp.add_argument("--sweep", default=None, metavar="NAME=START:STOP",
                      help="the ramped parameter and its ends (up when STOP > START)")  # fmt: skip
    ramp.add_argument("--rate", default=None, metavar="R[,R2,...]",
                      help="|d NAME/dt| (> 0), or several rates")  # fmt: skip
    ramp.add_argument("--both-ways", action="store_true", help="also ramp back from STOP")
    ramp.add_argument("--yes", action="store_true",
                      help="confirm ramps estimated at more than an hour of work")  # fmt: skip
    ramp.add_argument("--plot", default=None, metavar="FILE",
                      help="also save the envelopes against the parameter (needs matplotlib)")  # fmt: skip
    add_format(ramp, "ramp")


# ---------------------------------------------------------------------------------- values
def _whole(flag: str, text, least: int) -> int:
    try:
        value = int(text)
    except (TypeError, ValueError):
        raise _UsageError(f"{flag} {text!r}: give a whole number >= {least}") from None
    if value < least:
        raise _UsageError(f"{flag} {value}: give a whole number >= {least}")
    return value


def _phase(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise _UsageError(f"--phase {text!r}: give the drive phase in radians, e.g. 0") from None
    if not math.isfinite(value):
        raise _UsageError(f"--phase {text!r}: give a finite phase (radians)")
    return value


def _state(text: str | None) -> dict[str, float]:
    if not text:
        raise _UsageError("--from: give the initial state, e.g. --from x=0.5,xdot=0")
    out = {}
    for item in text.split(","):
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise _UsageError(f"--from {text!r}: write NAME=VALUE,..., e.g. x=0.5,xdot=0")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise _UsageError(f"--from {text!r}: {value!r} is not a number") from None
    return out


def _problem(args):
    from problems import load_problem

    return load_problem(args.problem).create(**_parse_sets(args.sets))


# ---------------------------------------------------------------------------------- basins
def _cmd_basins(args) -> int:
    from perturb._defaults import BASIN_DEFAULT_PERIODS

    plot = _check_plot(args)
    cap = BASIN_DEFAULT_PERIODS if args.periods is None else _whole("--periods", args.periods, 1)
    samples = None if args.samples is None else _whole("--samples", args.samples, 1)
    workers = None if args.workers is None else _whole("--workers", args.workers, 0)
    if workers is not None and args.scheduler is not None:
        raise _UsageError(f"--workers {workers}: with --scheduler drop --workers")
    chunk = None if args.chunk_points is None else _whole("--chunk-points", args.chunk_points, 1)
    if args.resume and args.output is None:
        raise _UsageError("--resume: give the store to continue with --output STORE")
    from perturb.dynamics.basins import require_xarray
    from perturb.errors import MissingDependencyError
    from perturb.sweep.api import require_extra

    try:
        require_xarray()
        if args.output is not None or (workers or 0) > 0 or args.scheduler is not None:
            require_extra()
    except MissingDependencyError as exc:
        raise _UsageError(str(exc)) from None
    problem = _problem(args)
    order = order_of(args.order, problem)
    from perturb.dynamics.basins import basins

    try:
        result = basins(
            problem, args.grids, samples=samples, phase=_phase(args.phase), periods=cap,
            order=order, output=args.output, resume=args.resume, workers=workers,
            scheduler=args.scheduler, yes=args.yes, backend=args.ensemble, chunk_points=chunk,
        )  # fmt: skip
    except KeyboardInterrupt:
        where = f"; every chunk finished is in {args.output}: run again with --resume" if (
            args.output) else ""  # fmt: skip
        print(f"\nperturb: interrupted{where}", file=sys.stderr)
        return EXIT_INTERRUPTED
    from perturb.report.dynamics import BasinsOutput

    _emit("basins", args.format, BasinsOutput(result, args.output))
    if result.dataset is None:
        raise _RunFailed(result.message)
    if plot is not None and not result.sampled:
        _plot_basins(result, plot)
    elif plot is not None:
        print("perturb: warning: --plot draws a grid's map; random samples have none",
              file=sys.stderr)  # fmt: skip
    return EXIT_OK if result.status.success else EXIT_FAILED


def _plot_basins(result, plot) -> None:
    import numpy as np

    from perturb.report.plots.dynamics import plot_basins

    ds = result.dataset
    horizontal, vertical = result.axes
    names = list(result.catalogue.names)
    h, v = names.index(horizontal), names.index(vertical)

    def points(state):
        return np.column_stack([state.points[:, h], state.points[:, v]])

    chart = result.catalogue
    figure = plot_basins(
        np.asarray(ds[horizontal].values), np.asarray(ds[vertical].values),
        np.asarray(ds["code"].values), result.names(),
        [(s.name, points(s)) for s in chart.attractors],
        [(s.name, points(s)) for s in chart.saddles], result.separatrix,
        xname=horizontal, yname=vertical,
        title=f"{chart.problem}: basins at drive phase {chart.phase:g}",
    )  # fmt: skip
    _save_plot(figure, plot)


# ---------------------------------------------------------------------------------- transient
def _cmd_transient(args) -> int:
    plot = _check_plot(args)
    start = _state(args.start)
    if args.periods is None:
        raise _UsageError("--periods: give the drive periods to follow, e.g. --periods 300")
    periods = _whole("--periods", args.periods, 1)
    phase = _phase(args.phase)
    problem = _problem(args)
    order = order_of(args.order, problem)
    from perturb.dynamics.transient import transient

    result = transient(problem, start, periods, order=order, phase=phase, yes=args.yes)
    _emit("transient", args.format, result)
    if plot is not None:
        from perturb.report.plots.dynamics import plot_transient

        i = result.names.index(result.coordinates[0])
        figure = plot_transient(
            result.times, result.state[:, i], result.envelope()[:, 0],
            result.envelope(slow=True)[:, 0], result.phase_of()[:, 0],
            result.phase_of(slow=True)[:, 0], coordinate=result.coordinates[0],
            settle_time=result.settle_time,
            title=f"{result.problem}: settles on {result.settled}",
        )  # fmt: skip
        _save_plot(figure, plot)
    if not result.catalogue.status.success:
        raise _RunFailed(result.catalogue.message)
    return EXIT_OK


# ---------------------------------------------------------------------------------- ramp
def _sweep(text: str | None) -> tuple[str, float, float]:
    if not text:
        raise _UsageError("--sweep: give the ramped parameter and its ends, e.g. "
                          "--sweep Omega=0.95:1.1")  # fmt: skip
    name, sep, rest = text.partition("=")
    parts = rest.split(":")
    if not sep or not name.strip() or len(parts) != 2:
        raise _UsageError(f"--sweep {text!r}: write NAME=START:STOP, e.g. Omega=0.95:1.1")
    try:
        start, stop = float(parts[0]), float(parts[1])
    except ValueError:
        raise _UsageError(f"--sweep {text!r}: START and STOP must be numbers") from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise _UsageError(f"--sweep {text!r}: give finite START and STOP")
    if start == stop:
        raise _UsageError(f"--sweep {text!r}: the ramp does not move; give START != STOP")
    return name.strip(), start, stop


def _cmd_ramp(args) -> int:
    plot = _check_plot(args)
    name, start, stop = _sweep(args.sweep)
    if args.rate is None:
        raise _UsageError("--rate: give the ramp's rate |d NAME/dt| > 0, e.g. --rate 1e-5")
    rates = [_parse_positive("--rate", r.strip()) for r in args.rate.split(",") if r.strip()]
    if not rates:
        raise _UsageError(f"--rate {args.rate!r}: give a rate > 0")
    overrides = _parse_sets(args.sets)
    if name in overrides:
        raise _UsageError(f"--sweep {args.sweep!r}: {name!r} is also set with --set; ramp it or "
                          "set it, not both")  # fmt: skip
    problem = _problem(args)
    order = order_of(args.order, problem)
    from perturb.dynamics.ramp import ramp

    result = ramp(problem, name, start, stop, rates, both_ways=args.both_ways, order=order,
                  yes=args.yes)  # fmt: skip
    _emit("ramp", args.format, result)
    if plot is not None:
        from perturb.report.plots.dynamics import plot_ramp

        runs = [(f"{r.direction}, rate {r.rate:g}", r.values, r.envelope, r.jump)
                for r in result.runs]  # fmt: skip
        figure = plot_ramp(runs, result.folds, parameter=name, coordinate=result.coordinate,
                           title=f"{result.problem}: ramps of {name}")  # fmt: skip
        _save_plot(figure, plot)
    return EXIT_OK
