"""Basins of attraction of a driven problem: which steady state each initial state reaches.

:func:`basins` classifies every initial state of a grid over two components of the state (or N
states drawn uniformly in a box, ``samples=N``: a basin-stability estimate, in any number of
dimensions) on the section at drive phase φ: its true motion's stroboscopic returns against the
catalogue of proved steady states (:mod:`perturb.dynamics.attractors`,
:mod:`perturb.dynamics.classify`). The states are cut in chunks (whole rows), run in this process
or on Dask (:func:`perturb.sweep.driver.run_calls`: a LocalCluster or a scheduler) and written as
each finishes into a resumable Zarr store (:class:`perturb.sweep.store.MapStore`: the sweep's
rules; the catalogue is stored beside the map, so a resumed run classifies the same way).

The result, :class:`BasinMap`, holds an ``xarray.Dataset`` (``code``: one code per
attractor, the outcomes that are not attractors negative, meanings in its attributes), the basin
fractions with their binomial sampling error, and the first-order slow flow's separatrix (the
saddle's stable manifold, :meth:`perturb.dynamics.slowflow.SlowFlow.separatrix`) mapped to the
section, drawn over the map.
"""

from __future__ import annotations

import enum
import json
import math
import time
from collections.abc import Mapping

import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    BASIN_DEFAULT_PERIODS,
    BASIN_LOCAL_POINTS,
    BASIN_POINT_SECONDS,
    BASIN_SEED,
    SWEEP_CONNECT_SECONDS,
    SWEEP_MEMORY_BYTES,
)
from perturb.dynamics.classify import Outcome, merge_found, outcome_meanings
from perturb.dynamics.mapping import assemble, meanings, open_sink, stored_catalogue
from perturb.errors import InvalidParameterError, MissingDependencyError, PerturbError, bad_value

__all__ = ["BasinMap", "BasinStatus", "Fraction", "basins"]


class BasinStatus(enum.Enum):
    """How a basin study ended; the values are the messages."""

    OK = "every initial state classified"
    INCOMPLETE = "some chunks could not be computed (their workers died); run again with resume"
    NO_STABLE_STATE = "no stable steady state was found: nothing to classify the motion against"

    @property
    def success(self) -> bool:
        return self is BasinStatus.OK


@frozen
class Fraction:
    """The share of the initial states with one code.

    Attributes
    ----------
    code : int
    name : str
        The attractor's name, or the outcome's words.
    count : int
    fraction : float
        count / states classified.
    error : float
        The binomial sampling error :math:`\\sqrt{f(1-f)/n}`.
    """

    code: int
    name: str
    count: int
    fraction: float
    error: float


@frozen
class BasinMap:
    """A basin study's result.

    Attributes
    ----------
    dataset : xarray.Dataset
        Grid mode: dimensions (vertical, horizontal) named by the state's components; samples
        mode: dimension ``sample``. Variables ``code``, ``periods``, ``final`` (the last return
        computed), ``initial`` (samples mode); meanings in their attributes.
    catalogue : Catalogue
        Its attractors (with those found by recurrence) give the codes 0, 1, ...
    fractions : tuple of Fraction
    separatrix : tuple of ndarray
        Curves of shape (K, 2) in the grid's (horizontal, vertical) components (empty in
        samples mode, or when the slow flow is not planar).
    status : BasinStatus
    message : str
    axes : tuple of str
        Grid mode: (horizontal, vertical); samples mode: the sampled components.
    """

    dataset: object = field(eq=False)
    catalogue: object = field(eq=False)
    fractions: tuple = field(converter=tuple)
    separatrix: tuple = field(converter=tuple, eq=False)
    status: BasinStatus
    message: str
    axes: tuple = field(converter=tuple)

    @property
    def sampled(self) -> bool:
        return "sample" in getattr(self.dataset, "dims", ())

    def names(self) -> dict[int, str]:
        """``{code: name}`` of every code a point may hold."""
        out = {k: s.name for k, s in enumerate(self.catalogue.attractors)}
        out.update(outcome_meanings())
        return out

    def decoded(self):
        """The map of names (an :class:`xarray.DataArray` of strings, like ``code``)."""
        codes = np.asarray(self.dataset["code"].values)
        names = self.names()
        lookup = np.vectorize(lambda c: names.get(int(c), f"code {int(c)}"), otypes=[object])
        return self.dataset["code"].copy(data=lookup(codes).astype(str))


