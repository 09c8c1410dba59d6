"""Steady states of driven systems by the series alone: the amplitude equations' real roots
(:mod:`~perturb.steady.roots`, :mod:`~perturb.steady.census`), their branches continued at order N
(:mod:`~perturb.steady.traced`, :mod:`~perturb.steady.continued`), stability
(:mod:`~perturb.steady.floquet`), amplitude measures and the backbone.

This room knows nothing of the oracle or of validation; :mod:`perturb.response` (the response
curve with its true orbits) and :mod:`perturb.validation` both stand on it.
"""

from perturb.steady.branches import (
    SteadyState,
    branch_names,
    branch_solution,
    branches_at,
    steady_state,
)
from perturb.steady.curve import Fold, FrequencyResponse, trace_branches
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
