"""The front door ``sweep``: check, derive once, run on Dask, keep the results."""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence

from perturb._defaults import (
    DEFAULT_PERIODS,
    DEFAULT_TOL,
    SWEEP_CONNECT_SECONDS,
    SWEEP_MAX_CONNECT_SECONDS,
    SWEEP_MAX_POINTS,
)
from perturb._install import install_hint
from perturb.errors import InvalidParameterError, MissingDependencyError, SweepError
from perturb.progress import stage
from perturb.sweep.derive import plan
from perturb.sweep.grid import Axis, Grid, parse_axis
from perturb.sweep.spec import SweepJob, check_spec

__all__ = ["axes_of", "sweep"]

#: The modules of the extra ``perturb[sweep]``.
EXTRA_MODULES = ("dask", "distributed", "xarray", "zarr")


def _version() -> str:
    import perturb

    return perturb.__version__


def require_extra() -> None:
    """Raise :class:`MissingDependencyError` unless the extra ``perturb[sweep]`` is installed."""
    from perturb.sweep.driver import importable

    missing = [name for name in EXTRA_MODULES if not importable(name)]
    if missing:
        raise MissingDependencyError(f"sweeps need {', '.join(missing)}: {install_hint('sweep')}")


def _check_sizes(texts) -> None:
    """The grid's points counted from its axes' texts before any value is made: past
    :data:`~perturb._defaults.SWEEP_MAX_POINTS` it is refused (:func:`perturb.cost.check_cost`)."""
    from perturb.axis import axis_size
    from perturb.cost import Cost, check_cost

    size = math.prod(axis_size(text) for text in texts)
    if size > SWEEP_MAX_POINTS:
        check_cost(Cost(f"{size:,} points", size, 0.0), yes=True)


def axes_of(grid) -> tuple[Axis, ...]:
    """The axes of ``grid``: a :class:`Grid`, axes, ``"NAME=START:STOP:N"`` strings, or a mapping
    name -> values (a sequence, or a ``"START:STOP:N"`` string)."""
    if isinstance(grid, Grid):
        return grid.axes
    if isinstance(grid, str):
        return (parse_axis(grid),)
    if isinstance(grid, Mapping):
        out = []
        for name, values in grid.items():
            if isinstance(values, str):
                out.append(parse_axis(f"{name}={values}"))
            else:
                text = ",".join(repr(float(v)) for v in values)
                out.append(parse_axis(f"{name}={text}") if text else parse_axis(f"{name}="))
        return tuple(out)
    if isinstance(grid, Sequence):
        _check_sizes(item for item in grid if not isinstance(item, Axis))
        return tuple(item if isinstance(item, Axis) else parse_axis(item) for item in grid)
    raise InvalidParameterError(
        f"`grid` = {grid!r} is invalid: give axes as ['NAME=START:STOP:N', ...] or a mapping "
        "{name: values}"
    )


