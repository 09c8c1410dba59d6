"""Where an analytic branch leaves the true curves by more than a tolerance (for
:mod:`perturb.response.true_curve`).

The difference is read at the grid's values and at the true curves' folds between them: past a
fold the true orbit an analytic branch followed is gone, and the nearest true orbit is another
one, so the difference jumps there. Read at the grid alone, a crossing interpolated across that
jump would be put near the last agreeing value, wherever the fold lies between it and the next;
with the fold read too, a branch that agrees up to the truth's fold parts at the fold, and one
that parts before it is interpolated where the difference is continuous.
"""

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
    folds = _fold_values(covered, equations, grid)
    values = sorted({*grid, *folds})
    readings: dict[float, list[dict]] = {g: [] for g in values}
    # "no true orbit here" is known only when every curve was followed to its end; a curve that
    # stopped short (budget, step floor) leaves the values it did not reach unknown, not parted
    complete = all(curve.success for curve, *_ in covered)
    coords = [c for c in response.coordinates if c in setup.harmonics]
    for curve, *_ in covered:
        if curve.points.shape[0] < 2:
            continue
        for g, found in zip(values, curve.values_at(values), strict=True):
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
        for value, analytic in _along(branch, coords, measure, folds):

            def distance(true, analytic=analytic):
                size = max(max(true[c] for c in coords), max(analytic.values()))
                if size <= TRIVIAL_AMPLITUDE:
                    return 0.0
                gap = max(abs(analytic[c] - true[c]) for c in coords)
                return gap / max(max(true[c] for c in coords), TRIVIAL_AMPLITUDE)

            trues = readings.get(value, [])
            if trues:
                best = min(trues, key=distance)
                rows.append((value, analytic[first], best[first], distance(best)))
            elif complete:
                rows.append((value, analytic[first], math.nan, math.inf))
        out.extend(_crossings(name, rows, tol, folds))
    return tuple(out)


def _fold_values(covered, equations, grid: list[float]) -> dict[float, set[int]]:
    """The swept values of the true curves' folds strictly inside the grid's span, each with the
    sides of it (+1 above, -1 below) where its curve goes on."""
    low, high = min(grid), max(grid)
    out: dict[float, set[int]] = {}
    for curve, *_ in covered:
        lam = curve.points[:, -1]
        for fold in curve.of_kind("fold"):
            value = equations.unscale(fold.x)[1]
            if not low < value < high or value in grid:
                continue
            near = [lam[k] for k in (fold.index - 1, fold.index + 1) if 0 <= k < len(lam)]
            sides = {1 if v > fold.x[-1] else -1 for v in near if v != fold.x[-1]}
            out.setdefault(value, set()).update(sides)
    return out


def _along(branch, coords, measure: str, folds):
    """``(value, {coordinate: analytic amplitude})`` at each point of the branch and at each true
    fold between two of its consecutive points (linear between them: the branch is smooth
    there, its own folds being points of it)."""
    previous = None
    for p in branch:
        here = (float(p.value), {c: _analytic(p, c, measure) for c in coords})
        if previous is not None:
            (v0, a0), (v1, a1) = previous, here
            inside = sorted(f for f in folds if min(v0, v1) < f < max(v0, v1))
            for f in inside if v1 > v0 else inside[::-1]:
                w = (f - v0) / (v1 - v0)
                yield f, {c: a0[c] + w * (a1[c] - a0[c]) for c in coords}
        yield here
        previous = here


def _analytic(point, coordinate: str, measure: str) -> float:
    """The analytic point's amplitude by ``measure`` (its initial-value norm is ``norms``)."""
    if measure == "initial":
        return float(point.norms[coordinate])
    return float(point.amplitude(coordinate, measure))


def _crossings(name, rows, tol, folds=None) -> list[Parting]:
    """Each passage from agreement (<= tol) to disagreement along the branch, either way; a
    branch that agrees nowhere parts at its first value (and says so). Agreement up to a true
    fold (a key of ``folds``) and none past it, on the side where the fold's curve does not go
    on, parts at the fold: the true orbit ends there."""
    if rows and all(not row[3] <= tol for row in rows):
        first = min(rows, key=lambda r: r[0])
        least = min(row[3] for row in rows)
        note = f"the analytic branch is off the truth at every grid value (by {least:.3g} at least)"
        return [
            Parting(name, first[0], first[1], first[2], first[3], tol, math.nan, first[0], note)
        ]
    folds = folds or {}
    out = []
    for order in (rows, rows[::-1]):
        agreed = None
        for row in order:
            if row[3] <= tol:
                agreed = row
                continue
            if agreed is not None:
                side = 1 if row[0] > agreed[0] else -1
                ended = agreed[0] in folds and side not in folds[agreed[0]]
                out.append(_parting(name, agreed, row, tol, ended))
            agreed = None
    unique = {}
    for p in out:
        unique.setdefault((round(p.before, 12), round(p.after, 12)), p)
    return sorted(unique.values(), key=lambda p: p.value)


def _parting(name, agreed, row, tol, at_fold: bool = False) -> Parting:
    v0, a0, t0, d0 = agreed
    v1, a1, t1, d1 = row
    if at_fold:
        w = 0.0  # the true orbit it agreed with ends at the fold: what is past it is another
    elif math.isfinite(d1) and d1 != d0:
        w = (tol - d0) / (d1 - d0)
    else:
        w = 0.0  # no true orbit at the next value: the parting is somewhere after the last agreement
    value = v0 + w * (v1 - v0)
    analytic = a0 + w * (a1 - a0)
    true = t0 + w * (t1 - t0) if math.isfinite(t1) else t0
    return Parting(name, value, analytic, true, d1, tol, v0, v1)