# ---------------------------------------------------------------------------------- requests
def _cap(periods) -> int:
    if isinstance(periods, bool) or not isinstance(periods, int | np.integer) or periods < 1:
        raise bad_value("periods", periods, "give the cap of drive periods, a whole number >= 1 "
                        "(--periods 1000)", InvalidParameterError)  # fmt: skip
    return int(periods)


def _grid_axes(grid, names: tuple, label: str) -> list[tuple[str, np.ndarray]]:
    """Two axes over components of the state, horizontal first."""
    from perturb.sweep.api import axes_of

    axes = axes_of(grid) if grid is not None else ()
    if len(axes) != 2:
        raise InvalidParameterError(
            f"--grid (grid=) {[a.spec or a.name for a in axes]}: a basin map needs two "
            f"coordinates of the state, e.g. --grid {names[0]}=-3:3:200 --grid "
            f"{names[len(names) // 2] if len(names) > 1 else names[0]}=-3:3:200 (or --samples N)"
        )
    out = []
    for axis in axes:
        if axis.name not in names:
            raise InvalidParameterError(
                f"--grid {axis.spec or axis.name!r}: {axis.name!r} is not a coordinate of the "
                f"state of {label}; give two of {', '.join(names)}"
            )
        values = np.asarray(axis.values, dtype=float)
        if values.size < 2:
            raise InvalidParameterError(f"--grid {axis.spec!r}: give at least 2 values "
                                        "(START:STOP:N, N >= 2)")  # fmt: skip
        out.append((axis.name, values))
    if out[0][0] == out[1][0]:
        raise InvalidParameterError(f"--grid {out[0][0]} twice: give two different coordinates "
                                    "of the state")  # fmt: skip
    return out


def _parse_box(text, names: tuple, label: str) -> tuple[str, float, float]:
    """``NAME=LOW:HIGH`` (or an axis, its extremes) of a sampled component."""
    from perturb.axis import parse_axis

    if not isinstance(text, str):
        name, (low, high) = text
        text = f"{name}={low}:{high}"
    name, _, rest = text.partition("=")
    parts = rest.split(":")
    try:
        if len(parts) == 2:
            low, high = float(parts[0]), float(parts[1])
        else:
            values = parse_axis(text).values
            low, high = min(values), max(values)
    except ValueError:
        raise InvalidParameterError(f"--grid {text!r}: write NAME=LOW:HIGH") from None
    name = name.strip()
    if name not in names:
        raise InvalidParameterError(f"--grid {text!r}: {name!r} is not a coordinate of the "
                                    f"state of {label}; give some of {', '.join(names)}")  # fmt: skip
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise InvalidParameterError(f"--grid {text!r}: give finite LOW < HIGH")
    return name, low, high


def _samples(samples) -> int:
    if isinstance(samples, bool) or not isinstance(samples, int | np.integer) or samples < 1:
        raise bad_value("samples", samples, "give the number of random initial states, a whole "
                        "number >= 1 (--samples 10000)", InvalidParameterError)  # fmt: skip
    return int(samples)


# ---------------------------------------------------------------------------------- the study
def require_xarray() -> None:
    """Raise :class:`~perturb.errors.MissingDependencyError` unless xarray is installed: a basin
    map is an ``xarray.Dataset`` (the extra ``perturb[sweep]``), checked before any work."""
    from perturb._install import install_hint, installed

    if not installed("xarray"):
        raise MissingDependencyError(f"a basin map is an xarray Dataset: {install_hint('sweep')}")


