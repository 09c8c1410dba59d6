"""Keller's pseudo-arclength continuation of a curve G(u, λ) = 0.

From a point x_k = (u_k, λ_k) on the curve with unit tangent t_k, the predictor steps along the
tangent, x_pred = x_k + h t_k, and the corrector solves {G(x) = 0, t_k·(x − x_pred) = 0} by Newton
(:func:`perturb.continuation.newton.correct`): the extended system is regular at folds, so the
curve is followed through its turning points. The step h grows after an easy corrector and shrinks
after a slow one; a corrector that fails, or a tangent that turns by more than ``MAX_TURN``, halves
it; below its floor the continuation stops with a failed status that says where.

At every accepted point the test functions are evaluated (the fold's λ-component of the tangent,
the branch point's determinant of the bordered matrix, and the client's); their sign changes are
located on the curve (:mod:`perturb.continuation.events`) and inserted into it as special points.
The curve ends where λ leaves its range (the point on the boundary is located and kept), where it
closes on itself, where it leaves the client's domain, or when the budget of points is spent.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    CLOSURE_FRACTION,
    CONTINUATION_MAX_POINTS,
    CORRECTOR_NOMINAL_ITER,
    INITIAL_STEP_FRACTION,
    MAX_STEP_FRACTION,
    MAX_TURN,
    MIN_STEP_FRACTION,
    STEP_GROWTH_FAST,
    STEP_GROWTH_NOMINAL,
    STEP_SHRINK,
)
from perturb.continuation.events import BRANCH_POINT, FOLD, TestFunction, locate
from perturb.continuation.newton import (
    correct,
    newton_fixed,
    newton_nearest,
    null_tangent,
    tangent,
)
from perturb.continuation.result import ContinuationStatus, Curve
from perturb.continuation.special import SpecialPoint
from perturb.errors import InvalidParameterError, bad_value

__all__ = ["CurveEquations", "continue_both", "continue_curve"]


@frozen
class CurveEquations:
    """The equations of a curve: G(x) = 0 with x = (u, λ), u in R^n, λ last.

    Parameters
    ----------
    residual : callable
        ``residual(x) -> array of n`` values.
    jacobian : callable
        ``jacobian(x) -> array (n, n + 1)``: [∂G/∂u | ∂G/∂λ].

    Examples
    --------
    The unit circle u² + λ² = 1:

    >>> from perturb.continuation import CurveEquations
    >>> circle = CurveEquations(lambda x: [x[0] ** 2 + x[1] ** 2 - 1],
    ...                         lambda x: [[2 * x[0], 2 * x[1]]])
    >>> circle.residual([0.6, 0.8])
    [0.0]
    """

    residual: Callable = field(eq=False)
    jacobian: Callable = field(eq=False)


def _check_range(lam_range) -> tuple[float, float]:
    try:
        lo, hi = (float(v) for v in lam_range)
    except (TypeError, ValueError):
        raise bad_value(
            "lam_range", lam_range, "give two numbers (low, high)", InvalidParameterError
        ) from None
    if math.isnan(lo) or math.isnan(hi) or not lo < hi:
        raise bad_value(
            "lam_range", lam_range, "give low < high (not NaN)", InvalidParameterError
        )  # fmt: skip
    return lo, hi


def _orient(t: np.ndarray, direction) -> np.ndarray:
    if np.ndim(direction) == 0:
        sign = float(direction)
        if sign == 0 or not math.isfinite(sign):
            raise bad_value(
                "direction", direction, "give +1 (λ increasing), -1, or a vector",
                InvalidParameterError,
            )  # fmt: skip
        reference = t[-1] if t[-1] != 0 else t[0]
        return t if (reference > 0) == (sign > 0) else -t
    d = np.asarray(direction, dtype=float)
    if d.shape != t.shape:
        raise bad_value(
            "direction", direction, f"give a vector of {t.size} numbers", InvalidParameterError
        )  # fmt: skip
    return t if float(t @ d) >= 0 else -t


class _Trace:
    """The growing curve: points, tangents, arclength, test values, special points."""

    def __init__(self, x, t, jac, tests):
        self.tests = tests
        self.points, self.tangents, self.arclength = [x], [t], [0.0]
        self.values = [[f(x, t, jac) for f in tests]]
        self.special: list[SpecialPoint] = []

    def add(self, x, t, jac, sigma_from_last: float):
        self.points.append(x)
        self.tangents.append(t)
        self.arclength.append(self.arclength[-1] + sigma_from_last)
        self.values.append([f(x, t, jac) for f in self.tests])

    def curve(self, status, message, equations, settings) -> Curve:
        values = np.array(self.values, dtype=float).reshape(len(self.points), len(self.tests))
        return Curve(
            points=np.array(self.points),
            tangents=np.array(self.tangents),
            arclength=np.array(self.arclength),
            special=tuple(self.special),
            tests={f.name: values[:, i] for i, f in enumerate(self.tests)},
            status=status,
            message=message,
            equations=equations,
            settings=settings,
        )


def continue_curve(
    equations: CurveEquations,
    start: Sequence[float],
    *,
    lam_range: tuple[float, float],
    direction=1.0,
    step: float | None = None,
    max_step: float | None = None,
    min_step: float | None = None,
    tests: Sequence[TestFunction] = (),
    domain: Callable | None = None,
    max_points: int = CONTINUATION_MAX_POINTS,
) -> Curve:
    """Follow the curve G(u, λ) = 0 from ``start`` until it leaves ``lam_range``.

    Parameters
    ----------
    equations : CurveEquations
    start : sequence of float
        ``(u, λ)`` near the curve: corrected first by Newton at fixed λ (by least-norm Newton,
        λ free, where that fails: a start on a fold).
    lam_range : (float, float)
        The continuation stops on leaving it (the point on the boundary is kept).
    direction : float or array_like
        +1: start with λ increasing, -1: decreasing; or a vector the first tangent leans to.
    step, max_step, min_step : float, optional
        Initial, largest and smallest pseudo-arclength step (defaults: fractions
        ``INITIAL_STEP_FRACTION``, ``MAX_STEP_FRACTION`` of the range's width and
        ``MIN_STEP_FRACTION`` of the initial step).
    tests : sequence of TestFunction
        Located besides the folds and branch points.
    domain : callable, optional
        ``domain(x) -> str``: "" inside, else why x is outside (the curve stops before it).
    max_points : int
        Budget of points.

    Returns
    -------
    Curve
        Its ``status`` says how it ended and ``message`` where.

    Raises
    ------
    InvalidParameterError
        A range that is not (low < high), a start outside it, or a bad direction.

    Examples
    --------
    The cubic's S-curve u³ − u − λ = 0 turns at λ = ∓2/(3√3):

    >>> import numpy as np
    >>> from perturb.continuation import CurveEquations, continue_curve
    >>> cubic = CurveEquations(lambda x: [x[0] ** 3 - x[0] - x[1]],
    ...                        lambda x: [[3 * x[0] ** 2 - 1, -1.0]])
    >>> curve = continue_curve(cubic, [-1.5, -1.875], lam_range=(-2.0, 2.0))
    >>> [round(p.value, 10) for p in curve.of_kind("fold")]
    [0.3849001795, -0.3849001795]
    >>> round(float(2 / (3 * np.sqrt(3))), 10)
    0.3849001795
    """
    lo, hi = _check_range(lam_range)
    x0 = np.array(start, dtype=float)
    if x0.ndim != 1 or x0.size < 2 or not np.all(np.isfinite(x0)):
        raise bad_value(
            "start", list(start), "give (u..., λ): finite numbers", InvalidParameterError
        )
    if not lo <= x0[-1] <= hi:
        raise bad_value(
            "start", x0.tolist(), f"its λ = {x0[-1]:g} is outside lam_range [{lo:g}, {hi:g}]",
            InvalidParameterError,
        )  # fmt: skip
    width = hi - lo if math.isfinite(hi - lo) else 1.0
    h = float(step) if step is not None else INITIAL_STEP_FRACTION * width
    h_max = float(max_step) if max_step is not None else max(MAX_STEP_FRACTION * width, h)
    h_min = float(min_step) if min_step is not None else MIN_STEP_FRACTION * h
    if not (0 < h_min <= h <= h_max and math.isfinite(h_max)):
        raise bad_value(
            "step", (h_min, h, h_max), "give 0 < min_step <= step <= max_step, finite",
            InvalidParameterError,
        )  # fmt: skip
    tests = (FOLD, BRANCH_POINT, *tests)
    settings = {"step": h, "max_step": h_max, "min_step": h_min, "lam_range": (lo, hi)}

    first = newton_fixed(equations, x0)
    if not first.converged and first.finite:  # a start on a fold: G_u is singular there
        first = newton_nearest(equations, x0)
    if not first.converged:
        empty = _Trace.__new__(_Trace)
        empty.tests, empty.points, empty.tangents = tests, [x0], [np.zeros_like(x0)]
        empty.arclength, empty.values, empty.special = [0.0], [[math.nan] * len(tests)], []
        status = ContinuationStatus.START_FAILED if first.finite else ContinuationStatus.NOT_FINITE
        return empty.curve(status, f"{status.value}: at {_where(x0)}", equations, settings)
    x, jac = first.x, first.jacobian
    singular = np.linalg.svd(jac, compute_uv=False)
    if singular[-1] <= 1e-12 * max(singular[0], 1e-300):
        empty = _Trace(x, null_tangent(jac), jac, ())
        empty.tests, empty.values = tests, [[math.nan] * len(tests)]
        status = ContinuationStatus.SINGULAR_START
        return empty.curve(status, f"{status.value}: at {_where(x)}", equations, settings)
    t = _orient(null_tangent(jac), direction)
    trace = _Trace(x, t, jac, tests)
    status, where = _run(equations, trace, jac, h, h_min, h_max, lo, hi, domain, max_points)
    return trace.curve(status, where, equations, settings)


def _where(x) -> str:
    return f"λ = {x[-1]:.10g}, u = [{', '.join(f'{v:.6g}' for v in x[:-1])}]"


def _run(equations, trace, jac, h, h_min, h_max, lo, hi, domain, max_points):
    """The predictor-corrector loop; returns (status, message)."""
    x, t = trace.points[-1], trace.tangents[-1]
    x_start, t_start = x, t
    while True:
        if len(trace.points) >= max_points:
            s = ContinuationStatus.MAX_POINTS
            return s, f"{s.value} ({max_points} points); last at {_where(x)}"
        predictor = x + h * t
        corr = correct(equations, predictor, t)
        if not corr.finite and not lo <= predictor[-1] <= hi and h * 0.5 >= h_min:
            h *= 0.5  # a step past the range's end, where the equations may not be defined
            continue
        if not corr.finite:
            s = ContinuationStatus.NOT_FINITE
            return s, f"{s.value}: near {_where(predictor)} (the curve is kept up to {_where(x)})"
        t_new = tangent(corr.jacobian, t) if corr.converged else None
        turn = math.acos(min(1.0, float(t @ t_new))) if t_new is not None else math.inf
        if t_new is None or turn > MAX_TURN:
            h *= 0.5
            if h < h_min:
                s = ContinuationStatus.STEP_FLOOR
                return s, (
                    f"{s.value}; at {_where(x)}, step {h:.3g} below the floor {h_min:.3g} "
                    f"after {len(trace.points)} points"
                )
            continue
        x_new, jac_new = corr.x, corr.jacobian
        if domain is not None:
            outside = domain(x_new)
            if outside:
                s = ContinuationStatus.LEFT_DOMAIN
                return s, f"{s.value} ({outside}) after {_where(x)}"
        closed = _closes(trace, x, x_new, x_start, t_start, h)
        boundary = _boundary(x, x_new, lo, hi)
        _advance(equations, trace, x, t, jac, x_new, t_new, jac_new, h, boundary)
        if boundary is not None:
            s = ContinuationStatus.LEFT_RANGE
            return s, f"{s.value} at {_where(trace.points[-1])}"
        if closed:
            s = ContinuationStatus.CLOSED
            return s, f"{s.value}: back at {_where(x_start)} after {len(trace.points)} points"
        x, t, jac = x_new, t_new, jac_new
        if corr.iterations <= 2:
            h = min(h_max, h * STEP_GROWTH_FAST)
        elif corr.iterations <= CORRECTOR_NOMINAL_ITER:
            h = min(h_max, h * STEP_GROWTH_NOMINAL)
        else:
            h = max(h_min, h * STEP_SHRINK)


def _boundary(x, x_new, lo, hi) -> float | None:
    """The bound of the range that the step from x to x_new crosses, if any."""
    if x_new[-1] > hi:
        return hi
    if x_new[-1] < lo:
        return lo
    return None


def _closes(trace, x, x_new, x_start, t_start, h) -> bool:
    """Whether the step x -> x_new passes by the first point, running its way."""
    if len(trace.points) < 3:
        return False
    d = x_new - x
    length = float(d @ d)
    if length == 0:
        return False
    theta = min(1.0, max(0.0, float((x_start - x) @ d) / length))
    gap = float(np.linalg.norm(x + theta * d - x_start))
    return gap <= CLOSURE_FRACTION * h and float(d @ t_start) > 0


def _advance(equations, trace, x, t, jac, x_new, t_new, jac_new, h, boundary):
    """Append x_new, with the special points located between x and it inserted before it; with
    a boundary crossed, stop at the point on it instead (special points beyond it dropped)."""
    f_old = trace.values[-1]
    f_new = [f(x_new, t_new, jac_new) for f in trace.tests]
    found = []
    for i, f in enumerate(trace.tests):
        a, b = f_old[i], f_new[i]
        if not (math.isfinite(a) and math.isfinite(b)) or a == 0 or (a > 0) == (b > 0):
            continue
        sigma, here, value, located = locate(f, equations, x, t, h, a, b)
        if here is None:
            continue
        kind = f.name
        if f.classify is not None:
            kind = f.classify(*here)
            if kind is None:
                continue
        note = "" if located else "the secant did not shrink its bracket to EVENT_TOL"
        found.append((sigma, kind, here, value, located, note))
    end_sigma = h
    end = (x_new, t_new, jac_new)
    if boundary is not None:
        crossing = _locate_boundary(equations, x, t, h, boundary)
        if crossing is not None:
            end_sigma, end = crossing
            found = [item for item in found if item[0] < end_sigma]
    last_sigma = 0.0
    for sigma, kind, here, value, located, note in sorted(found, key=lambda item: item[0]):
        trace.add(*here, sigma - last_sigma)
        last_sigma = sigma
        trace.special.append(
            SpecialPoint(kind, here[0], here[1], len(trace.points) - 1, value, located, note)
        )
    trace.add(*end, end_sigma - last_sigma)


def _locate_boundary(equations, x, t, h, bound):
    """The point of the segment where λ = bound, and its pseudo-arclength from x: Newton at
    λ = bound from the tangent's crossing, else the secant along the segment."""
    if t[-1] != 0:
        sigma = (bound - x[-1]) / t[-1]
        guess = x + sigma * t
        guess[-1] = bound
        direct = newton_fixed(equations, guess)
        if direct.converged and float(np.linalg.norm(direct.x - guess)) <= 0.5 * h:
            here = tangent(direct.jacobian, t)
            if here is not None:
                return float(t @ (direct.x - x)), (direct.x, here, direct.jacobian)
    f = TestFunction("boundary", lambda y, tt, jj: y[-1] - bound)
    sigma, here, _, _ = locate(f, equations, x, t, h, x[-1] - bound, x[-1] + h * t[-1] - bound)
    if here is None:
        return None
    return sigma, here


