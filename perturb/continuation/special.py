"""A special point of a continued curve: a fold, a branch point, or a client's event."""

from __future__ import annotations

import numpy as np
from attrs import field, frozen

__all__ = ["SpecialPoint"]


@frozen
class SpecialPoint:
    """A point where a test function changes sign along the curve, located on it.

    Attributes
    ----------
    kind : str
        The test function's name (``"fold"``, ``"branch-point"``, or a client's), or what its
        ``classify`` called it.
    x : ndarray
        The point ``(u, λ)``, on the curve to the corrector's tolerance.
    tangent : ndarray
        The unit tangent there, oriented along the continuation.
    index : int
        Its position in :attr:`Curve.points` (special points are inserted into the curve).
    residual : float
        The test function's value at ``x`` (zero to the location's tolerance when ``located``).
    located : bool
        False when the secant could not shrink the bracket to ``EVENT_TOL`` (the point is then the
        bracket's best end, and ``note`` says so).
    note : str

    Examples
    --------
    >>> from perturb.continuation import CurveEquations, continue_curve
    >>> circle = CurveEquations(lambda x: [x[0] ** 2 + x[1] ** 2 - 1],
    ...                         lambda x: [[2 * x[0], 2 * x[1]]])
    >>> fold = continue_curve(circle, [1.0, 0.0], lam_range=(-2.0, 2.0)).of_kind("fold")[0]
    >>> fold.kind, round(fold.value, 12), round(abs(float(fold.tangent[-1])), 12)
    ('fold', 1.0, 0.0)
    """

    kind: str
    x: np.ndarray = field(eq=False, converter=lambda v: np.array(v, dtype=float))
    tangent: np.ndarray = field(eq=False, converter=lambda v: np.array(v, dtype=float))
    index: int
    residual: float = 0.0
    located: bool = True
    note: str = ""

    @property
    def value(self) -> float:
        """λ at the point (the last coordinate)."""
        return float(self.x[-1])
