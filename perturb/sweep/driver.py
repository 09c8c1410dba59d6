"""The Dask driver: connect to a cluster, size the chunks, run the tasks, write what finishes.

By default a :class:`distributed.LocalCluster` of single-threaded worker processes over this
machine's cores; with a scheduler address, the identical tasks on an existing cluster (``dask
scheduler`` and ``dask worker`` started by hand, dask-jobqueue, Kubernetes). The job (spec and
derivation plan, as cloudpickle) is scattered to the workers once; a worker unpacks it once per
process (:func:`run_packed`). Results come back to this process, which is the store's only
writer: a chunk is written as soon as it finishes, in any order.

A worker that dies has its chunk run again by Dask elsewhere (its points were never written);
a chunk that kills workers again and again is left unwritten and reported (``--resume`` retries
it). Ctrl-C stops the run after the chunk being written; everything written stays.
"""

from __future__ import annotations

import contextlib
import importlib.util
import logging
import math
import os
import statistics
import time
import uuid
from collections.abc import Callable

from attrs import frozen

from perturb._defaults import (
    SWEEP_CHUNKS_PER_WORKER,
    SWEEP_CONNECT_SECONDS,
    SWEEP_MAX_CHUNK_POINTS,
    SWEEP_OVERHEAD_SHARE,
    SWEEP_PILOT_GROWTH,
    SWEEP_PILOT_POINTS,
    SWEEP_PILOT_SECONDS,
    SWEEP_PILOT_VALIDATIONS,
    SWEEP_RESCATTERS,
    SWEEP_TASK_OVERHEAD_SECONDS,
    SWEEP_TASK_SECONDS,
    SWEEP_WORKERS_PER_CORE,
)
from perturb.cache import CACHE_ENV, KEY_ENV, QUIET_ENV
from perturb.errors import InvalidParameterError
from perturb.progress import notify, stage
from perturb.sweep.grid import Chunking
from perturb.sweep.packing import pack, pickled
from perturb.sweep.scheduler import probe, refused
from perturb.sweep.spec import SweepJob
from perturb.sweep.task import run_chunk
from perturb.sweep.watch import scatter, watched

__all__ = [
    "Cluster",
    "RunStats",
    "run_calls",
    "chunk_points",
    "pack",
    "pilot_seconds",
    "run_packed",
    "run_tasks",
]

#: Per worker process: the jobs unpacked, by key.
_JOBS: dict[str, SweepJob] = {}


def run_packed(blob: bytes, key: str, shape, chunk, number: int, session: int) -> dict:
    """The task a worker runs: unpack the job (once per process), compute chunk ``number``."""
    job = _JOBS.get(key)
    if job is None:
        import cloudpickle

        job = _JOBS[key] = cloudpickle.loads(blob)
    chunking = Chunking(shape, chunk)
    return run_chunk(job, chunking.indices(number), session)


# ---------------------------------------------------------------------------------- sizing
def pilot_seconds(job: SweepJob) -> float:
    """Seconds one point takes, timed here on the points of the grid's first chunk (which share a
    derivation) after a run that pays the one-time costs (compiling, caches): for an evaluation
    a batch of :data:`SWEEP_PILOT_POINTS` — and, if that is quick, the cost of the extra points of
    a batch :data:`SWEEP_PILOT_GROWTH` times larger (the chunk's fixed cost left out); the median
    of :data:`SWEEP_PILOT_VALIDATIONS` single points for a validation."""
    if job.spec.validate:
        times = []
        for index in _pilot_indices(job, 1 + SWEEP_PILOT_VALIDATIONS):
            clock = time.perf_counter()
            run_chunk(job, [index])
            times.append(time.perf_counter() - clock)
        return statistics.median(times[1:] or times)
    n = SWEEP_PILOT_POINTS
    indices = _pilot_indices(job, 2 * n)
    first = indices[:n]
    second = indices[n:] or first
    run_chunk(job, first)
    seconds = _timed(job, second)
    if seconds >= SWEEP_PILOT_SECONDS:
        return seconds / len(second)
    more = _pilot_indices(job, len(second) * SWEEP_PILOT_GROWTH)
    if len(more) <= len(second):
        return seconds / len(second)
    larger = _timed(job, more)
    marginal = (larger - seconds) / (len(more) - len(second))
    return marginal if marginal > 0 else larger / len(more)


def _timed(job: SweepJob, indices) -> float:
    clock = time.perf_counter()
    run_chunk(job, indices)
    return time.perf_counter() - clock


def _pilot_indices(job: SweepJob, count: int) -> list[int]:
    """The (at most ``count``) points of a chunk at the grid's origin, as the sweep's chunks are
    filled: with one derivation per distinct parameter set they share a derivation, as a chunk's
    points do, so the pilot times a point and not a derivation per point (which made the disk's
    r0 x gamma3_0 map run in one-point chunks, each paying its own derivation)."""
    block = Chunking.of(job.spec.grid.shape, count, job.fill_first())
    return [int(i) for i in block.indices(0)]


