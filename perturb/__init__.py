"""perturb: periodic solutions of quasilinear oscillating systems by Poincaré's method.

Nothing symbolic happens at import time: systems are derived and solved on demand. The public names
are loaded on first use (PEP 562 module ``__getattr__``), so that ``import perturb`` — and the
command line's ``--help`` — does not load sympy, numpy or the engine.
"""

from __future__ import annotations

import importlib

from perturb.errors import (
    AccuracyWarning,
    IntegrationError,
    InvalidParameterError,
    InvalidSystemError,
    ParameterOverflowError,
    PerturbError,
    UnknownNameError,
)

__version__ = "0.1.0"

#: Public name -> the module that defines it (imported on first access).
_LAZY = {
    "PoincareMethod": "perturb.method",
    "solve": "perturb.method",
    "PeriodicSolution": "perturb.solution",
    "SolutionFailed": "perturb.solution",
    "Status": "perturb.solution",
    "EPS": "perturb.system",
    "QuasilinearSystem": "perturb.system",
    "Regime": "perturb.system",
    "Excitation": "perturb.excitation",
    "amplitude_equations": "perturb.method.driven",
    "frequency_response": "perturb.response",
    "Family": "perturb.method.family",
    "FamilyList": "perturb.method.family",
    "find_families": "perturb.method.families",
    "validate": "perturb.validation",
    "phase_diagram": "perturb.sweep.phase",
    "basins": "perturb.dynamics.basins",
    "transient": "perturb.dynamics.transient",
    "ramp": "perturb.dynamics.ramp",
}

#: Public names that are subpackages called like functions (``perturb.sweep(...)``: the package
#: :mod:`perturb.sweep` is callable); imported on first access, which needs their extra.
_LAZY_MODULES = {"sweep": "perturb.sweep"}

__all__ = [
    "EPS",
    "AccuracyWarning",
    "Excitation",
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
    "ParameterOverflowError",
    "UnknownNameError",
    "amplitude_equations",
    "basins",
    "find_families",
    "frequency_response",
    "phase_diagram",
    "ramp",
    "solve",
    "sweep",
    "transient",
    "validate",
]


def __getattr__(name: str):
    if name in _LAZY_MODULES:
        return importlib.import_module(_LAZY_MODULES[name])  # the import sets the attribute
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'perturb' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later lookups skip this hook
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