def sweep(
    problem,
    grid,
    *,
    order: int = 1,
    validate: bool = False,
    times=(0.0,),
    tol: float = DEFAULT_TOL,
    periods: float = DEFAULT_PERIODS,
    integrator: str | None = None,
    derive: str = "auto",
    output=None,
    resume: bool = False,
    workers: int | None = None,
    scheduler: str | None = None,
    client=None,
    timeout: float = SWEEP_CONNECT_SECONDS,
    yes: bool = False,
    attrs: Mapping | None = None,
    chunk_points: int | None = None,
):
    """Evaluate (and validate) ``problem``'s periodic solution over a grid of its parameters.

    The solution is derived once (symbolic in the swept parameters where the problem allows,
    ``perturb.sweep.derive``), the points are computed in chunks on Dask and written as they
    finish.

    Parameters
    ----------
    problem : perturb.validation.Model
        A problem instance (``problems.get_problem(name).create(...)``): its parameter values are
        the fixed ones; the swept ones are replaced at each point.
    grid : sequence of str, mapping or Grid
        The axes: ``["r0=0.5:1:21", "gamma3_0=0.1:0.4:16"]`` (``NAME=START:STOP:N``, also
        ``:log`` and ``NAME=V1,V2,...``), or ``{"r0": values, ...}``.
    order : int
    validate : bool
        Also shoot and judge every point, exactly as ``perturb.validation.validate``
        (``perturb validate``) with ``integrator``, ``periods`` and ``tol``.
    times : sequence of float
        Physical times of the state recorded at every point (default: the initial state).
    derive : {"auto", "per-point"}
        ``"per-point"``: each point's own derivation (``perturb validate``'s), instead of one
        symbolic derivation where the problem offers it.
    output : path, optional
        A Zarr store, created (or continued with ``resume``) and written chunk by chunk; without
        it the results are kept in memory.
    resume : bool
        Continue the sweep in ``output`` (it must be this very sweep): no point is computed twice.
    workers : int, optional
        Worker processes of the LocalCluster started here (default: one per core).
    scheduler : str, optional
        Address of an existing Dask scheduler (``tcp://HOST:PORT``) instead of a LocalCluster.
    client : distributed.Client, optional
        An existing client to use (left open).
    timeout : float
        Seconds to wait for the ``scheduler`` to answer.
    yes : bool
        Confirm a grid of more than ``perturb._defaults.SWEEP_CONFIRM_POINTS`` points.
    attrs : mapping, optional
        Extra attributes for the results (e.g. how the problem was named).
    chunk_points : int, optional
        Points per chunk (a task; the store's chunk along the grid). Default: about
        ``SWEEP_TASK_SECONDS`` of work each, from a pilot timed here. A resumed store keeps its
        own chunks.

    Returns
    -------
    xarray.Dataset
        One dimension per swept parameter, a variable per quantity (``docs/sweeps.md``).

    Raises
    ------
    perturb.errors.UnknownNameError, perturb.errors.InvalidParameterError
        Bad input (checked before any work): an unknown parameter (the closest is suggested), N < 1,
        too many points without ``yes``, a store holding anything but this sweep, an unreachable
        scheduler.
    perturb.errors.MissingDependencyError
        The extra ``perturb[sweep]`` is not installed.
    perturb.errors.SweepError
        Some chunks could not be computed (their workers died repeatedly): every other point is
        written (the error's ``dataset`` holds them); ``resume=True`` retries them.
    """
    require_extra()
    if chunk_points is not None and (
        isinstance(chunk_points, bool) or not isinstance(chunk_points, int) or chunk_points < 1
    ):
        raise InvalidParameterError(
            f"chunk_points (--chunk-points) = {chunk_points!r} is invalid: give a whole number >= 1"
        )
    spec = check_spec(
        problem,
        axes_of(grid),
        order=order,
        validate=validate,
        times=times,
        tol=tol,
        periods=periods,
        integrator=integrator,
        derive=derive,
        yes=yes,
    )
    version = _version()
    from perturb.sweep.driver import Cluster, pilot_seconds, run_tasks
    from perturb.sweep.driver import chunk_points as points_per_chunk
    from perturb.sweep.grid import Chunking

    if resume and output is None:
        raise InvalidParameterError("`resume` = True needs `output`: the store to continue")
    if output is not None:
        from perturb.sweep.store import SweepStore

        if SweepStore.check(output, spec, resume=resume, version=version) is not False:
            from perturb.sweep.lock import StoreLock

            StoreLock(output).acquire().release()  # another driver at work: refused now
    extra = {"perturb_version": version, **dict(attrs or {})}
    if isinstance(timeout, bool) or not (
        isinstance(timeout, int | float) and 0 < timeout <= SWEEP_MAX_CONNECT_SECONDS
    ):
        raise InvalidParameterError(
            f"`timeout` (--timeout) = {timeout!r} is invalid: give seconds > 0 and at most "
            f"{SWEEP_MAX_CONNECT_SECONDS:g} (a scheduler that has not answered by then is not "
            "coming)"
        )
    if workers is not None and (scheduler is not None or client is not None):
        raise InvalidParameterError(
            f"`workers` = {workers!r}: the cluster's own workers run the tasks with a scheduler "
            "or a client; drop workers"
        )
    if output is None:
        from perturb.sweep.memory import check_memory

        check_memory(spec)  # the results are kept here: they must fit
    sink = None
    try:
        with Cluster(workers, scheduler, client, timeout) as cluster:
            workers_now = cluster.n_workers()
            with stage(f"sweep {spec.label}: deriving the order-{spec.order} solution"):
                derivation, _ = plan(spec.model, spec.grid.axes, spec.order, spec.derive)
            job = SweepJob(spec, derivation, spec.fingerprint(version))

            def size() -> int:
                if chunk_points is not None:
                    return min(chunk_points, spec.grid.size)
                with stage(f"sweep {spec.label}: timing pilot points here (the chunks' size)"):
                    seconds = pilot_seconds(job)
                return points_per_chunk(seconds, spec.grid.size, workers_now)

            if output is not None:
                sink = SweepStore.prepare(
                    output, job, resume=resume, version=version, chunk_points=size, extra=extra
                )
            else:
                from perturb.sweep.memory import MemoryResult

                sink = MemoryResult(
                    job, Chunking.of(spec.grid.shape, size(), job.fill_first()), extra
                )
            pending = sink.pending()
            session = sink.begin_session() if output is not None else 1
            done = spec.grid.size - sum(_chunk_size(sink.chunking, n) for n in pending)
            clock = time.perf_counter()
            stats = run_tasks(
                cluster, job, sink.chunking, pending, sink.write, session=session, done=done,
                label=f"sweep {spec.label}",
            )  # fmt: skip
            elapsed = time.perf_counter() - clock
        if output is not None:
            sink.finish()
            left = sink.pending()  # the store's own count, not the tasks'
    finally:
        if output is not None and sink is not None:
            sink.close()
    if output is not None:
        from perturb.sweep.store import open_dataset

        dataset = open_dataset(output)
    else:
        left = [n for n, _ in stats.lost]
        dataset = sink.dataset()
    missing = sum(_chunk_size(sink.chunking, n) for n in left)
    # this run's figures (not stored): wall seconds of the tasks, their CPU on the workers, the
    # seconds spent writing here, the points computed
    dataset.attrs.update(
        seconds=elapsed,
        task_cpu_seconds=stats.cpu,
        write_seconds=stats.writing,
        points_computed=sum(_chunk_size(sink.chunking, n) for n in pending) - missing,
    )
    if left:
        reasons = dict(stats.lost)
        number = next((n for n in left if n in reasons), left[0])
        reason = reasons.get(number, "its task did not finish (the cluster lost it)")
        error = SweepError(
            f"{missing} of {spec.grid.size} points ({len(left)} of {sink.chunking.n_chunks} "
            f"chunks) are not written (e.g. chunk {number}: {reason}); every other point is "
            "written"
            + (
                "; run again with --resume (resume=True in Python) to compute them"
                if output is not None
                else ""
            )
        )
        error.dataset = dataset
        raise error
    return dataset


def _chunk_size(chunking, number: int) -> int:
    return math.prod(s.stop - s.start for s in chunking.region(number))