def chunk_points(seconds_per_point: float, size: int, workers: int) -> int:
    """Points per chunk: about :data:`SWEEP_TASK_SECONDS` of work, and at least
    :data:`SWEEP_CHUNKS_PER_WORKER` chunks per worker when the grid has enough points — but never
    less work than keeps a task's overhead within :data:`SWEEP_OVERHEAD_SHARE` of it; at most
    :data:`SWEEP_MAX_CHUNK_POINTS`."""
    per = max(seconds_per_point, 1e-9)
    points = math.ceil(SWEEP_TASK_SECONDS / per)
    share = math.ceil(size / (SWEEP_CHUNKS_PER_WORKER * max(workers, 1)))
    least = math.ceil(SWEEP_TASK_OVERHEAD_SECONDS / SWEEP_OVERHEAD_SHARE / per)
    points = max(min(points, share), least)
    return max(1, min(points, SWEEP_MAX_CHUNK_POINTS, size))


# ---------------------------------------------------------------------------------- the cluster
class Cluster:
    """A Dask client: to the scheduler at ``address``, or to a new LocalCluster of ``workers``
    single-threaded processes (default: one per core). A context manager: a cluster it started
    is closed on exit, an existing one is left running.

    Raises
    ------
    perturb.errors.InvalidParameterError
        No scheduler answers at ``address`` within ``timeout`` seconds (one line), or
        ``workers`` < 1.
    """

    def __init__(
        self,
        workers: int | None = None,
        address: str | None = None,
        client=None,
        timeout: float = SWEEP_CONNECT_SECONDS,
    ):
        self.workers = workers
        self.address = address
        self.timeout = timeout
        self.client = client
        self._owned = client is None
        self._cluster = None

    def __enter__(self) -> Cluster:
        if self.client is not None:
            return self
        from distributed import Client

        if self.address is not None:
            self.client = _connect(self.address, self.timeout)
            return self
        import dask
        from distributed import LocalCluster

        n = self.workers if self.workers is not None else (os.cpu_count() or 1)
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise InvalidParameterError(
                f"--workers (workers=) {n!r} is invalid: give a whole number >= 1"
            )
        cores = os.cpu_count() or 1
        if n > SWEEP_WORKERS_PER_CORE * cores:
            raise InvalidParameterError(
                f"--workers (workers=) {n} is more than {SWEEP_WORKERS_PER_CORE} worker processes "
                f"per core of this machine ({cores} cores): give at most "
                f"{SWEEP_WORKERS_PER_CORE * cores}, or run on a cluster with --scheduler"
            )
        private = {PRE_SPAWN: _pre_spawn_environment(), **NO_HTTP_ROUTES}
        with (
            dask.config.set(private),
            _environment_kept(SAFE_PATH),
            stage(f"starting a local Dask cluster of {n} worker" + ("s" if n != 1 else "")),
        ):
            self._cluster = LocalCluster(
                n_workers=n,
                threads_per_worker=1,
                processes=True,
                host="127.0.0.1",
                dashboard_address="127.0.0.1:0",  # nothing served there (NO_HTTP_ROUTES)
                silence_logs=logging.ERROR,
                env=_worker_environment(),
                security=_private(),
            )
        self.client = Client(self._cluster, set_as_default=False)
        return self

    def n_workers(self) -> int:
        """Workers connected now (at least 1, so that chunk sizing can divide by it)."""
        info = self.client.scheduler_info()
        return max(len(info.get("workers", {})), 1)

    def __exit__(self, *exc) -> None:
        if not self._owned:
            return
        if self._cluster is not None:  # the workers of our own cluster closed without a word
            with contextlib.suppress(Exception):
                self.client.run(_quiet_shutdown)
        with contextlib.suppress(Exception):
            self.client.close()
        if self._cluster is not None:
            distributed = logging.getLogger("distributed")
            level = distributed.level
            distributed.setLevel(logging.CRITICAL)
            try:
                with contextlib.suppress(Exception):
                    self._cluster.close()
            finally:
                distributed.setLevel(level)


def _quiet_shutdown() -> None:
    """Run on each worker of the local cluster before it closes: the heartbeat a worker sends
    to a scheduler closing first fails, and Dask logs it with a traceback on the terminal
    (perturb reports the run's failures itself, in one line)."""
    logging.getLogger("distributed").setLevel(logging.CRITICAL)


