"""What a continuation returns: the points of the curve, its special points, how it ended."""

from __future__ import annotations

import enum

import numpy as np
from attrs import field, frozen

from perturb.continuation.reading import values_at as _values_at
from perturb.continuation.special import SpecialPoint
from perturb.errors import ContinuationError

__all__ = ["ContinuationStatus", "Curve"]


class ContinuationStatus(enum.Enum):
    """How a continuation ended; the values are the messages shown to users.

    :attr:`Curve.message` adds where (the last point) and the numbers of the run.

    Examples
    --------
    >>> from perturb.continuation import ContinuationStatus
    >>> ContinuationStatus.LEFT_RANGE.success, ContinuationStatus.STEP_FLOOR.success
    (True, False)
    >>> print(ContinuationStatus.STEP_FLOOR.value)
    the step fell below its floor: the corrector does not converge there at any step (a singular point the curve cannot pass, or a curve that ends)
    """

    LEFT_RANGE = "the curve left the parameter range"
    CLOSED = "the curve closed on itself (a loop)"
    LEFT_DOMAIN = "the curve left the domain of the unknowns"
    MAX_POINTS = (
        "the budget of points was spent before the curve left the range: raise `max_points`"
    )
    STEP_FLOOR = (
        "the step fell below its floor: the corrector does not converge there at any step (a "
        "singular point the curve cannot pass, or a curve that ends)"
    )
    NOT_FINITE = "the residual or its Jacobian is not finite there"
    START_FAILED = "the starting point could not be corrected onto the curve (Newton's method)"
    SINGULAR_START = (
        "the curve's tangent is not defined at the starting point (the Jacobian [G_u | G_λ] has "
        "rank below n: a branch point): start beside it"
    )

    @property
    def success(self) -> bool:
        """The curve was followed until it left the range or the domain, or closed."""
        return self in (
            ContinuationStatus.LEFT_RANGE,
            ContinuationStatus.CLOSED,
            ContinuationStatus.LEFT_DOMAIN,
        )


@frozen
class Curve:
    """A branch of solutions of G(u, λ) = 0 followed by pseudo-arclength continuation.

    Attributes
    ----------
    points : ndarray, shape (m, n + 1)
        The points ``(u, λ)`` in the order of the continuation, special points included.
    tangents : ndarray, shape (m, n + 1)
        The unit tangent at each point, oriented along the continuation.
    arclength : ndarray, shape (m,)
        Arclength from the first point (the sum of the pseudo-arclength steps).
    special : tuple of SpecialPoint
        In the order met.
    tests : dict of str to ndarray
        Each test function's value at every point.
    status : ContinuationStatus
    message : str
        The status with where and the numbers of the run.
    equations : object
        The :class:`~perturb.continuation.CurveEquations` it was traced on (for
        :meth:`values_at`).

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.continuation import CurveEquations, continue_curve
    >>> line = CurveEquations(lambda x: [x[0] - 2 * x[1]], lambda x: [[1.0, -2.0]])
    >>> curve = continue_curve(line, [0.0, 0.0], lam_range=(0.0, 1.0))
    >>> curve.status.name, [round(float(u), 12) for u in curve.values_at(0.5)[0][:, 0]]
    ('LEFT_RANGE', [1.0])
    """

    points: np.ndarray = field(eq=False)
    tangents: np.ndarray = field(eq=False)
    arclength: np.ndarray = field(eq=False)
    special: tuple = field(converter=tuple)
    tests: dict = field(eq=False)
    status: ContinuationStatus
    message: str
    equations: object = field(eq=False, repr=False, default=None)
    settings: object = field(eq=False, repr=False, default=None)

    @property
    def success(self) -> bool:
        return self.status.success

    @property
    def lam(self) -> np.ndarray:
        """λ at every point."""
        return self.points[:, -1]

    def raise_for_status(self) -> Curve:
        """``self`` if the continuation succeeded, else raise :class:`~perturb.errors.ContinuationError`."""
        if not self.success:
            raise ContinuationError(f"continuation failed ({self.status.name}): {self.message}")
        return self

    def of_kind(self, kind: str) -> tuple[SpecialPoint, ...]:
        """The special points of ``kind``."""
        return tuple(p for p in self.special if p.kind == kind)

    def values_at(self, values) -> list[np.ndarray]:
        """Every point of the curve at each λ in ``values``, polished onto G(·, λ) = 0.

        Returns
        -------
        list of ndarray
            One array of shape (k, n + 1) per value (k = 0 where the curve does not reach it).
        """
        return _values_at(self, values)
