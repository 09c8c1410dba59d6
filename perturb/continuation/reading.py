"""Values of a continued curve at given λ: every crossing, interpolated, then polished.

Between two consecutive points λ is monotone (the folds are points of the curve), so each segment
holds at most one point of a given λ. Its first guess is the cubic Hermite interpolant of the
segment's ends and tangents; Newton at fixed λ polishes it onto G(·, λ) = 0. Where that does not
converge within ``READ_MAX_ITER`` (beside a fold, where G_u is nearly singular) or strays off the
segment, the crossing is located on the curve itself by the secant along the segment
(:func:`perturb.continuation.events.locate`), whose corrector is regular at folds.
"""

from __future__ import annotations

import numpy as np

from perturb._defaults import READ_MAX_ITER, SAME_READING
from perturb.continuation.events import TestFunction, locate
from perturb.continuation.newton import newton_fixed

__all__ = ["read_segment", "values_at"]


def _hermite(x0, t0, x1, t1, theta):
    length = float(np.linalg.norm(x1 - x0))
    h00 = 2 * theta**3 - 3 * theta**2 + 1
    h10 = theta**3 - 2 * theta**2 + theta
    h01 = -2 * theta**3 + 3 * theta**2
    h11 = theta**3 - theta**2
    return h00 * x0 + h10 * length * t0 + h01 * x1 + h11 * length * t1


def read_segment(curve, k: int, value: float):
    """The point of ``curve``'s segment ``k`` (between points k and k + 1) at λ = ``value``
    (inside the segment's λ-range): interpolated, then polished (see the module notes); None
    when neither route finds it."""
    x0, x1 = curve.points[k], curve.points[k + 1]
    t0, t1 = curve.tangents[k], curve.tangents[k + 1]
    if x0[-1] == value:
        return x0
    if x1[-1] == value:
        return x1
    theta = (value - x0[-1]) / (x1[-1] - x0[-1])
    guess = _hermite(x0, t0, x1, t1, theta)
    guess[-1] = value
    polished = newton_fixed(curve.equations, guess, READ_MAX_ITER)
    reach = float(np.linalg.norm(x1 - x0))
    if polished.converged and float(np.linalg.norm(polished.x - guess)) <= reach:
        return polished.x
    length = float(t0 @ (x1 - x0))
    f = TestFunction("value", lambda y, t, j: y[-1] - value)
    _, here, _, located = locate(f, curve.equations, x0, t0, length, x0[-1] - value, x1[-1] - value)
    if here is None:
        return None
    x = np.array(here[0])
    x[-1] = value  # the secant's zero: within EVENT_TOL of it in λ
    return x


def values_at(curve, values) -> list[np.ndarray]:
    """Every point of ``curve`` at each λ in ``values`` (see the module notes).

    Parameters
    ----------
    curve : Curve
        A continued curve (it carries its equations for the polish).
    values : float or sequence of float

    Returns
    -------
    list of ndarray
        Per value, an array (k, n + 1) of the points found (k may be 0), in the curve's order.

    Examples
    --------
    >>> from perturb.continuation import CurveEquations, continue_both, values_at
    >>> cubic = CurveEquations(lambda x: [x[0] ** 3 - x[0] - x[1]],
    ...                        lambda x: [[3 * x[0] ** 2 - 1, -1.0]])
    >>> curve = continue_both(cubic, [0.0, 0.0], lam_range=(-1.0, 1.0))
    >>> [len(found) for found in values_at(curve, [-0.5, 0.0, 0.5])]
    [1, 3, 1]
    """
    lam = curve.points[:, -1]
    if len(lam) < 2:
        return [curve.points[lam == v] for v in np.atleast_1d(values)]
    low = np.minimum(lam[:-1], lam[1:])
    high = np.maximum(lam[:-1], lam[1:])
    out = []
    for value in np.atleast_1d(np.asarray(values, dtype=float)):
        found: list[np.ndarray] = []
        for k in np.flatnonzero((low <= value) & (value <= high) & (low < high)):
            x = read_segment(curve, int(k), float(value))
            if x is None:
                continue
            scale = max(1.0, float(np.max(np.abs(x))))
            if any(float(np.max(np.abs(x - y))) <= SAME_READING * scale for y in found):
                continue
            found.append(x)
        width = curve.points.shape[1]
        out.append(np.array(found, dtype=float).reshape(len(found), width))
    return out
