"""Problem classes for perturb, registered by name (``perturb list`` shows them).

A class in a module of this package is registered by its ``@register`` decorator alone: the
modules are found by a static scan, and imported only when one of their problems is used.
Problems also come from other installed distributions (entry-point group ``perturb.problems``) and,
named explicitly, from any file or module (:func:`load_problem`: ``path/to/file.py:ClassName``).

``problems`` depends on ``perturb``, never the reverse.
"""

from __future__ import annotations

from problems._registry import (
    ALL_PROBLEMS,
    ENTRY_POINT_GROUP,
    get_problem,
    problem_names,
    register,
)
from problems.base import ParameterSpec, Problem
from problems.loading import load_problem

__all__ = [
    "ALL_PROBLEMS",
    "ENTRY_POINT_GROUP",
    "ParameterSpec",
    "Problem",
    "get_problem",
    "load_problem",
    "problem_names",
    "register",
]
