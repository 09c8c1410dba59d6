"""Where an analytic branch leaves the true curves by more than a tolerance (for
:mod:`perturb.response.true_curve`)."""

from __future__ import annotations

import math

from perturb._defaults import TRIVIAL_AMPLITUDE
from perturb.response.true_family import OutsideDomain
from perturb.response.true_results import Parting

__all__ = ["partings"]


def partings(
    setup, equations, response, names, covered, tol, measure: str = "initial"
) -> tuple[Parting, ...]:
    """Along each analytic branch, where it leaves the true curves by more than ``tol``: the
    largest difference over the resonant coordinates, relative to the true orbit's largest
    amplitude, against the true point nearest it at the same grid value, both by ``measure``
    (``initial`` from the states alone; ``peak`` and ``first-harmonic`` from a sampled shot)."""
    grid = [float(g) for g in response.grid]
    readings: dict[float, list[dict]] = {g: [] for g in grid}
    # "no true orbit here" is known only when every curve was followed to its end; a curve that
    # stopped short (budget, step floor) leaves the values it did not reach unknown, not parted
    complete = all(curve.success for curve, *_ in covered)
    coords = [c for c in response.coordinates if c in setup.harmonics]
    for curve, *_ in covered:
        if curve.points.shape[0] < 2:
            continue
        for g, found in zip(grid, curve.values_at(grid), strict=True):
            for x in found:
                y0, lam = equations.unscale(x)
                try:
                    if measure == "initial":
                        readings[g].append(setup.norms(lam, y0))
                    else:
                        point = setup.point(lam, y0)
                        readings[g].append({c: point.amplitude(c, measure) for c in coords})
                except OutsideDomain:
                    continue
    first = coords[0] if coords else None
    by_id = {id(p): n for p, n in zip(response.points, names, strict=True)}
    out = []
    for branch in response.branches():
        if not branch or first is None:
            continue
        name = by_id.get(id(branch[len(branch) // 2]), "branch")
        rows = []
        for p in branch:
            analytic = {c: _analytic(p, c, measure) for c in coords}

            def distance(true, analytic=analytic):
                size = max(max(true[c] for c in coords), max(analytic.values()))
                if size <= TRIVIAL_AMPLITUDE:
                    return 0.0
                gap = max(abs(analytic[c] - true[c]) for c in coords)
                return gap / max(max(true[c] for c in coords), TRIVIAL_AMPLITUDE)

            trues = readings.get(float(p.value), [])
            if trues:
                best = min(trues, key=distance)
                rows.append((float(p.value), analytic[first], best[first], distance(best)))
            elif complete:
                rows.append((float(p.value), analytic[first], math.nan, math.inf))
        out.extend(_crossings(name, rows, tol))
    return tuple(out)


def _analytic(point, coordinate: str, measure: str) -> float:
    """The analytic point's amplitude by ``measure`` (its initial-value norm is ``norms``)."""
    if measure == "initial":
        return float(point.norms[coordinate])
    return float(point.amplitude(coordinate, measure))


def _crossings(name, rows, tol) -> list[Parting]:
    """Each passage from agreement (<= tol) to disagreement along the branch, either way; a
    branch that agrees nowhere parts at its first value (and says so)."""
    if rows and all(not row[3] <= tol for row in rows):
        first = min(rows, key=lambda r: r[0])
        least = min(row[3] for row in rows)
        note = f"the analytic branch is off the truth at every grid value (by {least:.3g} at least)"
        return [
            Parting(name, first[0], first[1], first[2], first[3], tol, math.nan, first[0], note)
        ]
    out = []
    for order in (rows, rows[::-1]):
        agreed = None
        for row in order:
            if row[3] <= tol:
                agreed = row
                continue
            if agreed is not None:
                out.append(_parting(name, agreed, row, tol))
            agreed = None
    unique = {}
    for p in out:
        unique.setdefault((round(p.before, 12), round(p.after, 12)), p)
    return sorted(unique.values(), key=lambda p: p.value)


def _parting(name, agreed, row, tol) -> Parting:
    v0, a0, t0, d0 = agreed
    v1, a1, t1, d1 = row
    if math.isfinite(d1) and d1 != d0:
        w = (tol - d0) / (d1 - d0)
    else:
        w = 0.0  # no true orbit at the next value: the parting is somewhere after the last agreement
    value = v0 + w * (v1 - v0)
    analytic = a0 + w * (a1 - a0)
    true = t0 + w * (t1 - t0) if math.isfinite(t1) else t0
    return Parting(name, value, analytic, true, d1, tol, v0, v1)
