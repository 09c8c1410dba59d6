"""Problem classes for perturb, registered by name (``perturb list`` shows them).

``problems`` depends on ``perturb``, never the reverse.
"""

from __future__ import annotations

from importlib import import_module

from perturb.errors import UnknownNameError
from problems.base import ParameterSpec, Problem

__all__ = ["ALL_PROBLEMS", "ParameterSpec", "Problem", "get_problem", "register"]

#: name -> "module:Class", imported on first use so that listing problems stays cheap.
_LAZY = {
    "duffing": "problems.duffing:Duffing",
    "van-der-pol": "problems.van_der_pol:VanDerPol",
    "linear-pair": "problems.linear_pair:LinearPair",
    "resonant-pair": "problems.resonant_pair:ResonantPair",
    "disk": "problems.rigid_body.disk:DiskInNewtonianField",
    "rigid-body": "problems.rigid_body.fast_spin:FastSpinRigidBody",
}

ALL_PROBLEMS: dict[str, type[Problem]] = {}


def register(cls: type[Problem]) -> type[Problem]:
    """Class decorator adding a problem to the registry under ``cls.name``."""
    ALL_PROBLEMS[cls.name] = cls
    return cls


def problem_names() -> list[str]:
    return sorted(set(_LAZY) | set(ALL_PROBLEMS))


def get_problem(name: str) -> type[Problem]:
    """The problem class registered as ``name``."""
    if name not in ALL_PROBLEMS and name in _LAZY:
        module, _, attr = _LAZY[name].partition(":")
        getattr(import_module(module), attr)
    if name not in ALL_PROBLEMS:
        raise UnknownNameError(f"`problem` = {name!r} is unknown: choose from {problem_names()}")
    return ALL_PROBLEMS[name]
