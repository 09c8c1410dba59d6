"""A continued response as a :class:`~perturb.response.curve.FrequencyResponse`: its points at the
grid values, named; its folds and special points; what failed.

Points at each grid value are sorted by the chosen amplitude measure of the first resonant
coordinate and named by count (:func:`perturb.response.branches.branch_names`): ``lower``,
``middle``, ``upper``… A point whose series' terms do not decrease keeps its place and says so
in ``note`` (``series_ok`` False): it is a root of the order-N equations where the series is
outside its domain, drawn apart and never silently taken for a motion.
"""

from __future__ import annotations

import math

import numpy as np

from perturb.response.branches import branch_names
from perturb.response.continued import Continued, continued_response
from perturb.response.curve import Fold, FrequencyResponse, ResponsePoint

__all__ = ["frequency_response_on", "name_at", "response_of"]


def _first_order_folds(result: Continued) -> list[float]:
    line = result.traced.line
    return [
        float(line.lam(p.value)) for curve in result.traced.first for p in curve.of_kind("fold")
    ]


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
        names.extend(branch_names(here))
    first = _first_order_folds(result)
    folds = []
    for s in result.special:
        if s.kind != "fold":
            continue
        nearest = min(first, key=lambda f: abs(f - s.value), default=math.nan)
        folds.append(
            Fold(s.value, s.amplitudes, s.norms, nearest, "", inside=s.inside, peak=s.peak)
        )
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
    from perturb.response.census import same_orbit

    traced = result.traced
    here = traced.at([lam])[0]
    if not here:
        return None
    at = result.evaluator.evaluate([v for v, _ in here], [lam] * len(here))
    points = [
        ResponsePoint(lam, {}, {c: float(at["initial"][c][i]) for c in at["initial"]}, None,
                      (), (), peak={c: float(at["peak"][c][i]) for c in at["peak"]},
                      first_harmonic={c: float(at["first-harmonic"][c][i])
                                      for c in at["first-harmonic"]})
        for i in range(len(here))
    ]  # fmt: skip
    order = sorted(range(len(points)), key=lambda i: points[i].amplitude(None, measure))
    names = branch_names([points[i] for i in order])
    for rank, i in enumerate(order):
        if same_orbit(here[i][0], u, traced.harmonics, traced.group):
            return names[rank]
    return None
