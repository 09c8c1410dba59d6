"""The work of one task: :func:`run_chunk` computes a chunk of points on a worker.

It imports neither Dask nor the store: it takes the job (spec and derivation plan) and the flat
indices of its points, and returns plain arrays, one per variable of
:func:`perturb.sweep.quantities.variables`, with the points along the first axis. A point that
fails is recorded with its status and reason; the chunk goes on. The derivation is rebuilt once
per worker process: the problem's own caches (memory, and disk when enabled) keep it.
"""

from __future__ import annotations

import contextlib
import gc
import math
import time
import traceback
import warnings
from collections.abc import Sequence

import numpy as np

from perturb._defaults import VALIDITY_ESTIMATE_LIMIT
from perturb.cache import held_warnings
from perturb.domain import DomainCheck, series_domain
from perturb.errors import PerturbError
from perturb.sweep.evaluate import (
    DomainScreen,
    SolutionFailed,
    evaluate_group,
    evaluate_one,
    group_arrays,
)
from perturb.sweep.quantities import CHECK_CODES, LEGACY_NONE, check_names, variables
from perturb.sweep.spec import SweepJob
from perturb.sweep.status import NOT_COMPUTED, PointStatus, code_of
from perturb.validation.model import parameter_value_of

__all__ = ["ChunkResult", "run_chunk", "validate_point"]

#: Per worker process: a domain screen per solution (keyed by the solution object's id, the
#: solution kept alive beside it so that the id is not reused).
_SCREENS: dict[int, tuple[object, DomainScreen]] = {}

#: What :func:`run_chunk` returns: variable name -> array (points first), plus ``"seconds"`` and
#: ``"cpu"`` (the chunk's wall and CPU time).
ChunkResult = dict


def _empty(job: SweepJob, n_points: int, n_components: int) -> dict[str, np.ndarray]:
    sizes = {
        "component": n_components,
        "time": len(job.spec.times),
        "multiplier": n_components,
        "check": len(check_names()),
    }
    out = {}
    for var in variables(job.spec.validate):
        shape = (n_points, *(sizes[d] for d in var.dims))
        dtype = object if var.dtype == "str" else var.dtype
        out[var.name] = np.full(shape, var.fill, dtype=dtype)
    return out


def _screen(solution) -> DomainScreen:
    entry = _SCREENS.get(id(solution))
    if entry is None or entry[0] is not solution:
        entry = (solution, DomainScreen(solution))
        _SCREENS[id(solution)] = entry
    return entry[1]