def basins(
    problem,
    grid=None,
    *,
    samples: int | None = None,
    phase: float = 0.0,
    periods: int = BASIN_DEFAULT_PERIODS,
    order: int = 1,
    base: Mapping | None = None,
    seed: int = BASIN_SEED,
    output=None,
    resume: bool = False,
    workers: int | None = None,
    scheduler: str | None = None,
    client=None,
    timeout: float = SWEEP_CONNECT_SECONDS,
    yes: bool = False,
    backend: str | None = None,
    chunk_points: int | None = None,
) -> BasinMap:
    """The basins of attraction of the driven ``problem`` (see the module notes).

    Parameters
    ----------
    problem : problems.base.Problem or perturb.validation.Model
        A driven problem at its parameter values.
    grid : sequence of str or mapping
        Grid mode: two coordinates of the state, horizontal first
        (``["x=-3:3:200", "xdot=-3:3:200"]``). With ``samples``: the box the states are drawn in,
        any number of components (``["x=-3:3", "xdot=-3:3"]``).
    samples : int, optional
        Draw this many initial states uniformly in the box (seed ``seed``) instead of a grid.
    phase : float
        The section's drive phase φ (radians): the initial states are states at θ = φ.
    periods : int
        The cap: drive periods a state is followed at most.
    order : int
        The series' order whose branches seed the catalogue's shooting.
    base : mapping, optional
        Values of the state's components that are neither on the grid nor sampled (default 0).
    output : path, optional
        A Zarr store, created (or continued with ``resume``) and written chunk by chunk.
    resume : bool
        Continue the study in ``output``: no point computed twice, none lost.
    workers : int, optional
        Worker processes of a LocalCluster; 0: in this process. Default: in this process up to
        :data:`~perturb._defaults.BASIN_LOCAL_POINTS` states, else one worker a core.
    scheduler, client, timeout
        As for :func:`perturb.sweep`.
    yes : bool
        Confirm a request past :func:`perturb.cost.check_cost`'s limits.
    backend : {"heyoka", "numpy"}, optional
        The ensemble integrator (default heyoka when installed).
    chunk_points : int, optional
        States per chunk (default: about :data:`~perturb._defaults.SWEEP_TASK_SECONDS` of work).

    Returns
    -------
    BasinMap
        ``status`` NO_STABLE_STATE (nothing computed, the reasons in ``message``) when the
        catalogue holds no attractor; INCOMPLETE when chunks were lost.

    Raises
    ------
    perturb.errors.InvalidParameterError
        Bad input, checked before any work: a grid that is not two coordinates of the state, a
        component or base value not in the state space, a cap below 1, a store holding anything
        else, too much work without ``yes``.

    Examples
    --------
    The bistable forced Duffing (Omega = 1.05): which of its two stable responses each state of
    a coarse grid reaches.

    >>> import perturb
    >>> from problems import get_problem
    >>> duffing = get_problem("forced-duffing").create(Omega=1.05)
    >>> result = perturb.basins(duffing, ["x=-3:3:8", "xdot=-3:3:8"])
    >>> [f.name for f in result.fractions], sum(f.count for f in result.fractions)
    (['lower', 'upper'], 64)
    >>> [s.name for s in result.catalogue.saddles]
    ['middle']
    """
    from perturb.dynamics.attractors import catalogue as make_catalogue
    from perturb.dynamics.attractors import decode
    from perturb.dynamics.chunks import BasinJob
    from perturb.dynamics.ensemble import ensemble
    from perturb.dynamics.motion import motion_of

    require_xarray()
    cap = _cap(periods)
    if not (isinstance(phase, int | float) and math.isfinite(phase)):
        raise bad_value("phase", phase, "give a finite drive phase (radians)",
                        InvalidParameterError)  # fmt: skip
    motion = motion_of(problem)
    names = motion.names
    base_state = motion.state(base or {}, "base")
    ensemble(motion, phase, backend)  # the backend checked now
    backend = ensemble(motion, phase, backend).backend
    if samples is not None:
        count = _samples(samples)
        items = [grid] if isinstance(grid, str) else list((grid or {}).items()) if isinstance(
            grid, Mapping) else list(grid or ())  # fmt: skip
        if not items:
            raise InvalidParameterError("--grid: give the box the states are drawn in, e.g. "
                                        f"--grid {names[0]}=-3:3 (with --samples)")  # fmt: skip
        box = tuple(_parse_box(t, names, motion.label) for t in items)
        if len({b[0] for b in box}) != len(box):
            raise InvalidParameterError("--grid: a component twice; give each once")
        axes = None  # made once the request is known to be affordable
        size = count
    else:
        box = ()
        horizontal, vertical = _grid_axes(grid, names, motion.label)
        axes = [vertical, horizontal]
        size = math.prod(len(v) for _, v in axes)
    if resume and output is None:
        raise InvalidParameterError("`resume` = True needs `output`: the store to continue")
    from perturb.cost import Cost, check_cost, response_cost

    # a state the cap stops costs cap periods: a cap past the default scales the estimate
    stretch = max(1.0, cap / BASIN_DEFAULT_PERIODS)
    work = Cost(f"{size:,} initial states, a cap of {cap:,} periods", size,
                size * BASIN_POINT_SECONDS * stretch)  # fmt: skip
    check_cost(work + response_cost(1, order, 0), yes)  # the catalogue's series at its order
    if output is None:
        need = size * (2 * motion.m * 8 + 2 + 4)
        if need > SWEEP_MEMORY_BYTES:
            raise InvalidParameterError(
                f"the {size:,} initial states would take about {need / 2**30:,.3g} GiB in memory "
                f"(more than {SWEEP_MEMORY_BYTES / 2**30:g} GiB): write them to a store, "
                "--output STORE (output= in Python), which holds one chunk at a time"
            )
    if axes is None:
        axes = [("sample", np.arange(size, dtype=float))]
    local = workers == 0 or (workers is None and scheduler is None and client is None
                             and size <= BASIN_LOCAL_POINTS)  # fmt: skip
    if output is not None or not local:
        from perturb.sweep.api import require_extra

        require_extra()
    if output is not None:  # the store checked before any work (and its lock free now)
        import perturb
        from perturb.dynamics.chunks import request_fingerprint
        from perturb.sweep.lock import StoreLock
        from perturb.sweep.mapstore import MapStore

        fingerprint = request_fingerprint(
            motion.label, problem.case().values, order, float(phase), axes, box,
            base_state, cap, backend, int(seed), perturb.__version__,
        )  # fmt: skip
        if MapStore.check_map(output, fingerprint, resume) is not False:
            StoreLock(output).acquire().release()
    stored = stored_catalogue(output) if resume else None
    found_before: list = []
    if stored is not None:
        chart, found_before = stored
        chart = decode(chart)
    else:
        from perturb.progress import stage

        with stage("basins: the steady states, shot"):
            chart = make_catalogue(problem, order, float(phase), motion)
    if not chart.status.success:
        return BasinMap(None, chart, (), (), BasinStatus.NO_STABLE_STATE, chart.message,
                        _axis_names(axes, box))  # fmt: skip
    from perturb.sweep.driver import chunk_points as points_per_chunk

    chunk_size = chunk_points or points_per_chunk(BASIN_POINT_SECONDS, size, workers or 2)
    from perturb.sweep.grid import Chunking

    chunk = Chunking.of(tuple(len(v) for _, v in axes), chunk_size).chunk
    job = BasinJob(motion, chart, tuple(axes), box, base_state, cap, backend, int(seed), chunk)
    sink = open_sink(job, output, resume, chart)
    try:
        return _run(job, sink, found_before, local, workers, scheduler, client, timeout, problem)
    finally:
        sink.close()