def continue_both(equations: CurveEquations, start: Sequence[float], **options) -> Curve:
    """Follow the curve through ``start`` both ways and join the two into one :class:`Curve`
    (λ decreasing first, then increasing; a loop is followed once).

    Parameters
    ----------
    equations : CurveEquations
    start : sequence of float
        ``(u, λ)`` near the curve.
    **options
        Those of :func:`continue_curve` but ``direction``.

    Returns
    -------
    Curve
        Its status is the forward run's unless the backward one failed; its message has both
        ends.

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.continuation import CurveEquations, continue_both
    >>> circle = CurveEquations(lambda x: [x[0] ** 2 + x[1] ** 2 - 1],
    ...                         lambda x: [[2 * x[0], 2 * x[1]]])
    >>> curve = continue_both(circle, [1.0, 0.0], lam_range=(-2.0, 2.0))
    >>> curve.status.name, len(curve.of_kind("fold"))
    ('CLOSED', 2)
    """
    options.pop("direction", None)
    forward = continue_curve(equations, start, direction=1.0, **options)
    if forward.status is ContinuationStatus.CLOSED or len(forward.points) < 2:
        return forward
    backward = continue_curve(equations, forward.points[0], direction=-1.0, **options)
    if len(backward.points) < 2:
        return forward
    m = len(backward.points)
    points = np.vstack((backward.points[::-1], forward.points[1:]))
    tangents = np.vstack((-backward.tangents[::-1], forward.tangents[1:]))
    total = backward.arclength[-1]
    arclength = np.concatenate((total - backward.arclength[::-1], total + forward.arclength[1:]))
    special = [
        SpecialPoint(p.kind, p.x, -p.tangent, m - 1 - p.index, p.residual, p.located, p.note)
        for p in reversed(backward.special)
    ] + [
        SpecialPoint(p.kind, p.x, p.tangent, p.index + m - 1, p.residual, p.located, p.note)
        for p in forward.special
    ]
    tests = {}
    for name, values in forward.tests.items():
        back = backward.tests[name][::-1]
        if name == FOLD.name:
            back = -back  # the tangent reversed
        elif name == BRANCH_POINT.name:
            back = -back  # det [J; -t] = -det [J; t] (one row flipped)
        tests[name] = np.concatenate((back, values[1:]))
    status = forward.status if backward.success else backward.status
    message = f"λ decreasing: {backward.message}; λ increasing: {forward.message}"
    return Curve(
        points, tangents, arclength, tuple(special), tests, status, message,
        equations, forward.settings,
    )  # fmt: skip
