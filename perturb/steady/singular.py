"""The singular points of a response: folds and branch points, told apart.

Where two first-order roots meet, :math:`P_1(u, \\lambda) = 0` and :math:`\\det J = 0`
(:math:`J = \\partial P_1/\\partial u`, u the amplitudes, λ the swept parameter): the real solutions
of that system in (u, λ) are found exactly (:func:`perturb.steady.roots.real_roots`: certified).
Each is one of two things, read off the left null vector w of J (:math:`w^T J = 0`):

* a **fold** (saddle-node) when :math:`w \\cdot \\partial P_1/\\partial\\lambda \\ne 0`: the branch
  turns back in λ, two branches end there and the response jumps in a slow sweep;
* a **branch point** when :math:`w \\cdot \\partial P_1/\\partial\\lambda = 0`: a branch crosses
  another one and goes on (a pitchfork where a symmetric response loses its symmetry, where a mode
  at rest starts to move, or where a parametric system's trivial response loses its stability at
  the edge of its tongue). Symmetry makes the product vanish exactly; it is tested against
  :data:`BRANCH_POINT_TOL` relative to the sizes of w and of the derivative.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from perturb._defaults import BRANCH_POINT_TOL, SAME_POINT
from perturb.steady.roots import RootStatus, real_roots

__all__ = ["SingularPoints", "singular_points"]


class SingularPoints(tuple):
    """``(folds, branch_points, why)``: lists of ``(value, amplitudes, norms)`` and the reason they
    could not be found ("" when they were)."""

    __slots__ = ()

    @property
    def folds(self) -> list:
        return self[0]

    @property
    def branch_points(self) -> list:
        return self[1]

    @property
    def why(self) -> str:
        return self[2]


def singular_points(
    first, unknowns, swept, low: float, high: float, coordinates, seconds: float | None = None
) -> SingularPoints:
    """Folds and branch points of the first-order rows ``first`` in ``[low, high]`` of ``swept``.

    Parameters
    ----------
    first : sequence of sympy.Expr
        The first-order rows, polynomials in ``unknowns`` and ``swept`` with rational coefficients.
    unknowns : sequence of sympy.Symbol
        The amplitudes ``a_c, b_c`` of each coordinate c of ``coordinates``.
    swept : sympy.Symbol
    low, high : float
    coordinates : sequence of str
    seconds : float, optional
        The certified solver's budget (default that of :func:`~perturb.steady.roots.real_roots`).

    Returns
    -------
    SingularPoints

    Examples
    --------
    >>> import sympy as sp
    >>> a, b, s = sp.symbols("a_x b_x sigma")
    >>> rows = [s * a - a * (a**2 + b**2) - b / 10, s * b - b * (a**2 + b**2) + a / 10 + 1]
    >>> found = singular_points(rows, [a, b], s, -5.0, 200.0, ["x"])
    >>> len(found.folds), len(found.branch_points)
    (2, 0)
    """
    unknowns = list(unknowns)
    if swept not in set().union(*(sp.sympify(e).free_symbols for e in first)):
        return SingularPoints(([], [], ""))
    jac = sp.Matrix([[sp.diff(e, u) for u in unknowns] for e in first])
    det = sp.expand(jac.det(method="berkowitz"))
    budget = {} if seconds is None else {"seconds": seconds}
    found = real_roots([*first, det], [*unknowns, swept], floats=True, **budget)
    if found.status is RootStatus.NO_REAL_ROOT:
        return SingularPoints(([], [], ""))
    if found.status is not RootStatus.SOLVED:
        return SingularPoints(([], [], f"{found.status.value} ({found.message})"))
    args = [*unknowns, swept]
    jacobian = sp.lambdify(args, jac, "numpy")
    along = sp.lambdify(args, [sp.diff(e, swept) for e in first], "numpy")
    folds, branch_points = [], []
    for root in found.roots:
        value = float(root[swept])
        if not low <= value <= high:
            continue
        x = [float(root[u]) for u in args]
        amplitudes = {u.name: float(root[u]) for u in unknowns}
        norms = {c: math.hypot(amplitudes[f"a_{c}"], amplitudes[f"b_{c}"]) for c in coordinates}
        kind = branch_points if _is_branch_point(jacobian(*x), along(*x)) else folds
        if any(_same(point, value, norms) for point in kind):
            continue  # shifted by one forcing period: the same orbit
        kind.append((value, amplitudes, norms))
    folds.sort(key=lambda p: p[0])
    branch_points.sort(key=lambda p: p[0])
    return SingularPoints((folds, branch_points, ""))


def _is_branch_point(jacobian, derivative) -> bool:
    matrix = np.asarray(jacobian, dtype=float)
    d = np.asarray(derivative, dtype=float).ravel()
    size = float(np.linalg.norm(d))
    if size == 0.0:
        return True
    w = np.linalg.svd(matrix)[0][:, -1]
    return abs(float(w @ d)) <= BRANCH_POINT_TOL * size


def _same(point, value: float, norms: dict) -> bool:
    pairs = [(point[0], value), *((point[2][c], n) for c, n in norms.items())]
    return all(abs(p - q) <= SAME_POINT * max(1.0, abs(p)) for p, q in pairs)
