"""A basin study's work, cut in chunks: what a worker is sent, what it computes, what it returns.

A :class:`BasinJob` holds all a worker needs — the motion (symbolic equations, picklable), the
catalogue, the initial states' rule (a grid of two components, or N states drawn uniformly in a
box from a seed) and the cap — and nothing of the problem's class, so that a problem from a file
needs no import on the workers. :func:`basin_chunk` classifies the states of one chunk
(:func:`perturb.dynamics.classify.classify`) and returns their codes, periods and final states,
with the orbits it found by recurrence (merged by the driver, which renumbers them).
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import time

import numpy as np
from attrs import field, frozen

from perturb.sweep.grid import Chunking

__all__ = ["BasinJob", "basin_chunk", "request_fingerprint"]


@frozen
class BasinJob:
    """A basin study's request, as its workers see it.

    Attributes
    ----------
    motion : DrivenMotion
    catalogue : Catalogue
    axes : tuple of (str, ndarray)
        Grid mode: the store's axes, the vertical component first, then the horizontal one
        (C order: a chunk is whole rows). Samples mode: ``(("sample", 0..N-1),)``.
    box : tuple of (str, float, float)
        Samples mode: each sampled component with its range (empty in grid mode).
    base : ndarray, shape (m,)
        The state's components that are not on the grid or in the box.
    cap : int
        Drive periods at most.
    backend : str
    seed : int
        Of the random states (samples mode).
    chunk : tuple of int
        The chunk's shape (a store keeps its own).
    """

    motion: object = field(eq=False)
    catalogue: object = field(eq=False)
    axes: tuple = field(eq=False)
    box: tuple
    base: np.ndarray = field(eq=False)
    cap: int
    backend: str
    seed: int
    chunk: tuple

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(values) for _, values in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def sampled(self) -> bool:
        return bool(self.box)

    @property
    def chunking(self) -> Chunking:
        return Chunking(self.shape, self.chunk)

    def states(self, indices) -> np.ndarray:
        """The initial states of the points numbered ``indices`` (C order), shape (M, m)."""
        indices = np.asarray(indices, dtype=np.int64)
        if self.sampled:
            return _sampled(self)[indices]
        out = np.repeat(self.base[None, :], indices.size, axis=0)
        where = np.unravel_index(indices, self.shape)
        for (name, values), w in zip(self.axes, where, strict=True):
            out[:, self.motion.names.index(name)] = np.asarray(values)[w]
        return out

    def fingerprint(self, version: str) -> str:
        """What the study's store holds (:func:`perturb.dynamics.chunks.request_fingerprint` of this job)."""
        chart = self.catalogue
        return request_fingerprint(
            chart.problem, chart.values, chart.order, chart.phase, self.axes, self.box,
            self.base, self.cap, self.backend, self.seed, version,
        )  # fmt: skip


def request_fingerprint(
    problem: str, values, order: int, phase: float, axes, box, base, cap: int, backend: str,
    seed: int, version: str,
) -> str:  # fmt: skip
    """The fingerprint of a basin study: the problem and its values, the section, the states'
    rule, the cap and the integrator (a resumed run must be this very study); known before the
    catalogue is computed, so that a store is checked before any work."""
    what = {
        "kind": "basins",
        "problem": problem,
        "values": {k: float(v) for k, v in sorted(dict(values).items())},
        "order": int(order),
        "phase": float(phase),
        "axes": [[n, np.asarray(v, dtype=float).tolist()] for n, v in axes],
        "box": [list(b) for b in box],
        "base": np.asarray(base, dtype=float).tolist(),
        "cap": int(cap),
        "backend": backend,
        "seed": int(seed),
        "version": version,
    }
    return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()


@functools.lru_cache(maxsize=2)
def _sampled_cached(m: int, base: tuple, columns: tuple, low: tuple, high: tuple,
                    count: int, seed: int) -> np.ndarray:  # fmt: skip
    rng = np.random.default_rng(seed)
    draws = rng.random((count, len(columns)))
    out = np.repeat(np.asarray(base)[None, :], count, axis=0)
    for j, c in enumerate(columns):
        out[:, c] = low[j] + (high[j] - low[j]) * draws[:, j]
    return out


def _sampled(job: BasinJob) -> np.ndarray:
    """Every random initial state of ``job`` (drawn once per process, the same on every one)."""
    names = job.motion.names
    columns = tuple(names.index(n) for n, _, _ in job.box)
    return _sampled_cached(
        len(names), tuple(job.base.tolist()), columns,
        tuple(lo for _, lo, _ in job.box), tuple(hi for _, _, hi in job.box), job.size, job.seed,
    )  # fmt: skip


def basin_chunk(job: BasinJob, number: int) -> dict:
    """Classify the states of chunk ``number`` (runs on a worker, or here).

    Returns
    -------
    dict
        ``code``, ``periods`` (int arrays over the chunk's points, C order), ``final`` and
        ``initial`` (shape (M, m)), ``found`` (the orbits found, as dicts of their points),
        ``cpu`` (seconds).
    """
    from perturb.dynamics.classify import classify
    from perturb.dynamics.ensemble import ensemble

    clock = time.process_time()
    indices = job.chunking.indices(number)
    states = job.states(indices)
    integrator = ensemble(job.motion, job.catalogue.phase, job.backend)
    result = classify(integrator, job.catalogue, states, job.cap)
    return {
        "code": result.codes.astype(np.int16),
        "periods": result.periods.astype(np.int32),
        "final": result.final,
        "initial": states,
        "found": [
            {"points": f.points.tolist(), "radius": f.radius, "name": f.name} for f in result.found
        ],  # fmt: skip
        "cpu": time.process_time() - clock,
    }
