"""The order-N response over a sweep, read off its continued curves (issue 29).

:func:`continued_response` traces every order-N branch through a window a little wider than the
sweep (:func:`perturb.steady.traced.trace`), reads every branch at each grid value, and
evaluates every point in one batch from the compiled series: its amplitude measures
(:mod:`perturb.steady.measures`), the series' own estimate, and its Floquet multipliers along
the order-N orbit (:mod:`perturb.steady.floquet`). The curves themselves, densely, come back for
the figure; their folds and branch points, and the Neimark-Sacker and period-doubling points where
the multipliers cross the unit circle, are located on them, inside the sweep or just beside it.
"""

from __future__ import annotations

import cmath
import math

import attrs
import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    FOLD_PAIRING,
    FOLD_REACH,
    ORDER_SEED_ERROR,
    SAME_CONTINUED_POINT,
    WINDOW_MARGIN,
)
from perturb.continuation import TestFunction, locate_on_curve
from perturb.continuation.reading import read_segment
from perturb.steady.census import order_census, same_orbit
from perturb.steady.evaluate import PointEvaluator
from perturb.steady.exact import exact_number
from perturb.steady.point import by_measure
from perturb.steady.traced import trace
from perturb.system import EPS

__all__ = [
    "Continued",
    "ResponseCurve",
    "SpecialResponse",
    "continued_response",
    "reach_of",
    "window_of",
]


@frozen
class SpecialResponse:
    """A located special point of the order-N response.

    ``kind``: ``fold``, ``branch-point``, ``neimark-sacker`` or ``period-doubling``; ``inside``:
    within the sweep's range (else just beside it, in the window). A fold's ``uncertainty`` is
    the series' own estimate of its error in the swept parameter: the distance to the same fold
    one order lower (NaN where that order has no fold beside it: the series cannot tell);
    ``first_order`` the same fold of the first-order equations (NaN: none beside it).
    ``steepness``: |dλ/ds| of the curve it was located on (a branch point is met on both curves
    through it; the transversal one's location is kept).
    """

    kind: str
    value: float
    amplitudes: dict
    norms: dict
    peak: dict
    inside: bool
    multipliers: tuple = field(converter=tuple, factory=tuple)
    uncertainty: float = math.nan
    first_order: float = math.nan
    steepness: float = field(default=math.nan, eq=False, repr=False)
    first_harmonic: dict = field(factory=dict)

    def amplitude(self, coordinate: str | None = None, measure: str = "initial") -> float:
        """``coordinate``'s amplitude by ``measure`` (``peak``, ``first-harmonic`` or
        ``initial``), as a response point's."""
        return by_measure(self, coordinate, measure)


@frozen
class ResponseCurve:
    """One order-N branch, densely: the continuation's points, in the swept parameter.

    ``measures[name][coordinate]`` an array along the curve for each amplitude measure;
    ``stable`` and ``series_ok`` per point; ``largest`` the largest multiplier's modulus.
    """

    values: np.ndarray = field(eq=False)
    amplitudes: np.ndarray = field(eq=False)
    measures: dict = field(eq=False)
    stable: tuple = field(converter=tuple)
    series_ok: tuple = field(converter=tuple)
    largest: np.ndarray = field(eq=False)
    arclength: np.ndarray = field(eq=False)
    status: str = ""
    multipliers: np.ndarray = field(eq=False, default=None)


@frozen
class Continued:
    """What :func:`continued_response` returns: the grid's points (with their curve), the
    curves, the special points, the failures."""

    readings: tuple = field(converter=tuple)  # per point: (value, u, branch, evaluation dict)
    curves: tuple = field(converter=tuple)
    special: tuple = field(converter=tuple)
    failures: tuple = field(converter=tuple)
    traced: object = field(eq=False, repr=False)
    evaluator: object = field(eq=False, repr=False, default=None)


def _widened(line, low: float, high: float, margin: float) -> tuple[float, float]:
    """[low, high] widened by ``margin`` on each side, where the problem accepts the values (a
    side shrunk toward the range until it does)."""
    ends = []
    for edge, outward in ((low, -margin), (high, margin)):
        step = outward
        while step and line.invalid(edge + step):
            step = step / 2 if abs(step) > 1e-6 * margin else 0.0
        ends.append(edge + step)
    return ends[0], ends[1]


def window_of(line, low: float, high: float) -> tuple[float, float]:
    """The sweep's range widened by ``WINDOW_MARGIN`` on each side, where the problem accepts
    the values (a side shrunk toward the sweep until it does)."""
    return _widened(line, low, high, WINDOW_MARGIN * (high - low))


