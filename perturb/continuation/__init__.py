"""Pseudo-arclength continuation of curves G(u, λ) = 0: a room of its own, numpy only.

:func:`continue_curve` follows a curve through its folds (Keller's predictor along the tangent,
Newton's corrector on the hyperplane normal to it, the step from the corrector), locates the sign
changes of test functions on it (folds, branch points, and a client's: Neimark-Sacker, period
doubling...), and stops where λ leaves its range, the curve closes or leaves a domain; a step below
its floor is a failed status that says where. :meth:`Curve.values_at` reads every point of the curve
at given λ. Every corrector is one Newton loop, :func:`newton`, whose step is a function (a
client corrects onto its own augmented systems with it). Nothing here knows what the unknowns mean: the response of a driven system
(:mod:`perturb.response`) and the shooting of true orbits are its clients.

Examples
--------
The unit circle u² + λ² = 1 from (1, 0), both ways: a loop with two folds at λ = ±1.

>>> from perturb.continuation import CurveEquations, continue_both
>>> circle = CurveEquations(lambda x: [x[0] ** 2 + x[1] ** 2 - 1],
...                         lambda x: [[2 * x[0], 2 * x[1]]])
>>> curve = continue_both(circle, [1.0, 0.0], lam_range=(-2.0, 2.0))
>>> sorted(round(p.value, 12) for p in curve.of_kind("fold"))
[-1.0, 1.0]
>>> [round(abs(float(p[0])), 12) for p in curve.values_at(0.6)[0]]
[0.8, 0.8]
"""

from perturb.continuation.arclength import CurveEquations, continue_both, continue_curve
from perturb.continuation.events import BRANCH_POINT, FOLD, TestFunction, locate_on_curve
from perturb.continuation.newton import Correction, newton
from perturb.continuation.reading import values_at
from perturb.continuation.result import ContinuationStatus, Curve
from perturb.continuation.special import SpecialPoint

__all__ = [
    "BRANCH_POINT",
    "FOLD",
    "ContinuationStatus",
    "Correction",
    "Curve",
    "CurveEquations",
    "SpecialPoint",
    "TestFunction",
    "continue_both",
    "continue_curve",
    "locate_on_curve",
    "newton",
    "values_at",
]
