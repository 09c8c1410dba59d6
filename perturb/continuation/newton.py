"""The linear algebra of a continuation step: the tangent, and one Newton loop with three steps.

For G: R^(n+1) -> R^n with Jacobian J = [G_u | G_λ] (n x (n+1)), the tangent t is the unit null
vector of J, oriented along the continuation by solving the bordered system

.. math:: \\begin{pmatrix} J \\\\ t_{old}^T \\end{pmatrix} z = e_{n+1}, \\qquad t = z/|z|,

so that t·t_old > 0 (Keller). The corrector is Newton's method on {G(x) = 0, t_k·(x − x_pred) = 0}
(the hyperplane through the predictor orthogonal to the previous tangent); its matrix is the same
bordered matrix, regular at folds. The determinant of the bordered matrix keeps its sign along a
curve with a continuously oriented tangent except where the curve crosses another: a branch point.

Every corrector of the continuation is :func:`newton`, one loop whose step is a function: the
bordered step (:func:`correct`), the step of G_u at fixed λ (:func:`newton_fixed`), the least-norm
step (:func:`newton_nearest`), and a client's own (the true curve's minimally augmented systems).
"""

from __future__ import annotations

import math

import numpy as np
from attrs import frozen

from perturb._defaults import CORRECTOR_MAX_ITER, CORRECTOR_TOL

__all__ = [
    "Correction",
    "bordered",
    "correct",
    "newton",
    "newton_fixed",
    "newton_nearest",
    "null_tangent",
    "tangent",
]


@frozen
class Correction:
    """The outcome of one corrector run (:func:`newton`).

    Attributes
    ----------
    x : ndarray
        The corrected point (the last iterate when not converged).
    jacobian : ndarray or None
        J at ``x`` (None where it was not evaluated or not finite).
    iterations : int
        The Newton steps taken.
    converged : bool
    finite : bool
        False: a non-finite value was met, which ends the continuation.

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.continuation import CurveEquations, newton
    >>> line = CurveEquations(lambda x: [x[0] - 2 * x[1]], lambda x: [[1.0, -2.0]])
    >>> found = newton(line, np.array([0.0, 1.0]), lambda x, g, jac: np.append(-g, 0.0))
    >>> found.converged, found.x.tolist(), found.iterations
    (True, [2.0, 1.0], 2)
    """

    x: np.ndarray
    jacobian: np.ndarray | None
    iterations: int
    converged: bool
    finite: bool = True


def _finite(*arrays) -> bool:
    # a sum is not finite when any term is not (inf - inf is nan): one reduction an array
    return all(math.isfinite(a.sum()) for a in arrays)


