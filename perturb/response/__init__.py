"""Frequency responses of driven systems: every branch, its stability, its folds.

:func:`frequency_response` sweeps a parameter and solves the amplitude equations of
:mod:`perturb.method.driven` for every real root at each value (:func:`real_roots`).
"""

from perturb.steady.branches import (
    SteadyState,
    branch_names,
    branch_solution,
    branches_at,
    steady_state,
)
from perturb.steady.curve import (
    Fold,
    FrequencyResponse,
    trace_branches,
)
from perturb.steady.point import BranchPoint, ResponsePoint
from perturb.steady.roots import RootSet, RootStatus, real_roots
from perturb.steady.sampled import frequency_response

__all__ = [
    "BranchPoint",
    "SteadyState",
    "branch_names",
    "branch_solution",
    "branches_at",
    "Fold",
    "FrequencyResponse",
    "ResponsePoint",
    "RootSet",
    "RootStatus",
    "frequency_response",
    "real_roots",
    "steady_state",
    "trace_branches",
]
