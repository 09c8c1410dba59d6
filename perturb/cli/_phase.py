"""``perturb phase-diagram PROBLEM --grid X=... --grid Y=...``: stable steady states over two
parameters (:func:`perturb.sweep.phase.phase_diagram`). Imported only when the command runs."""

from __future__ import annotations

import sys

from perturb._install import install_hint
from perturb.cli._errors import EXIT_FAILED, EXIT_OK, _UsageError, pressed
from perturb.cli._order import order_of
from perturb.cli._output import _emit
from perturb.cli._values import _check_plot, _parse_positive, _parse_sets, _save_plot
from perturb.errors import MissingDependencyError

#: Exit code of an interrupted run (128 + SIGINT, as shells report it).
EXIT_INTERRUPTED = 130


def _cmd_phase(args) -> int:
    from problems import load_problem

    try:
        from perturb.sweep.api import require_extra

        require_extra()
    except (ImportError, MissingDependencyError) as exc:
        raise _UsageError(f"{exc}" if str(exc) else f"needs {install_hint('sweep')}") from None
    if len(args.grids) != 2:
        raise _UsageError(
            f"--grid: give two, x then y (got {len(args.grids)}), e.g. --grid "
            "Omega=1.98:2.02:21 --grid h=0.2:3:15"
        )
    plot = _check_plot(args)  # before any work: matplotlib, the format, a file not a user's
    if args.workers is not None and args.scheduler is not None:
        raise _UsageError(f"--workers {args.workers}: with --scheduler drop --workers")
    workers = None if args.workers is None else _parse_positive("--workers", args.workers, int)
    overrides = _parse_sets(args.sets)
    for text in args.grids:  # a parameter swept and set: the --set would be ignored in silence
        name = text.partition("=")[0].strip()
        if name in overrides:
            raise _UsageError(
                f"--grid {text!r}: {name!r} is also set with --set; sweep it or set it, not both"
            )
    problem = load_problem(args.problem).create(**overrides)
    order = order_of(args.order, problem)
    from perturb.sweep.phase import phase_diagram

    try:
        dataset = phase_diagram(
            problem, args.grids, order=order, columns=not args.rows_only, output=args.output,
            workers=workers, scheduler=args.scheduler, yes=args.yes,
        )  # fmt: skip
    except KeyboardInterrupt:
        if not pressed():  # raised by a user's code, not Ctrl-C: named by the entry point
            raise
        print("\nperturb: interrupted: nothing is written", file=sys.stderr)
        return EXIT_INTERRUPTED
    from perturb.report.phase import PhaseOutput

    if plot is not None:
        _plot(dataset, plot, args.map == "first-order", args.force)
    _emit("phase", args.format, PhaseOutput(dataset, args.output))
    import numpy as np

    drawn = "n_stable_first_order" if args.map == "first-order" else "n_stable"
    missing = bool(np.any(np.asarray(dataset[drawn].values) < 0))
    return EXIT_FAILED if missing else EXIT_OK  # lines that failed elsewhere are listed above


def _plot(dataset, path, first_order: bool, force: bool = False) -> None:
    import numpy as np

    from perturb.report.phase import _special
    from perturb.report.plots import plot_phase_diagram

    y_name, x_name = dataset["n_stable"].dims
    special = [(p[x_name], p[y_name], p["kind"]) for p in _special(dataset, first_order)]
    name = "n_stable_first_order" if first_order else "n_stable"
    which = "first order, certified" if first_order else f"order {dataset.attrs['order']}"
    figure = plot_phase_diagram(
        np.asarray(dataset[x_name].values), np.asarray(dataset[y_name].values),
        np.asarray(dataset[name].values), special, xname=x_name, yname=y_name,
        title=f"{dataset.attrs['problem']}: stable steady states ({which})",
    )  # fmt: skip
    _save_plot(figure, path, force)
