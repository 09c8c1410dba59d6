"""``perturb sweep``: a problem over a grid of its parameters, on Dask, into a Zarr store."""

from __future__ import annotations

import json
import sys

from perturb.cli._errors import EXIT_FAILED, EXIT_OK, _UsageError
from perturb.cli._values import _parse_order, _parse_sets


def _cmd_sweep(args) -> int:
    try:
        from perturb.sweep import Grid, parse_axis, sweep
    except ImportError:
        raise _UsageError(
            "perturb sweep needs the extra 'sweep' (dask, xarray, zarr): "
            "pip install 'perturb[sweep]'"
        ) from None
    from problems import load_problem

    cls = load_problem(args.problem)
    problem = cls.create(**_parse_sets(args.sets))
    order = _parse_order(args.order)
    grid = Grid(tuple(parse_axis(text) for text in args.grid))
    workers = None
    if args.workers is not None:
        try:
            workers = int(args.workers)
        except ValueError:
            raise _UsageError(f"--workers {args.workers!r}: give a whole number >= 1") from None
        if workers < 1:
            raise _UsageError(f"--workers {workers}: give a whole number >= 1")
    if args.format in ("csv", "json") and args.output is None and grid.size > SMALL_SWEEP:
        raise _UsageError(
            f"--format {args.format} prints every point: {grid.size} points are too many; "
            f"write a store with --output (or sweep at most {SMALL_SWEEP} points)"
        )
    if args.output is None and args.format == "zarr":
        raise _UsageError(
            "--output STORE is needed to write the Zarr store (or use --format csv|json)"
        )
    if args.resume and args.output is None:
        raise _UsageError("--resume continues a store: give it with --output STORE")
    dataset = sweep(
        problem, grid, order=order, validate=args.validate, store=args.output,
        resume=args.resume, workers=workers, scheduler=args.scheduler, confirm=args.yes,
    )  # fmt: skip
    failed = int((dataset["status"].values != 0).sum())
    total = int(dataset["done"].values.size)
    if args.format == "json":
        print(json.dumps(_as_dict(dataset), allow_nan=True))
    elif args.format == "csv":
        print(dataset.drop_vars(["done"]).to_dataframe().reset_index().to_csv(index=False), end="")
    else:
        print(
            f"perturb: sweep of {problem.name}: {total} points, {total - failed} computed, "
            f"{failed} failed" + (f"; store {args.output}" if args.output else ""),
            file=sys.stderr,
        )
    return EXIT_OK if failed < total else EXIT_FAILED


#: Largest sweep printed as CSV or JSON (beyond, a store).
SMALL_SWEEP = 100_000


def _as_dict(dataset) -> dict:
    return {
        "dims": {k: int(v) for k, v in dataset.sizes.items()},
        "coords": {k: dataset[k].values.tolist() for k in dataset.dims},
        "attrs": {k: v for k, v in dataset.attrs.items()},
        "data": {k: dataset[k].values.tolist() for k in dataset.data_vars if k not in ("done",)},
    }
