"""perturb: periodic solutions of quasilinear oscillating systems by Poincaré's method.

Nothing symbolic happens at import time: systems are derived and solved on demand.
"""

from perturb.errors import (
    AccuracyWarning,
    IntegrationError,
    InvalidParameterError,
    InvalidSystemError,
    PerturbError,
    UnknownNameError,
)
from perturb.method import PoincareMethod, solve
from perturb.method.families import Family, FamilyList, find_families
from perturb.solution import PeriodicSolution, SolutionFailed, Status
from perturb.system import EPS, QuasilinearSystem, Regime

__version__ = "0.1.0"


def __getattr__(name: str):
    """``perturb.validate``: imported on first use (it brings in the numerical oracle)."""
    if name == "validate":
        from perturb.validation import validate

        return validate
    raise AttributeError(f"module 'perturb' has no attribute {name!r}")


__all__ = [
    "EPS",
    "AccuracyWarning",
    "Family",
    "FamilyList",
    "IntegrationError",
    "InvalidParameterError",
    "InvalidSystemError",
    "PeriodicSolution",
    "PerturbError",
    "PoincareMethod",
    "QuasilinearSystem",
    "Regime",
    "SolutionFailed",
    "Status",
    "UnknownNameError",
    "find_families",
    "solve",
    "validate",
]