def _multiplier_tests(evaluator, line):
    """Neimark-Sacker (Π_{i<j} (μᵢμⱼ − 1)) and period-doubling (Π (μᵢ + 1)) test functions on
    the curve, one point's multipliers each, and their batch values from multipliers."""

    def multipliers(x):
        lam = float(line.lam(x[-1]))
        return evaluator.evaluate(x[:-1], [lam], check_lower=False)["stability"].multipliers[0]

    def ns(mu):
        mu = np.asarray(mu)
        pairs = [mu[i] * mu[j] - 1 for i in range(len(mu)) for j in range(i + 1, len(mu))]
        return float(np.prod(pairs).real) if pairs else 1.0

    def pd(mu):
        return float(np.prod(np.asarray(mu) + 1).real)

    def classify_ns(x, t, j):
        mu = multipliers(x)
        pairs = [z for z in mu if abs(z.imag) > 1e-9 * abs(z)]
        return "neimark-sacker" if pairs and abs(abs(pairs[0]) - 1) < 1e-6 else None

    tests = (
        (TestFunction("neimark-sacker", lambda x, t, j: ns(multipliers(x)), classify_ns), ns),
        (TestFunction("period-doubling", lambda x, t, j: pd(multipliers(x))), pd),
    )
    return tests


def _dedupe(found: list[SpecialResponse], harmonics, group) -> list[SpecialResponse]:
    """One entry per point: images under the time shifts dropped, a fold at a branch point
    dropped (a pitchfork), a branch point met on both curves through it once (the transversal
    curve's location kept)."""
    out: list[SpecialResponse] = []

    def u(point):
        return np.array(list(point.amplitudes.values()))

    def close(p, q):
        scale = max(1.0, abs(p.value))
        if p.kind == q.kind == "branch-point":  # met on both curves: the turning one's secant
            reach = math.sqrt(SAME_CONTINUED_POINT)  # locates it in λ to the square root only
            return abs(p.value - q.value) <= reach * scale and float(
                np.max(np.abs(u(p) - u(q)))
            ) <= reach * max(1.0, float(np.max(np.abs(u(p)))))
        return (
            abs(p.value - q.value) <= SAME_CONTINUED_POINT * scale
            and same_orbit(u(p), u(q), harmonics, group)
            or (
                abs(p.value - q.value) <= SAME_CONTINUED_POINT * scale
                and float(np.max(np.abs(u(p) - u(q))))
                <= 1e-4 * max(1.0, float(np.max(np.abs(u(p)))))
            )
        )

    # branch points first, the one on the curve crossing transversally (|dλ/ds| largest: the
    # one whose secant converged) before the one on the curve that turns there
    ranked = sorted(found, key=lambda p: (p.kind != "branch-point", -p.steepness))
    for point in ranked:
        if any(close(point, kept) for kept in out):
            continue
        out.append(point)
    return sorted(out, key=lambda p: p.value)


def reach_of(line, low: float, high: float) -> tuple[float, float]:
    """The window [low, high] widened by ``FOLD_REACH`` (in the line's scaled unit μ) on each
    side, where the problem accepts the values (a side shrunk toward the window until it does)."""
    below, above = _widened(line, low, high, FOLD_REACH / line.scale)
    return min(below, low), max(above, high)


def _order_seeds(equations, order: int, line, evaluator, ends):
    """``seeds(cap) -> [(u, λ)]``: the order-N census at ``ends`` (:func:`order_census`), each
    root kept when its amplitudes are below ``cap`` and the series describes it there: its terms
    decrease, an order-(N−1) root is reached from it (:class:`PointEvaluator`) and the last
    correction is at most ``ORDER_SEED_ERROR`` of its amplitude (most roots of a truncated
    series are far from every motion, their corrections as large as they are)."""
    symbols = {p.name: p for p in equations.system.parameters}

    def seeds(cap: float):
        found = []
        for lam in ends:
            values, eps = line.at(lam)
            fixed = {symbols[k]: exact_number(v) for k, v in zip(line.names, values, strict=True)}
            fixed[EPS] = exact_number(eps)
            roots, why = order_census(equations, order, fixed)
            if why:
                return []  # the first-order seeds alone, as before the order-N census
            found += [(u, lam) for u in roots if float(np.max(np.abs(u))) <= cap]
        if not found:
            return []
        with np.errstate(over="ignore", invalid="ignore"):  # a truncated series' far roots
            terms = evaluator.evaluate([u for u, _ in found], [v for _, v in found],
                                       check_lower=False)  # fmt: skip
            found = [f for f, why in zip(found, terms["reasons"], strict=True) if not why]
            if not found:
                return []
            full = evaluator.evaluate([u for u, _ in found], [v for _, v in found])
        kept = []
        for k, seed in enumerate(found):
            sizes = [float(full["peak"][c][k]) for c in full["peak"]]
            errors = [full["error"][k][c] for c in full["peak"]]
            relative = max((e / max(s, 1e-300) for e, s in zip(errors, sizes, strict=True)),
                           default=math.inf)  # fmt: skip
            if not full["reasons"][k] and relative <= ORDER_SEED_ERROR:
                kept.append(seed)
        return kept

    return seeds