def _private():
    """Credentials made for this cluster alone (:meth:`distributed.security.Security.temporary`):
    its scheduler and workers speak TLS and accept only peers holding them, so that another
    user of this machine cannot connect to the ports and run code as this one.

    Raises
    ------
    perturb.errors.MissingDependencyError
        The ``cryptography`` package (which makes the credentials) is not installed.
    """
    from distributed.security import Security

    try:
        return Security.temporary()
    except ImportError:
        from perturb.errors import MissingDependencyError

        raise MissingDependencyError(
            "the local cluster needs cryptography for its private TLS credentials: pip install "
            "'perturb[sweep]' (or cryptography), or run on a cluster with --scheduler"
        ) from None


def _connect(address: str, timeout: float):
    """A client of the scheduler at ``address``, connected within ``timeout`` seconds in all
    (the probe and the client's own connection), or a one-line refusal.

    Raises
    ------
    perturb.errors.InvalidParameterError
        No Dask scheduler answers at ``address`` within ``timeout`` seconds: the reason in one
        line (refused, silent, another kind of server, a malformed address).
    """
    import threading

    from distributed import Client

    deadline = time.monotonic() + timeout
    probe(address, timeout)
    left = max(deadline - time.monotonic(), 0.1)
    outcome: dict = {}

    def connect():
        try:
            outcome["client"] = Client(address, timeout=left, set_as_default=False)
        except BaseException as exc:  # noqa: BLE001 - reported below, in one line
            outcome["error"] = exc

    thread = threading.Thread(target=connect, daemon=True)
    thread.start()
    thread.join(left)
    if "client" in outcome:
        return outcome["client"]
    error = outcome.get("error")
    reason = (
        " ".join(f"{type(error).__name__}: {error}".split())
        if error is not None
        else "the connection did not complete"
    )
    raise refused(address, timeout, reason[:200])


#: No pages on the HTTP servers of the local cluster's scheduler and workers (Dask starts them
#: whatever the dashboard: info, JSON, metrics and a proxy to the workers, readable by any user of
#: the machine); they listen on 127.0.0.1 at a free port and answer nothing.
NO_HTTP_ROUTES = {"distributed.scheduler.http.routes": [], "distributed.worker.http.routes": []}

#: Dask's setting of the variables its nanny sets before it starts a worker process.
PRE_SPAWN = "distributed.nanny.pre-spawn-environ"

#: Variables of :data:`PRE_SPAWN` left out for the workers perturb starts: MALLOC_TRIM_THRESHOLD_
#: fixes malloc's threshold for mapping fresh pages, so that every array above 128 kB is mapped
#: and unmapped again; a chunk's evaluation ran 3 times slower on such a worker (0.59 s against
#: 0.17 s for 44,601 van der Pol points, benchmarks/bench_sweep.md). A sweep's chunks hold little
#: memory, which is what that setting returns to the system.
PRE_SPAWN_LEFT_OUT = ("MALLOC_TRIM_THRESHOLD_",)


#: The variable that starts the worker processes in Python's safe-path mode: the interpreter a
#: nanny spawns (``python -c "from multiprocessing.spawn import ..."``) would otherwise put the
#: working folder first on its ``sys.path`` and import a ``multiprocessing.py`` lying there.
SAFE_PATH = "PYTHONSAFEPATH"


def _pre_spawn_environment() -> dict:
    """Dask's pre-spawn variables without :data:`PRE_SPAWN_LEFT_OUT`, with :data:`SAFE_PATH`."""
    import dask

    environ = dict(dask.config.get(PRE_SPAWN, default={}) or {})
    environ = {k: v for k, v in environ.items() if k not in PRE_SPAWN_LEFT_OUT}
    environ[SAFE_PATH] = "1"
    return environ


@contextlib.contextmanager
def _environment_kept(name: str):
    """Restore the variable ``name`` of this process after the block (a nanny sets its
    pre-spawn variables in the environment of the process that starts it: safe-path mode is
    for the workers, not for the caller's own later subprocesses)."""
    before = os.environ.get(name)
    try:
        yield
    finally:
        if before is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = before


