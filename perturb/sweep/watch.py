"""Watching a Dask cluster's workers while a sweep or a phase diagram waits on it: a cluster
left without workers (an existing scheduler whose workers were stopped, or never started) ends
the run with a failed status ("no worker: start one, then --resume") after
:data:`~perturb._defaults.SWEEP_NO_WORKER_SECONDS`, where Dask would raise its TimeoutError or
wait for ever.

Only the client's methods are called here: Dask itself is imported by :mod:`.driver`.
"""

from __future__ import annotations

import contextlib
import time

from perturb._defaults import SWEEP_NO_WORKER_SECONDS, SWEEP_WORKER_POLL_SECONDS
from perturb.errors import SweepError

__all__ = ["no_worker", "scatter", "watched", "workers_now"]


def no_worker(client) -> SweepError:
    """The failed status of a cluster that has had no worker for too long."""
    address = getattr(client.scheduler, "address", None) or "the cluster"
    return SweepError(
        f"no worker: the Dask cluster at {address} has had no worker for "
        f"{SWEEP_NO_WORKER_SECONDS:g} s: start one (dask worker {address}), then run the same "
        "command again with --resume (what is written is kept)"
    )


def workers_now(client) -> int:
    """The workers connected to the client's scheduler now (0 when it does not answer)."""
    try:
        return len(client.scheduler_info().get("workers", {}))
    except Exception:  # noqa: BLE001 - a scheduler that does not answer has no worker for us
        return 0


def scatter(client, data):
    """``data`` sent to every worker: waits :data:`SWEEP_NO_WORKER_SECONDS` for a first worker,
    then a failed status, not Dask's TimeoutError."""
    if not workers_now(client):
        try:
            client.wait_for_workers(1, timeout=SWEEP_NO_WORKER_SECONDS)
        except (TimeoutError, OSError):
            raise no_worker(client) from None
    try:
        return client.scatter(data, broadcast=True, hash=False)
    except (TimeoutError, OSError) as exc:
        if not workers_now(client):  # the workers left while the job was sent
            raise no_worker(client) from None
        address = getattr(client.scheduler, "address", None) or "the cluster"
        detail = " ".join(f"{type(exc).__name__}: {exc}".split())[:200]
        raise SweepError(
            f"the job could not be sent to the workers of {address} ({detail}): check the "
            "cluster's network, then run the same command again with --resume"
        ) from None


@contextlib.contextmanager
def watched(client, futures):
    """While the block waits on ``futures``, watch the cluster's workers: none for
    :data:`SWEEP_NO_WORKER_SECONDS` cancels the futures and ends the block with a failed status
    ("no worker"), where Dask would wait for ever."""
    import threading

    stop = threading.Event()
    fired = []

    def watch():
        alone = None
        while not stop.wait(SWEEP_WORKER_POLL_SECONDS):
            if workers_now(client):
                alone = None
                continue
            alone = time.monotonic() if alone is None else alone
            if time.monotonic() - alone > SWEEP_NO_WORKER_SECONDS:
                fired.append(True)
                with contextlib.suppress(Exception):
                    client.cancel(list(futures))
                return

    thread = threading.Thread(target=watch, daemon=True, name="perturb-worker-watch")
    thread.start()
    try:
        yield fired
    finally:
        stop.set()
        thread.join(SWEEP_WORKER_POLL_SECONDS * 2)
    if fired:
        raise no_worker(client)