def _in_window(curve, mu_low: float, mu_high: float):
    """The runs of ``curve`` inside [mu_low, mu_high]: (index array, first point or None, last
    point or None), the ends read on the segments that cross the window's edges."""
    mu = curve.points[:, -1]
    inside = (mu >= mu_low) & (mu <= mu_high)
    runs = []
    k = 0
    while k < len(mu):
        if not inside[k]:
            k += 1
            continue
        end = k
        while end + 1 < len(mu) and inside[end + 1]:
            end += 1
        runs.append((k, end))
        k = end + 1
    out = []
    for a, b in runs:
        before = after = None
        if a > 0:
            edge = mu_low if mu[a - 1] < mu_low else mu_high
            before = read_segment(curve, a - 1, edge)
        if b < len(mu) - 1:
            edge = mu_low if mu[b + 1] < mu_low else mu_high
            after = read_segment(curve, b, edge)
        out.append((np.arange(a, b + 1), before, after))
    return out


def continued_response(equations, order: int, line, grid) -> Continued:
    """Every order-N point at each grid value, the dense curves and their special points (see
    the module notes); ``line`` the sweep's :class:`~perturb.steady.line.ParameterLine`."""
    grid = np.asarray(grid, dtype=float)
    low, high = window_of(line, float(grid[0]), float(grid[-1]))
    reach = reach_of(line, low, high)
    evaluator = PointEvaluator(equations, line)
    seeds = _order_seeds(equations, order, line, evaluator, (low, high)) if order >= 1 else None
    traced = trace(equations, order, line, low, high, reach=reach, order_seeds=seeds)
    mu_low, mu_high = float(line.mu(low)), float(line.mu(high))
    coords = equations.coordinates
    names = [s.name for s in equations.amplitudes]
    readings_at = traced.at(grid)
    flat = [(float(v), u, b) for v, found in zip(grid, readings_at, strict=True) for u, b in found]
    batch = evaluator.evaluate([u for _, u, _ in flat], [v for v, _, _ in flat]) if flat else None
    readings = []
    for k, (value, u, branch) in enumerate(flat):
        stability = batch["stability"]
        readings.append(
            (
                value,
                dict(zip(names, map(float, u), strict=True)),
                branch,
                _point(batch, k, stability),
            )
        )
    curves, special = [], []
    tests = _multiplier_tests(evaluator, line)
    for branch in traced.branches:
        curve = branch.curve
        located = [
            p for p in curve.special if p.kind == "fold" or mu_low <= p.x[-1] <= mu_high
        ]  # folds in the reach, the others in the window
        for run, before, after in _in_window(curve, mu_low, mu_high):
            ends = [x for x in (before,) if x is not None]
            tail = [x for x in (after,) if x is not None]
            points = np.vstack([*ends, curve.points[run], *tail])
            arclength = curve.arclength[run]
            if before is not None:
                arclength = np.concatenate(([arclength[0] - _gap(before, points[1])], arclength))
            if after is not None:
                arclength = np.concatenate((arclength, [arclength[-1] + _gap(after, points[-2])]))
            if len(points) < 2:
                continue
            lam = line.lam(points[:, -1])
            dense = evaluator.evaluate(points[:, :-1], lam, check_lower="along")
            stability = dense["stability"]
            curves.append(
                ResponseCurve(
                    values=np.asarray(lam),
                    amplitudes=points[:, :-1],
                    measures={m: dense[m] for m in ("peak", "first-harmonic", "initial")},
                    stable=stability.stable,
                    series_ok=[not r for r in dense["reasons"]],
                    largest=np.abs(stability.multipliers[:, 0]),
                    arclength=arclength,
                    status=curve.message,
                    multipliers=stability.multipliers,
                )
            )
            offset = int(run[0]) - (1 if before is not None else 0)
            for test, batch_test in tests:
                values = [batch_test(mu) for mu in stability.multipliers]
                for k in range(len(values) - 1):
                    a, b = values[k], values[k + 1]
                    inner = 0 <= offset + k and offset + k + 1 < len(curve.points)
                    if not inner or (before is not None and k == 0):
                        continue  # the edge segment: a reading, not a segment of the curve
                    if after is not None and k == len(values) - 2:
                        continue
                    if math.isfinite(a) and math.isfinite(b) and a != 0 and (a > 0) != (b > 0):
                        point = locate_on_curve(curve, test, offset + k, a, b)
                        if point is not None:
                            located.append(point)
        for point in located:
            u, value = point.x[:-1], float(line.lam(point.x[-1]))
            at = evaluator.evaluate(u, [value])
            special.append(
                SpecialResponse(
                    kind=point.kind,
                    value=value,
                    amplitudes=dict(zip(names, map(float, u), strict=True)),
                    norms={c: float(at["initial"][c][0]) for c in coords},
                    peak={c: float(at["peak"][c][0]) for c in coords},
                    inside=bool(grid[0] <= value <= grid[-1]),
                    multipliers=tuple(complex(z) for z in at["stability"].multipliers[0]),
                    steepness=abs(float(point.tangent[-1])),
                    first_harmonic={c: float(at["first-harmonic"][c][0]) for c in coords},
                )
            )
    special = _dedupe(special, traced.harmonics, traced.group)
    special = _fold_errors(special, equations, order, line, traced, (low, high), reach)
    return Continued(readings, curves, special, traced.failures, traced, evaluator)