def _axis_names(axes, box) -> tuple:
    return tuple(b[0] for b in box) if box else (axes[1][0], axes[0][0])


def _run(job, sink, found, local, workers, scheduler, client, timeout, problem) -> BasinMap:
    from perturb.dynamics.attractors import encode_state
    from perturb.dynamics.chunks import basin_chunk
    from perturb.progress import notify

    chart = job.catalogue
    known = len(chart.attractors)
    scale = chart.scale
    pending = sink.pending()
    session = sink.begin_session()
    chunking = job.chunking
    sizes = {n: math.prod(s.stop - s.start for s in chunking.region(n)) for n in pending}
    done = job.size - sum(sizes.values())
    label = f"basins {chart.problem}"
    lost: list[str] = []
    cpu = [0.0]

    def write(number: int, result: dict) -> None:
        cpu[0] += float(result.get("cpu", 0.0))
        codes = np.asarray(result["code"]).astype(np.int16)
        if result["found"]:
            from perturb.dynamics.attractors import StateKind, SteadyOrbit

            new = tuple(SteadyOrbit(f["name"], StateKind.FOUND, f["points"], radius=f["radius"])
                        for f in result["found"])  # fmt: skip
            before = len(found)
            mapping = merge_found(found, new, scale)
            local_codes = codes.copy()
            for i, j in mapping.items():
                codes[local_codes == known + i] = known + j
            if len(found) > before:
                sink.update({"found": json.dumps([encode_state(f) for f in found])})
        arrays = {name: result[name] for name in ("periods", "final", "initial")}
        arrays["code"] = codes
        arrays["session"] = np.full(codes.shape, session, dtype=np.int32)
        sink.write(number, arrays)

    clock = time.perf_counter()
    if local:
        notify(label, done, job.size)
        for number in pending:
            write(number, basin_chunk(job, number))
            done += sizes[number]
            notify(label, done, job.size)
    else:
        from perturb.sweep.driver import Cluster, run_calls

        with Cluster(workers, scheduler, client, timeout) as cluster:
            results = run_calls(
                cluster, basin_chunk, job, [(n,) for n in pending], label=label,
                on_result=lambda i, r: write(pending[i], r), done=done, total=job.size,
                sizes=[sizes[n] for n in pending],
            )  # fmt: skip
        lost = [f"chunk {pending[i]}: {r}" for i, r in enumerate(results) if r is not None]
    seconds = time.perf_counter() - clock
    left = sink.pending() if hasattr(sink, "finish") else []
    if hasattr(sink, "finish"):
        sink.finish()
    from perturb.dynamics.attractors import confirm

    chart_now = chart.with_found(tuple(confirm(job.motion, f, chart.phase) for f in found))
    dataset = assemble(job, sink, chart_now)
    fractions = _fractions(dataset, chart_now)
    dataset.attrs.update(
        seconds=seconds, task_cpu_seconds=cpu[0], points_computed=sum(sizes.values()),
        fractions=json.dumps([[f.code, f.name, f.count, f.fraction, f.error] for f in fractions]),
    )  # fmt: skip
    axes = _axis_names(job.axes, job.box)
    curves = () if job.sampled else _separatrix(problem, job, chart)
    if lost or left:
        why = "; ".join(lost[:1]) or f"{len(left)} chunks not written"
        return BasinMap(dataset, chart_now, fractions, curves, BasinStatus.INCOMPLETE,
                        f"{BasinStatus.INCOMPLETE.value} ({why})", axes)  # fmt: skip
    return BasinMap(dataset, chart_now, fractions, curves, BasinStatus.OK,
                    BasinStatus.OK.value, axes)  # fmt: skip


