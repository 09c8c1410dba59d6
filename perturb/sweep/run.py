"""The driver: a sweep's chunks on a Dask cluster, written to the store as they finish.

By default a ``dask.distributed`` LocalCluster over this machine's cores (one single-threaded
worker process each: the work is Python and sympy); with ``scheduler="tcp://HOST:PORT"`` the
identical tasks run on an existing cluster (``dask scheduler`` / ``dask worker``, dask-jobqueue,
Kubernetes). Chunks are sized from a pilot point so that a task's scheduling overhead
(:data:`TASK_OVERHEAD`) stays under :data:`OVERHEAD_FRACTION` of its work, with enough chunks to
keep every worker busy. A worker that dies has its task re-run by Dask on another; an interrupted
driver leaves every finished chunk in the store, and ``resume`` computes only what is missing.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping

import numpy as np

from perturb import __version__
from perturb.errors import InvalidParameterError, bad_value
from perturb.progress import track
from perturb.sweep.grid import CONFIRM_POINTS, Grid
from perturb.sweep.points import QUANTITIES, VALIDATION_QUANTITIES, evaluate_chunk, verdict_codes
from perturb.sweep.store import create_store, open_store, pending_points, write_chunk

__all__ = ["sweep"]

#: Scheduling cost of one Dask task (submit, serialise, run, gather; measured 2-4 ms on loopback:
#: benchmarks/bench_sweep.md), and the largest share of it a chunk may carry.
TASK_OVERHEAD = 0.004
OVERHEAD_FRACTION = 0.05
#: Chunks per worker at least (load balance), unless there are fewer points.
CHUNKS_PER_WORKER = 4
#: Seconds to wait for a scheduler given by address before saying it cannot be reached.
CONNECT_TIMEOUT = 10.0


def _client(workers: int | None, scheduler: str | None):
    from distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            return Client(scheduler, timeout=CONNECT_TIMEOUT), None
        except (OSError, TimeoutError) as exc:
            raise bad_value(
                "scheduler", scheduler,
                f"no Dask scheduler answered within {CONNECT_TIMEOUT:g} s ({exc}); start one "
                "with `dask scheduler` and give its tcp://HOST:PORT",
                InvalidParameterError,
            ) from None  # fmt: skip
    cluster = LocalCluster(
        n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0"
    )
    return Client(cluster), cluster


def _chunks(points: np.ndarray, seconds_per_point: float, workers: int) -> list[np.ndarray]:
    smallest = max(1, math.ceil(TASK_OVERHEAD / (OVERHEAD_FRACTION * max(seconds_per_point, 1e-9))))
    balanced = max(1, math.ceil(len(points) / (CHUNKS_PER_WORKER * max(workers, 1))))
    size = max(smallest, min(balanced, len(points)))
    return [points[i : i + size] for i in range(0, len(points), size)]


def sweep(
    problem,
    grid: Grid | Mapping,
    *,
    order: int = 1,
    validate: bool = False,
    store=None,
    resume: bool = False,
    workers: int | None = None,
    scheduler: str | None = None,
    confirm: bool = False,
    validate_options: Mapping | None = None,
):
    """Evaluate (and with ``validate`` judge) ``problem`` at every point of ``grid``, on Dask.

    Parameters
    ----------
    problem : problems.base.Problem
        The problem with its fixed parameters; each point is ``problem.with_parameters(**point)``.
    grid : Grid or mapping
        ``{name: values}`` or a :class:`~perturb.sweep.grid.Grid`; one dimension per parameter.
    order : int
    validate : bool
        Also shoot and judge each point (verdict, orbit error, period error, slope, Floquet).
    store : path, optional
        A Zarr store written chunk by chunk (default: a temporary one, deleted after reading).
    resume : bool
        Continue the sweep already in ``store`` (same problem, grid, order, options).
    workers : int, optional
        Worker processes of the LocalCluster (default: the machine's cores).
    scheduler : str, optional
        ``tcp://HOST:PORT`` of an existing Dask scheduler (then ``workers`` is ignored).
    confirm : bool
        Needed above :data:`~perturb.sweep.grid.CONFIRM_POINTS` points.
    validate_options : mapping, optional
        Keyword arguments of :func:`perturb.validation.validate` (``periods``, ``tol``…).

    Returns
    -------
    xarray.Dataset
        One dimension per swept parameter; ``status`` (0 computed, 1 failed: ``reason``),
        ``epsilon``, ``period``, ``frequency``, ``amplitude_<state>``, and with ``validate``
        ``verdict`` (codes in ``attrs["verdict_codes"]``), ``orbit_error``, ``period_error``,
        ``slope``, ``floquet_max``, ``resolution``; ``done``; attributes: the problem, its fixed
        parameters, order, perturb version.

    Raises
    ------
    InvalidParameterError
        An unknown parameter (the closest suggested), a grid of more than
        ``CONFIRM_POINTS`` points without ``confirm``, a store that is not this sweep's, an
        unreachable scheduler.
    """
    import json
    import tempfile
    from difflib import get_close_matches

    grid = grid if isinstance(grid, Grid) else Grid.of(grid)
    for name in grid.names:
        if name not in problem.values:
            close = get_close_matches(name, list(problem.values), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise bad_value(
                "grid", name,
                f"it is not a parameter of {problem.name}: choose from {sorted(problem.values)}{hint}",
                InvalidParameterError,
            )  # fmt: skip
    if grid.size > CONFIRM_POINTS and not confirm:
        raise bad_value(
            "grid", f"{grid.size} points",
            f"more than {CONFIRM_POINTS:.0e} points: confirm with --yes (confirm=True)",
            InvalidParameterError,
        )  # fmt: skip
    names = tuple(f"amplitude_{n}" for n in problem.state_names())
    quantities = (*QUANTITIES, *names, *(VALIDATION_QUANTITIES if validate else ()))
    fixed = {k: v for k, v in problem.values.items() if k not in grid.names}
    attrs = {
        "problem": problem.name,
        "order": order,
        "validate": bool(validate),
        "fixed": json.dumps(fixed, sort_keys=True),
        "perturb_version": __version__,
        "status_codes": json.dumps({0: "computed", 1: "failed (see reason)"}),
    }
    if validate:
        attrs["verdict_codes"] = json.dumps(verdict_codes())
    temporary = None
    if store is None:
        temporary = tempfile.TemporaryDirectory(prefix="perturb-sweep-")
        store = f"{temporary.name}/sweep.zarr"
    create_store(store, grid, quantities, attrs, resume)
    todo = pending_points(store, grid)
    options = dict(validate_options or {})
    if len(todo):
        # a pilot point sizes the chunks (and fills this process's caches, which do not travel)
        start = time.perf_counter()
        first = evaluate_chunk(problem, grid, todo[:1], order, validate, names, options)
        per_point = time.perf_counter() - start
        write_chunk(store, grid, *first)
        todo = todo[1:]
    if len(todo):
        client, cluster = _client(workers, scheduler)
        try:
            n_workers = max(1, len(client.scheduler_info().get("workers", {})) or (workers or 1))
            chunks = _chunks(todo, per_point, n_workers)
            futures = [
                client.submit(
                    evaluate_chunk, problem, grid, chunk, order, validate, names, options,
                    pure=False,
                )
                for chunk in chunks
            ]  # fmt: skip
            from distributed import as_completed

            for future in track(as_completed(futures), label="sweep", total=len(futures)):
                write_chunk(store, grid, *future.result())
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    dataset = open_store(store)
    if temporary is not None:
        dataset = dataset.load()
        temporary.cleanup()
    return dataset