def _folds_of(curves, line) -> list[np.ndarray]:
    """The folds of continued curves as points (u, λ) in the swept parameter."""
    return [
        np.append(p.x[:-1], float(line.lam(p.x[-1]))) for c in curves for p in c.of_kind("fold")
    ]


def _matched(folds: list, others: list, line) -> list[float]:
    """For each fold (u, λ), λ of the fold among ``others`` it is paired with (NaN: none): pairs
    taken nearest first in (u, μ), each fold of ``others`` used once, and only one lying beside
    it (amplitudes within ``FOLD_PAIRING`` of its size)."""
    pairs = []
    for i, a in enumerate(folds):
        for j, b in enumerate(others):
            size = max(1.0, float(np.max(np.abs(a[:-1]))))
            du = float(np.max(np.abs(np.abs(a[:-1]) - np.abs(b[:-1])))) / size
            if du > FOLD_PAIRING:
                continue
            dmu = abs(float(line.mu(a[-1]) - line.mu(b[-1])))
            pairs.append((math.hypot(du, dmu), i, j))
    out = [math.nan] * len(folds)
    used: set = set()
    for _, i, j in sorted(pairs):
        if math.isnan(out[i]) and j not in used:
            out[i] = float(others[j][-1])
            used.add(j)
    return out


def _fold_errors(special, equations, order: int, line, traced, window, reach):
    """Each order-N fold with its uncertainty (the same fold one order lower: the order-(N−1)
    curves traced over the same window, the first-order ones at N = 1) and its first-order fold
    (paired one to one, not merely the nearest: two folds never share one)."""
    folds = [s for s in special if s.kind == "fold"]
    if not folds:
        return special
    points = [np.append(list(s.amplitudes.values()), s.value) for s in folds]
    first = _matched(points, _folds_of(traced.first, line), line)
    if order >= 2:
        evaluator = PointEvaluator(equations, line, order - 1)
        seeds = _order_seeds(equations, order - 1, line, evaluator, window)
        lower = trace(equations, order - 1, line, *window, reach=reach, order_seeds=seeds)
        below = _matched(points, _folds_of([b.curve for b in lower.branches], line), line)
    elif order == 1:
        below = first
    else:  # the first-order equations themselves: no order below them
        below = [math.nan] * len(folds)
    out = []
    for s in special:
        if s.kind == "fold":
            k = folds.index(s)
            s = attrs.evolve(s, uncertainty=abs(s.value - below[k]), first_order=first[k])
        out.append(s)
    return out


def _gap(a, b) -> float:
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)))


def _point(batch, k: int, stability) -> dict:
    """One grid point's evaluation out of a batch."""
    eps = float(batch["eps"][k])
    multipliers = tuple(complex(z) for z in stability.multipliers[k])
    return {
        "peak": {c: float(v[k]) for c, v in batch["peak"].items()},
        "first-harmonic": {c: float(v[k]) for c, v in batch["first-harmonic"].items()},
        "initial": {c: float(v[k]) for c, v in batch["initial"].items()},
        "stable": stability.stable[k],
        "multipliers": multipliers,
        "eigenvalues": tuple(
            cmath.log(z) / eps if z != 0 else complex(-math.inf) for z in multipliers
        ),
        "liouville": float(stability.liouville[k]),
        "error": batch["error"][k],
        "reasons": batch["reasons"][k],
    }
