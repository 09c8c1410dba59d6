"""Test functions along a curve and the location of their sign changes.

A test function φ(x, t, J) is evaluated at every accepted point. Where it changes sign between
two points, the zero is located on the curve between them: a point at pseudo-arclength σ from
the segment's start x_k is the corrector's solution on the hyperplane t_k·(x − x_k) = σ, and
φ(σ) is driven to zero by the Illinois variant of the secant (regula falsi that halves the stale
end's value), whose bracket always holds the zero. The built-in tests are the fold (the tangent's
λ-component) and the branch point (the determinant of the bordered matrix [J; tᵀ]).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from attrs import field, frozen

from perturb._defaults import EVENT_MAX_ITER, EVENT_TOL, NUDGES
from perturb.continuation.newton import bordered, correct, tangent
from perturb.continuation.special import SpecialPoint

__all__ = [
    "BRANCH_POINT",
    "FOLD",
    "TestFunction",
    "locate",
    "locate_on_curve",
    "point_on_segment",
]


@frozen
class TestFunction:
    """A scalar function along the curve whose sign changes mark special points.

    Parameters
    ----------
    name : str
        The kind given to its special points.
    function : callable
        ``function(x, t, J) -> float``: x = (u, λ), t the unit tangent, J = [G_u | G_λ] there.
    classify : callable, optional
        ``classify(x, t, J) -> str or None`` at a located zero: the kind to report (e.g. a
        Neimark–Sacker point or a neutral saddle of the same test), None to drop it.

    Examples
    --------
    >>> from perturb.continuation import TestFunction
    >>> crossing = TestFunction("u=1", lambda x, t, J: x[0] - 1.0)
    >>> crossing.name
    'u=1'
    """

    __test__ = False  # not a pytest class

    name: str
    function: Callable = field(eq=False)
    classify: Callable | None = field(eq=False, default=None)

    def __call__(self, x, t, jac) -> float:
        return float(self.function(x, t, jac))


#: A fold (turning point in λ): the λ-component of the tangent changes sign.
FOLD = TestFunction("fold", lambda x, t, jac: t[-1])
#: A branch point: the bordered matrix [J; tᵀ] is singular there, its determinant changes sign
#: (the tangent keeps its orientation through it).
BRANCH_POINT = TestFunction("branch-point", lambda x, t, jac: np.linalg.det(bordered(jac, t)))


def point_on_segment(equations, start: np.ndarray, direction: np.ndarray, sigma: float):
    """The curve's point at pseudo-arclength ``sigma`` from ``start`` along ``direction``:
    ``(x, t, J)``, or None when the corrector fails there."""
    predictor = start + sigma * direction
    corr = correct(equations, predictor, direction)
    if not corr.converged:
        return None
    t = tangent(corr.jacobian, direction)
    if t is None:
        return None
    return corr.x, t, corr.jacobian


def locate(function, equations, start, direction, length, f0, f1):
    """The zero of ``function`` on the segment of pseudo-arclength ``length`` from ``start``
    (``f0``, ``f1`` its values at the ends, of opposite signs).

    Returns
    -------
    (sigma, (x, t, J) or None, value, located)
        ``located`` False when the bracket could not be shrunk to ``EVENT_TOL * length`` (then the
        best point found is returned).
    """
    a, fa, b, fb = 0.0, float(f0), float(length), float(f1)
    best = None
    side = 0
    last = math.nan
    for _ in range(EVENT_MAX_ITER):
        c = (a * fb - b * fa) / (fb - fa) if fb != fa else 0.5 * (a + b)
        if not (min(a, b) < c < max(a, b)):
            c = 0.5 * (a + b)
        here = point_on_segment(equations, start, direction, c)
        for nudge in NUDGES:  # the corrector is singular on a branch point itself: step aside
            if here is not None:
                break
            c = c + nudge * (b - c)
            here = point_on_segment(equations, start, direction, c)
        if here is None:
            return (best[0], best[1], best[2], False) if best else (c, None, math.nan, False)
        fc = function(*here)
        best = (c, here, fc)
        if fc == 0.0 or abs(c - last) <= EVENT_TOL * length or abs(b - a) <= EVENT_TOL * length:
            return c, here, fc, True
        last = c
        if (fc > 0) == (fb > 0):
            b, fb = c, fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
    return best[0], best[1], best[2], False


def locate_on_curve(curve, test: TestFunction, k: int, f0: float, f1: float):
    """The zero of ``test`` between points ``k`` and ``k + 1`` of ``curve``, where its values
    ``f0`` and ``f1`` differ in sign: a :class:`~perturb.continuation.SpecialPoint` (index
    ``k + 1``, the position it would take in the curve), or None when ``classify`` drops it or the
    corrector fails on the segment.

    For test functions too costly to evaluate inside the continuation: evaluate them at the
    curve's points afterwards (in one batch), then locate each sign change here.

    Parameters
    ----------
    curve : Curve
        A continued curve (it carries its equations).
    test : TestFunction
    k : int
        The segment: between ``curve.points[k]`` and ``curve.points[k + 1]``.
    f0, f1 : float
        ``test``'s values at its ends.

    Returns
    -------
    SpecialPoint or None

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.continuation import CurveEquations, TestFunction, continue_curve
    >>> cubic = CurveEquations(lambda x: [x[0] ** 3 - x[0] - x[1]],
    ...                        lambda x: [[3 * x[0] ** 2 - 1, -1.0]])
    >>> curve = continue_curve(cubic, [-1.5, -1.875], lam_range=(-2.0, 2.0))
    >>> test = TestFunction("u=-1.2", lambda x, t, j: x[0] + 1.2)
    >>> values = curve.points[:, 0] + 1.2
    >>> k = int(np.flatnonzero(np.diff(np.sign(values)))[0])
    >>> point = locate_on_curve(curve, test, k, values[k], values[k + 1])
    >>> round(float(point.x[0]), 12), round(point.value, 12)
    (-1.2, -0.528)
    """
    x0, t0 = curve.points[k], curve.tangents[k]
    length = float(t0 @ (curve.points[k + 1] - x0))
    sigma, here, value, located = locate(test, curve.equations, x0, t0, length, f0, f1)
    if here is None:
        return None
    kind = test.name
    if test.classify is not None:
        kind = test.classify(*here)
        if kind is None:
            return None
    note = "" if located else "the secant did not shrink its bracket to EVENT_TOL"
    return SpecialPoint(kind, here[0], here[1], k + 1, value, located, note)
