"""``perturb sweep PROBLEM --grid NAME=START:STOP:N ... --output STORE``: the sweep's front end.

Loads the problem (the CLI is the one place that knows ``problems``), reads the options, runs
:func:`perturb.sweep.api.sweep` and prints a summary (or the points as CSV/JSON). Imported only
when the command runs: ``perturb --help`` loads neither Dask nor xarray nor Zarr.
"""

from __future__ import annotations

import sys
from pathlib import Path

from perturb._install import install_hint
from perturb.cli._errors import EXIT_FAILED, EXIT_OK, _RunFailed, _UsageError, pressed
from perturb.cli._order import order_of
from perturb.cli._values import _parse_positive, _parse_sets, _parse_times
from perturb.errors import MissingDependencyError, SweepError
from perturb.validation.capabilities import label_of

#: Exit code of an interrupted run (128 + SIGINT, as shells report it).
EXIT_INTERRUPTED = 130


def _workers(args) -> int | None:
    if args.workers is None:
        return None
    if args.scheduler is not None:
        raise _UsageError(
            f"--workers {args.workers}: with --scheduler the cluster's own workers run the "
            "tasks; drop --workers (start more `dask worker` processes instead)"
        )
    return _parse_positive("--workers", args.workers, int)


def _check_output(args) -> None:
    if args.format == "zarr" and args.output is None:
        raise _UsageError(
            "--output: name the Zarr store to write, e.g. --output sweep.zarr (or ask for "
            "--format csv or json)"
        )
    if args.output is not None and not args.output.strip():
        raise _UsageError(f"--output {args.output!r}: name the store, e.g. --output sweep.zarr")
    if args.resume and args.format != "zarr":
        raise _UsageError("--resume continues a Zarr store: drop --format or --resume")
    if args.format != "zarr" and args.output is not None:
        from perturb.report.written import check_file

        check_file(args.output, "--output", force=args.force)


def _cmd_sweep(args) -> int:
    from perturb._defaults import DEFAULT_TOL, SWEEP_CONNECT_SECONDS
    from problems import load_problem

    try:
        from perturb.sweep.api import axes_of, require_extra, sweep
        from perturb.sweep.grid import check_names

        require_extra()
    except (ImportError, MissingDependencyError) as exc:
        raise _UsageError(
            f"{exc}" if str(exc) else f"sweeps need {install_hint('sweep')}"
        ) from None
    if not args.grids:
        raise _UsageError("--grid: give at least one, e.g. --grid eps=0.01:0.2:20")
    _check_output(args)
    cls = load_problem(args.problem)
    overrides = _parse_sets(args.sets)
    problem = cls.create(**overrides)
    order = order_of(args.order, problem)
    axes = axes_of(args.grids)
    check_names(
        axes, [spec.name for spec in cls.parameter_specs], cls.name, fixed=set(overrides),
        advice=lambda name: problem.case().map.set_by(name, "sweep"),
    )  # fmt: skip
    if args.family is not None:  # looked for along the grid; an unknown name exits 2 with the list
        from perturb.sweep.grid import Grid, check_size
        from perturb.sweep.spec import check_family

        check_size(Grid(axes).size, args.yes)
        problem = check_family(problem, args.family, Grid(axes), order)
    times = _parse_times(args.times)
    tol = DEFAULT_TOL if args.tol is None else _parse_positive("--tol", args.tol, float)
    store = args.output if args.format == "zarr" else None
    try:
        ds = sweep(
            problem,
            axes,
            order=order,
            validate=args.validate,
            times=(0.0,) if times is None else times,
            tol=tol,
            periods=_parse_positive("--periods", args.periods, float),
            integrator=args.integrator,
            derive=args.derive,
            output=store,
            resume=args.resume,
            workers=_workers(args),
            scheduler=args.scheduler,
            timeout=(
                SWEEP_CONNECT_SECONDS
                if args.timeout is None
                else _parse_positive("--timeout", args.timeout, float)
            ),
            yes=args.yes,
            attrs={"problem_argument": args.problem},
            chunk_points=(
                None
                if args.chunk_points is None
                else _parse_positive("--chunk-points", args.chunk_points, int)
            ),
        )
    except SweepError as exc:
        raise _RunFailed(str(exc)) from None
    except KeyboardInterrupt:
        if not pressed():  # raised by a user's code, not Ctrl-C: named by the entry point
            raise
        where = ""
        if store and Path(store).is_dir():
            where = f"; continue with the same command and --resume (store {store})"
        elif store:
            where = f"; nothing was written to {store}: run the command again"
        print(
            f"\nperturb: interrupted: the points finished so far are written{where}",
            file=sys.stderr,
        )
        return EXIT_INTERRUPTED
    from perturb.report.formats import write
    from perturb.report.sweep import SweepOutput

    text = write("sweep", args.format, SweepOutput(ds, label_of(problem), store))
    if store is not None:  # the points are in the store: the text is its summary
        print(text, end="")
        return EXIT_OK
    if args.output is not None:
        from perturb.report.written import write_file

        write_file(args.output, text)
    else:
        print(text, end="")
    return EXIT_OK if ds.attrs.get("complete", True) else EXIT_FAILED