def _solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a⁻¹ b`` for the small systems of a continuation: 2 x 2 and 3 x 3 by Cramer's rule on
    floats (numpy's per-call cost dwarfs their arithmetic), larger ones by LAPACK. Raises
    :class:`numpy.linalg.LinAlgError` on a singular matrix, as numpy does."""
    n = a.shape[0]
    if n == 2:
        (p, q), (r, t) = a.tolist()
        det = p * t - q * r
        if det == 0 or not math.isfinite(det):
            raise np.linalg.LinAlgError("singular matrix")
        u, v = b.tolist()
        return np.array([(t * u - q * v) / det, (p * v - r * u) / det])
    if n == 3:
        (a0, a1, a2), (b0, b1, b2), (c0, c1, c2) = a.tolist()
        m0, m1, m2 = b1 * c2 - b2 * c1, b2 * c0 - b0 * c2, b0 * c1 - b1 * c0
        det = a0 * m0 + a1 * m1 + a2 * m2
        if det == 0 or not math.isfinite(det):
            raise np.linalg.LinAlgError("singular matrix")
        u, v, w = b.tolist()
        x = (u * m0 + v * (a2 * c1 - a1 * c2) + w * (a1 * b2 - a2 * b1)) / det
        y = (u * m1 + v * (a0 * c2 - a2 * c0) + w * (a2 * b0 - a0 * b2)) / det
        z = (u * m2 + v * (a1 * c0 - a0 * c1) + w * (a0 * b1 - a1 * b0)) / det
        return np.array([x, y, z])
    return np.linalg.solve(a, b)


def _size(v: np.ndarray) -> float:
    """max |v_i| (ndarray methods: a fraction of numpy's function-call cost on tiny arrays)."""
    return float(abs(v).max()) if v.size else 0.0


def bordered(jacobian: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The (n+1) x (n+1) matrix [J; t^T]."""
    return np.vstack((jacobian, t[None, :]))


def null_tangent(jacobian: np.ndarray) -> np.ndarray:
    """The unit null vector of J (n x (n+1)) from its SVD, of arbitrary orientation (the start)."""
    return np.linalg.svd(np.atleast_2d(jacobian))[2][-1]


def tangent(jacobian: np.ndarray, previous: np.ndarray) -> np.ndarray | None:
    """The unit tangent at a point with Jacobian J, oriented like ``previous`` (None: singular)."""
    rhs = np.zeros(jacobian.shape[1])
    rhs[-1] = 1.0
    try:
        z = _solve(bordered(jacobian, previous), rhs)
    except np.linalg.LinAlgError:
        return None
    norm = float(np.linalg.norm(z))
    if not (math.isfinite(norm) and norm > 0):
        return None
    return z / norm


def newton(
    equations,
    x0: np.ndarray,
    step,
    max_iter: int = CORRECTOR_MAX_ITER,
    tol: float = CORRECTOR_TOL,
    contracting: bool = True,
    jacobian_at_end: bool = True,
) -> Correction:
    """The one Newton loop of the continuation, its step a function.

    From ``x0``, each iteration evaluates G and J = ``equations.jacobian`` at x and moves x by
    ``step(x, g, jac)`` (an array of x's length; it may raise
    :class:`numpy.linalg.LinAlgError` on a singular system). Converged when a step is below
    ``tol * max(1, |x|)`` (max norms); then J is evaluated at the result (unless
    ``jacobian_at_end`` is False: a caller that does not need it saves its cost). Rejected when
    a value is not finite (``finite`` False), the system is singular, the step is not finite, the
    steps stop shrinking (from the third on, one more than half the previous: the start is outside
    the basin; only when ``contracting``) or after ``max_iter`` iterations.

    Parameters
    ----------
    equations : CurveEquations or any object with ``residual(x)`` and ``jacobian(x)``
    x0 : ndarray
    step : callable
        ``step(x, g, jac) -> dx``.
    max_iter : int
    tol : float
    contracting : bool
    jacobian_at_end : bool

    Returns
    -------
    Correction

    Examples
    --------
    The unit circle u² + λ² = 1 at λ = 0.6, Newton in u alone:

    >>> import numpy as np
    >>> from perturb.continuation import CurveEquations
    >>> circle = CurveEquations(lambda x: [x[0] ** 2 + x[1] ** 2 - 1],
    ...                         lambda x: [[2 * x[0], 2 * x[1]]])
    >>> fixed = lambda x, g, jac: np.append(-g / jac[:, 0], 0.0)
    >>> found = newton(circle, np.array([1.0, 0.6]), fixed)
    >>> found.converged, round(float(found.x[0]), 12)
    (True, 0.8)
    """
    x = np.array(x0, dtype=float)
    previous = math.inf
    for iteration in range(1, max_iter + 1):
        g = np.asarray(equations.residual(x), dtype=float)
        jac = np.atleast_2d(np.asarray(equations.jacobian(x), dtype=float))
        if not _finite(g, jac):
            return Correction(x, None, iteration, False, False)
        try:
            dx = step(x, g, jac)
        except np.linalg.LinAlgError:
            return Correction(x, jac, iteration, False)
        size = _size(dx)
        if not math.isfinite(size) or (contracting and iteration > 2 and size > 0.5 * previous):
            return Correction(x, jac, iteration, False)  # not contracting: outside the basin
        x = x + dx
        previous = size
        if size <= tol * max(1.0, _size(x)):
            if not jacobian_at_end:
                return Correction(x, None, iteration, True, _finite(x))
            jac = np.atleast_2d(np.asarray(equations.jacobian(x), dtype=float))
            if not _finite(x, jac):
                return Correction(x, None, iteration, False, False)
            return Correction(x, jac, iteration, True)
    return Correction(x, None, max_iter, False)


def correct(equations, predictor: np.ndarray, normal: np.ndarray) -> Correction:
    """Newton on {G(x) = 0, normal·(x − predictor) = 0} from the predictor (:func:`newton` with
    the bordered step): regular at folds."""

    def bordered_step(x, g, jac):
        rhs = np.concatenate((-g, [-float(normal @ (x - predictor))]))
        return _solve(bordered(jac, normal), rhs)

    return newton(equations, predictor, bordered_step)


def newton_fixed(equations, x0: np.ndarray, max_iter: int = CORRECTOR_MAX_ITER) -> Correction:
    """Newton on G(u, λ) = 0 in u with λ = x0[-1] fixed (G_u square; :func:`newton` with the
    step of G_u alone)."""

    def fixed_step(x, g, jac):
        return np.append(_solve(jac[:, :-1], -g), 0.0)

    return newton(equations, x0, fixed_step, max_iter)


def newton_nearest(equations, x0: np.ndarray, max_iter: int = CORRECTOR_MAX_ITER) -> Correction:
    """Newton's method with the least-norm step (Gauss-Newton on the n x (n+1) Jacobian): to a
    point of the curve near x0, λ free; regular at folds, where Newton at fixed λ is not
    (:func:`newton` with the least-squares step)."""

    def least_norm_step(x, g, jac):
        return np.linalg.lstsq(jac, -g, rcond=None)[0]

    return newton(equations, x0, least_norm_step, max_iter)