def _fractions(dataset, chart) -> tuple[Fraction, ...]:
    from perturb.sweep.store import code_counts

    counts = code_counts(dataset["code"])
    counts.pop(Outcome.NOT_COMPUTED.code, None)
    total = sum(counts.values())
    names, _ = meanings(chart)
    out = []
    for code in sorted(counts, key=lambda c: (c < 0, abs(c))):
        f = counts[code] / total if total else math.nan
        error = math.sqrt(f * (1 - f) / total) if total else math.nan
        out.append(Fraction(int(code), names.get(code, f"code {code}"), counts[code], f, error))
    return tuple(out)


def _separatrix(problem, job, chart) -> tuple:
    """The first-order slow flow's separatrix in the grid's (horizontal, vertical) components."""
    from perturb.dynamics.slowflow import slow_flow_of

    names = job.motion.names
    box = [(b - 1.0, b + 1.0) for b in job.base]
    for name, values in job.axes:
        box[names.index(name)] = (float(np.min(values)), float(np.max(values)))
    try:
        curves = slow_flow_of(problem, 1).separatrix(box, chart.phase)
    except (PerturbError, ArithmeticError, ValueError):
        return ()
    (vertical, _), (horizontal, _) = job.axes
    h, v = names.index(horizontal), names.index(vertical)
    return tuple(np.column_stack([c[:, h], c[:, v]]) for c in curves)