def _describe(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    if isinstance(exc, PerturbError | ValueError):
        return text or type(exc).__name__
    where = traceback.extract_tb(exc.__traceback__)[-1:] if exc.__traceback__ else []
    at = f" at {where[0].filename.rsplit('/', 1)[-1]}:{where[0].lineno}" if where else ""
    return f"internal error ({type(exc).__name__}: {text}{at})"


class _Point:
    """One point's model, solution, status and notes while its chunk is computed."""

    __slots__ = ("model", "solution", "status", "reason", "notes", "domain")

    def __init__(self):
        self.model = None
        self.solution = None
        self.domain = None
        self.status = PointStatus.OK
        self.reason = ""
        self.notes: list[str] = []

    def fail(self, status: PointStatus, reason: str) -> None:
        if self.status is PointStatus.OK:
            self.status, self.reason = status, reason

    def note(self, messages) -> None:
        for message in messages:
            if message not in self.notes:
                self.notes.append(message)


def _recorded(point: _Point, function, *args):
    """``function(*args)``, its warnings noted on ``point``."""
    with held_warnings(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            return function(*args)
        finally:
            point.note(str(w.message) for w in caught)


def _build(job: SweepJob, values: dict, caught: list) -> _Point:
    """The point's model and solution; warnings (appended to ``caught``) are noted on it."""
    spec, point = job.spec, _Point()
    seen = len(caught)
    try:
        point.model = job.derivation.model_at(spec.model, values)
        point.solution = point.model.solve(spec.order)
    except (PerturbError, ValueError) as exc:
        status = PointStatus.INVALID_PARAMETERS if point.model is None else PointStatus.FAILED
        point.fail(status, _describe(exc))
    except Exception as exc:  # noqa: BLE001 - recorded, the sweep goes on
        point.fail(PointStatus.FAILED, _describe(exc))
    if len(caught) > seen:
        point.note(str(w.message) for w in caught[seen:])
    if point.solution is not None and not point.solution.success:
        point.fail(
            PointStatus.CONSTRUCTION_FAILED,
            f"{point.solution.status.value}: {point.solution.message}",
        )
    return point


@contextlib.contextmanager
def _collection_paused():
    """No cyclic garbage collection while a chunk's points are made: each point allocates a few
    objects that reference counting frees, yet every few thousand allocations would make the
    collector walk every sympy expression alive (most of the time of a cheap point)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _points(job: SweepJob, indices: Sequence[int]) -> list[_Point]:
    grid = job.spec.grid
    columns = [column.tolist() for column in grid.columns(indices).values()]
    names = grid.names
    with _collection_paused(), held_warnings(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        return [
            _build(job, dict(zip(names, row, strict=True)), caught)
            for row in zip(*columns, strict=True)
        ]


def _store_evaluation(out, k: int, result: dict) -> None:
    out["period"][k] = result["period"]
    out["frequency"][k] = result["frequency"]
    out["amplitude"][k] = result["amplitude"]
    out["state"][k] = result["state"]


def _domain(point: _Point, check) -> None:
    """The point's domain check (kept for its validation), and its status."""
    point.domain = check
    if check.ok and check.beyond_validity:  # flagged in the point's warnings
        point.note([check.validity_note()])
    if not check.ok:
        reasons = "; ".join(check.reasons)
        point.fail(PointStatus.OUTSIDE_DOMAIN, f"the series is outside its domain: {reasons}")


def _evaluate_vectorised(job, points: list[_Point], where: list[int], out) -> list[int]:
    """Evaluate the points of one solution together; returns those left for the per-point route."""
    models = [points[k].model for k in where]
    solution = points[where[0]].solution
    try:
        pv, values = group_arrays(models)
        with held_warnings(), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = evaluate_group(solution, pv, values, np.asarray(job.spec.times))
            domains = _screen(solution).check(pv, values, result["omega"])
    except (SolutionFailed, PerturbError, ValueError, ArithmeticError):
        return where  # some point is singular: find which, one by one
    if caught:
        return where  # a warning belongs to some point: say to which
    for name in ("period", "frequency", "amplitude", "state"):
        out[name][where] = result[name]
    for i, k in enumerate(where):
        _domain(points[k], domains[i])
    return []


def _evaluate_single(job, point: _Point, out, k: int):
    """The point through its model's own maps; returns ``(parameter value, values, omega)`` for
    its domain check (made for all such points of a solution at once), or None if it failed."""
    times = np.asarray(job.spec.times)
    model, solution = point.model, point.solution
    try:
        pv = parameter_value_of(model)
        values = model.symbol_values()
        omega = _recorded(point, solution.coefficients, pv, values)[0]
        result = _recorded(point, evaluate_one, model, solution, times)
    except SolutionFailed as exc:
        point.fail(PointStatus.NOT_FINITE, _describe(exc))
        return None
    except Exception as exc:  # noqa: BLE001 - recorded, the sweep goes on
        point.fail(PointStatus.FAILED, _describe(exc))
        return None
    _store_evaluation(out, k, result)
    if not (np.all(np.isfinite(result["state"])) and math.isfinite(result["period"])):
        point.fail(
            PointStatus.NOT_FINITE,
            "the solution is not finite at these parameter values (NaN or inf)",
        )
    return pv, values, float(np.asarray(omega))


def _check_domains(points: list[_Point], pending: dict[int, tuple]) -> None:
    """The domain checks of the points evaluated one by one, per solution in one screen."""
    by_solution: dict[int, list[int]] = {}
    for k in pending:
        by_solution.setdefault(id(points[k].solution), []).append(k)
    for where in by_solution.values():
        solution = points[where[0]].solution
        pv = np.array([pending[k][0] for k in where], dtype=float)
        names = dict.fromkeys(name for k in where for name in pending[k][1])
        values = {n: np.array([pending[k][1].get(n, np.nan) for k in where]) for n in names}
        omega = np.array([pending[k][2] for k in where])
        try:
            with held_warnings(), warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                checks = _screen(solution).check(pv, values, omega)
        except Exception as exc:  # noqa: BLE001 - recorded, the sweep goes on
            for k in where:
                points[k].fail(PointStatus.FAILED, "domain check: " + _describe(exc))
            continue
        for k, check in zip(where, checks, strict=True):
            points[k].note(str(w.message) for w in caught)
            _domain(points[k], check)


def _columns(job: SweepJob, indices: Sequence[int]):
    """The chunk's points as :class:`~perturb.case.CasePoints` (None: not offered,
    or its making warned: the per-point route says to which point a warning belongs)."""
    columns = job.spec.grid.columns(indices)
    with held_warnings(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            found = job.derivation.columns_at(job.spec.model, columns)
        except Exception:  # noqa: BLE001 - the per-point route records it point by point
            return None
    return None if caught else found


def _run_columns(job: SweepJob, indices: Sequence[int], out) -> list[PointStatus] | None:
    """The chunk evaluated from its columns, into ``out``: the points' statuses (reasons and notes
    written), or None where the per-point route must do it (a model that does not offer
    columns or does not evaluate its solution directly, a warning, a point that is singular)."""
    found = _columns(job, indices)
    if found is None:
        return None
    spec = job.spec
    valid = np.flatnonzero(found.valid())
    statuses = [PointStatus.OK if not e else PointStatus.INVALID_PARAMETERS for e in found.errors]
    if found.model is not None:
        model = found.model
        with held_warnings(), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                direct = model.case().evaluates_directly
                solution = model.solve(spec.order) if direct else None
            except Exception:  # noqa: BLE001 - the per-point route records it point by point
                return None
        if caught or solution is None:
            return None
        out["epsilon"][valid] = found.epsilon[valid]
        if not solution.success:
            reason = f"{solution.status.value}: {solution.message}"
            for k in valid:
                statuses[k] = PointStatus.CONSTRUCTION_FAILED
                out["reason"][k] = reason
        elif not _columns_evaluated(job, solution, found, valid, statuses, out):
            return None
    for k, error in enumerate(found.errors):
        if error:
            out["reason"][k] = " ".join(error.split())
        if found.notes[k]:
            out["warnings"][k] = found.notes[k]
    return statuses


def _columns_evaluated(job, solution, found, valid, statuses, out) -> bool:
    """The valid points' quantities and domain statuses; False: leave them to the per-point
    route (a warning, an error or a value that is not finite)."""
    pv = found.parameter_value[valid]
    values = {name: column[valid] for name, column in found.symbol_values.items()}
    with held_warnings(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = evaluate_group(solution, pv, values, np.asarray(job.spec.times))
            clear, freq, own = _screen(solution).screen(pv, values, result["omega"])
            estimates = DomainScreen.estimates(freq, own)
        except (SolutionFailed, PerturbError, ValueError, ArithmeticError):
            return False
    finite = np.all(np.isfinite(result["state"])) and np.all(np.isfinite(result["period"]))
    if caught or not finite:
        return False
    for name in ("period", "frequency", "amplitude", "state"):
        out[name][valid] = result[name]
    for i in np.flatnonzero(clear & ~(estimates <= VALIDITY_ESTIMATE_LIMIT)):
        check = DomainCheck(True, (), math.nan, (), (), {}, float(estimates[i]))
        out["warnings"][valid[i]] = check.validity_note()  # inside, beyond its validity
    for i in np.flatnonzero(~clear):
        point = {name: float(column[i]) for name, column in values.items()}
        with held_warnings(), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            check = series_domain(solution, float(pv[i]), point)
        k = valid[i]
        notes = [str(w.message) for w in caught]
        if check.ok and check.beyond_validity:
            notes.append(check.validity_note())
        if notes:
            out["warnings"][k] = "; ".join(dict.fromkeys(notes))
        if not check.ok:
            statuses[k] = PointStatus.OUTSIDE_DOMAIN
            reasons = "; ".join(check.reasons)
            out["reason"][k] = f"the series is outside its domain: {reasons}"
    return True


def validate_point(job: SweepJob, model, domain=None):
    """The validation of one point: exactly ``perturb validate``'s call (``domain``: the point's
    :func:`perturb.domain.series_domain`, when the evaluation has it already)."""
    from perturb.validation import validate

    spec = job.spec
    return validate(
        model,
        order=spec.order,
        integrator=spec.integrator,
        periods=spec.periods,
        tol=spec.tol,
        domain=domain,
    )


def _store_validation(out, k: int, report) -> None:
    out["verdict"][k] = code_of(report.outcome)
    out["verdict_reason"][k] = report.verdict
    out["completed"][k] = int(bool(report.completed))
    accurate = report.accurate_order
    out["accurate_order"][k] = NOT_COMPUTED if accurate is None else int(accurate)
    out["trajectory_status"][k] = LEGACY_NONE if report.status is None else report.status.code
    orbit = report.periodic_orbit
    if orbit is not None:
        out["orbit_status"][k] = LEGACY_NONE if orbit.status is None else orbit.status.code
        out["orbit_error"][k] = orbit.orbit_error
        out["period_error"][k] = orbit.period_error
        out["initial_state_error"][k] = orbit.initial_state_error
        out["true_period"][k] = orbit.period
        out["resolution"][k] = orbit.resolution
        floquet = np.asarray(orbit.floquet, dtype=complex)[: out["floquet_real"].shape[1]]
        out["floquet_real"][k, : floquet.size] = floquet.real
        out["floquet_imag"][k, : floquet.size] = floquet.imag
    if report.slope is not None:
        out["order_slope"][k] = report.slope.slope
    names = check_names()
    for check in report.checks:
        if check.name in names:
            i = names.index(check.name)
            out["check_value"][k, i] = check.value
            out["check_passed"][k, i] = CHECK_CODES[check.passed]


def run_chunk(
    job: SweepJob, indices: Sequence[int], session: int = 1, columns: bool = True
) -> ChunkResult:
    """Compute the points numbered ``indices`` (flat, C order) of ``job``'s grid.

    An evaluation-only chunk of a model whose case offers its points as columns
    (:meth:`perturb.case.Case.points`) is computed from them, without a model per point; ``columns=False``
    makes every point's model (the reference route: the same numbers, statuses and reasons).

    Returns
    -------
    dict
        One array per variable (points first), ``session`` set to ``session`` for every point,
        and ``"seconds"``, ``"cpu"``: the chunk's wall and CPU time (not stored).
    """
    clock, cpu = time.perf_counter(), time.process_time()
    spec = job.spec
    n_components = len(spec.model.state_names())
    if columns and not spec.validate:
        out = _empty(job, len(indices), n_components)
        with _collection_paused():
            statuses = _run_columns(job, indices, out)
        if statuses is not None:
            codes = {status: code_of(status) for status in PointStatus}
            out["status"][:] = [codes[status] for status in statuses]
            out["session"][:] = session
            out["seconds"] = time.perf_counter() - clock
            out["cpu"] = time.process_time() - cpu
            return out
    points = _points(job, indices)
    out = _empty(job, len(points), n_components)
    groups: dict[int, list[int]] = {}
    single: list[int] = []
    direct = spec.model.case().evaluates_directly  # the class's: the same at every point
    for k, point in enumerate(points):
        if point.solution is None or not point.solution.success:
            continue
        if direct:
            groups.setdefault(id(point.solution), []).append(k)
        else:
            single.append(k)
    for where in groups.values():
        single += _evaluate_vectorised(job, points, where, out)
    pending = {}
    for k in sorted(single):
        found = _evaluate_single(job, points[k], out, k)
        if found is not None:
            pending[k] = found
    _check_domains(points, pending)
    epsilon = out["epsilon"]
    for k, point in enumerate(points):
        if point.model is None:
            continue
        try:
            epsilon[k] = point.model.epsilon()
        except Exception as exc:  # noqa: BLE001
            point.fail(PointStatus.FAILED, _describe(exc))
        if spec.validate:
            try:
                report = _recorded(point, validate_point, job, point.model, point.domain)
            except Exception as exc:  # noqa: BLE001 - recorded, the sweep goes on
                point.fail(PointStatus.FAILED, "validation: " + _describe(exc))
            else:
                _store_validation(out, k, report)
    codes = {status: code_of(status) for status in PointStatus}
    out["status"][:] = [codes[point.status] for point in points]
    for k, point in enumerate(points):
        if point.reason:
            out["reason"][k] = point.reason
        if point.notes:
            out["warnings"][k] = "; ".join(point.notes)
    out["session"][:] = session
    out["seconds"] = time.perf_counter() - clock
    out["cpu"] = time.process_time() - cpu
    return out
