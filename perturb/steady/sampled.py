"""A continued response as a :class:`~perturb.steady.curve.FrequencyResponse`: its points at the
grid values, named; its folds and special points; what failed.

Points at each grid value are sorted by the chosen amplitude measure of the first resonant
coordinate and named by count (:func:`perturb.steady.branches.branch_names`): ``lower``,
``middle``, ``upper``… A point whose series' terms do not decrease keeps its place and says so
in ``note`` (``series_ok`` False): it is a root of the order-N equations where the series is
outside its domain, drawn apart and never silently taken for a motion.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from perturb.errors import InvalidParameterError, bad_value
from perturb.method.driven import AmplitudeEquations
from perturb.steady.branches import branch_names
from perturb.steady.continued import Continued, continued_response
from perturb.steady.curve import Fold, FrequencyResponse, ResponsePoint
from perturb.steady.exact import exact_number

__all__ = ["frequency_response", "frequency_response_on", "name_at", "response_of"]


def response_of(result: Continued, *, system: str, parameter: str, order: int, epsilon: float,
                values: dict, grid, coordinates, measure: str = "peak"):  # fmt: skip
    """``(FrequencyResponse, names)`` of a :func:`continued_response` result."""
    by_value: dict[float, list[ResponsePoint]] = {}
    for value, amplitudes, branch, at in result.readings:
        note = ""
        if at["reasons"]:
            note = "the series is outside its domain here: " + "; ".join(at["reasons"])
        point = ResponsePoint(
            value=value,
            amplitudes=amplitudes,
            norms=at["initial"],
            stable=at["stable"],
            eigenvalues=at["eigenvalues"],
            multipliers=at["multipliers"],
            note=note,
            peak=at["peak"],
            first_harmonic=at["first-harmonic"],
            error=at["error"],
            series_ok=not at["reasons"],
            liouville=at["liouville"],
            branch=branch,
        )
        by_value.setdefault(value, []).append(point)
    points, names = [], []
    for value in (float(g) for g in grid):
        here = sorted(by_value.get(value, []), key=lambda p: p.amplitude(None, measure))
        points.extend(here)
        names.extend(branch_names(here, result.traced.harmonics))
    folds = []
    for s in result.special:
        if s.kind != "fold":
            continue
        folds.append(
            Fold(s.value, s.amplitudes, s.norms, s.first_order, "", inside=s.inside, peak=s.peak,
                 uncertainty=s.uncertainty, first_harmonic=s.first_harmonic)
        )  # fmt: skip
    points = [_marked(p, folds, parameter) for p in points]
    response = FrequencyResponse(
        system=system,
        parameter=parameter,
        order=order,
        epsilon=float(epsilon),
        values=values,
        grid=tuple(float(g) for g in grid),
        points=tuple(points),
        folds=tuple(folds),
        failures=tuple(result.failures),
        coordinates=tuple(coordinates),
        special=result.special,
        curves=result.curves,
        measure=measure,
    )
    return response, names


def _marked(point: ResponsePoint, folds, parameter: str) -> ResponsePoint:
    """``point`` with a note when it lies within a fold's uncertainty band."""
    import attrs

    notes = [f.band_note(parameter) for f in folds if f.holds(point.value)]
    if not notes:
        return point
    return attrs.evolve(point, note="; ".join(filter(None, [point.note, *notes])))


def frequency_response_on(equations, order: int, line, grid, *, system: str, values: dict,
                          measure: str = "peak"):  # fmt: skip
    """The response of ``equations`` at ``order`` over ``grid`` on ``line``: ``(FrequencyResponse,
    names)``."""
    grid = np.asarray(grid, dtype=float)
    result = continued_response(equations, order, line, grid)
    return response_of(
        result, system=system, parameter=line.parameter, order=order, epsilon=line.eps,
        values=values, grid=grid, coordinates=equations.coordinates, measure=measure,
    )  # fmt: skip


def name_at(result: Continued, lam: float, u, measure: str) -> str | None:
    """The name (by count, as at a grid value) of the order-N point ``u`` at λ = ``lam``."""
    from perturb.steady.census import same_orbit

    traced = result.traced
    here = traced.at([lam])[0]
    if not here:
        return None
    at = result.evaluator.evaluate([v for v, _ in here], [lam] * len(here))
    points = [
        ResponsePoint({}, {c: float(at["initial"][c][i]) for c in at["initial"]}, None, (), (),
                      peak={c: float(at["peak"][c][i]) for c in at["peak"]},
                      first_harmonic={c: float(at["first-harmonic"][c][i])
                                      for c in at["first-harmonic"]}, value=lam)
        for i in range(len(here))
    ]  # fmt: skip
    order = sorted(range(len(points)), key=lambda i: points[i].amplitude(None, measure))
    names = branch_names([points[i] for i in order], traced.harmonics)
    for rank, i in enumerate(order):
        if same_orbit(here[i][0], u, traced.harmonics, traced.group):
            return names[rank]
    return None


def frequency_response(
    equations: AmplitudeEquations,
    parameter: str,
    grid: Sequence[float],
    values: Mapping[str, float],
    epsilon: float,
    order: int = 1,
) -> FrequencyResponse:
    """Every branch of the steady-state response over ``grid`` values of ``parameter``.

    Parameters
    ----------
    equations : AmplitudeEquations
        Of the driven system, to at least ``order`` (:func:`amplitude_equations`).
    parameter : str
        The swept parameter: one of the system's parameters (σ, a forcing level…).
    grid : sequence of float
    values : mapping
        Values of every other parameter of the system.
    epsilon : float
        ε (> 0).
    order : int
        The order of the state (0: the first-order response equations only).

    Returns
    -------
    FrequencyResponse

    Raises
    ------
    InvalidParameterError
        An unknown swept parameter or a missing value.

    Examples
    --------
    >>> import numpy as np
    >>> from problems import get_problem
    >>> from perturb import amplitude_equations, frequency_response
    >>> system = get_problem("forced-duffing").system()
    >>> response = frequency_response(
    ...     amplitude_equations(system, 0), "sigma", np.linspace(0.0, 2.0, 5),
    ...     {"zeta": 0.1, "gamma": 1.0, "F": 1.0}, epsilon=0.05, order=0)
    >>> [len(response.at(value)) for value in response.grid]  # one branch, then three
    [1, 1, 3, 3, 3]
    >>> [round(fold.value, 4) for fold in response.folds if fold.inside]
    [0.8497]
    """
    from perturb.steady.line import line_of_values

    system = equations.system
    names = {p.name: p for p in system.parameters}
    if parameter not in names:
        raise bad_value(
            "parameter", parameter, f"sweep one of the system's parameters {sorted(names)}",
            InvalidParameterError,
        )  # fmt: skip
    missing = sorted(set(names) - {parameter} - set(values))
    if missing:
        raise bad_value("values", dict(values), f"give values for {missing}", InvalidParameterError)
    grid = np.asarray(grid, dtype=float)
    if grid.ndim != 1 or grid.size < 2 or not np.all(np.diff(grid) > 0):
        raise bad_value(
            "grid", grid.tolist(), "give at least 2 increasing values", InvalidParameterError
        )  # fmt: skip
    fixed = {k: float(exact_number(v)) for k, v in values.items() if k in names and k != parameter}
    line = line_of_values(list(names), {**fixed, parameter: float(grid[0])}, epsilon, parameter)
    result = continued_response(equations, order, line, grid)
    response, _ = response_of(
        result, system=system.name, parameter=parameter, order=order, epsilon=epsilon,
        values=fixed, grid=grid, coordinates=equations.coordinates, measure="initial",
    )  # fmt: skip
    return response