def _worker_environment() -> dict[str, str]:
    """Variables for the workers: single-threaded BLAS (as the ``perturb`` command sets them),
    this process's disk cache folder (so that they read what the driver derived), and its
    warnings left to this process (:data:`perturb.cache.QUIET_ENV`: the folder's trouble is
    reported once, here, and never becomes a point's warning)."""
    env = {name: os.environ.get(name, "1") for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")}
    for name in (CACHE_ENV, KEY_ENV):
        if name in os.environ:
            env[name] = os.environ[name]
    env[QUIET_ENV] = "1"
    return env


# ---------------------------------------------------------------------------------- running
@frozen
class RunStats:
    """How a run of tasks went.

    Attributes
    ----------
    lost : tuple of (int, str)
        Chunks that could not be computed (their workers died again and again), with the reason.
    tasks : int
        Chunks computed and written.
    cpu : float
        CPU seconds the tasks took on their workers.
    writing : float
        Seconds this process spent writing results.
    """

    lost: tuple
    tasks: int
    cpu: float
    writing: float


def run_tasks(
    cluster: Cluster,
    job: SweepJob,
    chunking: Chunking,
    pending: list[int],
    write: Callable[[int, dict], None],
    *,
    session: int,
    done: int,
    label: str,
) -> RunStats:
    """Run the chunks ``pending`` on the cluster, ``write`` each as it finishes.

    ``done`` points are already written (for the progress report).
    """
    from distributed import as_completed
    from distributed.client import FutureCancelledError

    client = cluster.client
    packed = pack(job)
    total = math.prod(chunking.shape)
    lost: dict[int, str] = {}
    cpu = writing = 0.0
    tasks = 0
    notify(label, done, total)
    rounds = 0
    while pending:
        # the job once to every worker, not inside every task (an axis of 10^6 values is 9 MB)
        blob = scatter(client, packed)
        token = uuid.uuid4().hex[:8]
        futures = {}
        for number in pending:
            future = client.submit(
                run_packed,
                blob,
                job.key,
                chunking.shape,
                chunking.chunk,
                number,
                session,
                key=f"perturb-sweep-{job.key[:10]}-{token}-{number}",
                pure=False,
            )
            futures[future] = number
        orphaned: list[int] = []
        try:
            with watched(client, futures) as fired:
                for future in as_completed(futures, loop=client.loop):
                    if fired:
                        break
                    number = futures[future]
                    try:
                        # a result lost with its worker after it finished is recomputed: waits
                        result = future.result()
                    except FutureCancelledError as exc:
                        # the scattered job went down with the only worker holding it (a worker
                        # that joined after the scatter has no copy): not the chunk's fault,
                        # sent again
                        orphaned.append(number)
                        lost[number] = " ".join(f"{type(exc).__name__}: {exc}".split())
                        continue
                    except Exception as exc:  # noqa: BLE001 - a chunk that kept killing workers
                        lost[number] = " ".join(f"{type(exc).__name__}: {exc}".split())
                        continue
                    cpu += result.get("cpu", 0.0)
                    clock = time.perf_counter()
                    write(number, result)
                    writing += time.perf_counter() - clock
                    tasks += 1
                    done += _points(chunking, number)
                    notify(label, done, total)
                    future.release()
        except BaseException:
            client.cancel(list(futures))
            raise
        rounds += 1
        pending = orphaned if rounds <= SWEEP_RESCATTERS else []
        for number in pending:
            del lost[number]
    return RunStats(tuple(sorted(lost.items())), tasks, cpu, writing)


def _call_packed(blob: bytes, key: str, function, args: tuple):
    """A task of :func:`run_calls`: ``function(payload, *args)``, the payload unpacked once per
    worker process."""
    payload = _JOBS.get(key)
    if payload is None:
        import cloudpickle

        payload = _JOBS[key] = cloudpickle.loads(blob)
    return function(payload, *args)


def run_calls(
    cluster: Cluster, function, payload, calls: list[tuple], *, label: str, on_result=None,
    done: int = 0, total: int | None = None, sizes: list[int] | None = None,
) -> list:  # fmt: skip
    """``function(payload, *args)`` for each ``args`` of ``calls`` on the cluster, the payload
    (a problem, a problem from a file travelling by value) sent to every worker once; the results
    in the order of ``calls``. A call whose worker died again and again gives the exception in its
    place (the others are kept).

    ``on_result(index, result)``, if given, is called here as each call finishes (a store
    written chunk by chunk; the result is then not kept: None in its place); the progress counts
    ``sizes[index]`` for each (default 1: the calls) from ``done`` of ``total``."""
    from distributed import as_completed

    client = cluster.client
    blob = scatter(client, pickled(payload, payload))
    key = uuid.uuid4().hex
    futures = {
        client.submit(_call_packed, blob, key, function, tuple(args), pure=False): i
        for i, args in enumerate(calls)
    }
    results: list = [None] * len(calls)
    total = len(calls) if total is None else total
    notify(label, done, total)
    try:
        with watched(client, futures) as fired:
            for future in as_completed(futures, loop=client.loop):
                if fired:
                    break
                index = futures[future]
                try:
                    result = future.result()
                except Exception as exc:  # noqa: BLE001 - a call that kept killing its workers
                    results[index] = exc
                else:
                    if on_result is None:
                        results[index] = result
                    else:
                        on_result(index, result)
                done += 1 if sizes is None else sizes[index]
                notify(label, done, total)
                future.release()
    except BaseException:
        client.cancel(list(futures))
        raise
    return results


def _points(chunking: Chunking, number: int) -> int:
    return math.prod(s.stop - s.start for s in chunking.region(number))


def importable(name: str) -> bool:
    """Whether ``name`` can be imported here (the extra ``perturb[sweep]`` installed)."""
    return importlib.util.find_spec(name) is not None
