"""A base for driven problems whose excitation frequency Ω is a user parameter.

The quasilinear form of a driven system is written in the detuning σ of
:math:`\\Omega = (p/q)\\,\\omega + \\varepsilon\\sigma`; users think in Ω. A driven problem says so
in its parameter map, ``parameter_map = {"sigma": "(Omega - 1)/eps"}`` (see
:attr:`problems.base.Problem.parameter_map`): the response can then be swept in Ω, its folds
are mapped back to Ω exactly, its backbone is drawn in Ω, and the order check rescales ε with σ
kept (Ω moves to (p/q)ω + ε'σ) — all read from the map.

:class:`DrivenProblem` only adds the check that ε is positive (σ divides by it); a user's own
driven problem does not need it: any :class:`~problems.base.Problem` whose system has an
``excitation`` is driven.
"""

from __future__ import annotations

from perturb.errors import InvalidParameterError
from problems.base import Problem

__all__ = ["DrivenProblem", "non_negative", "positive_frequency"]


def non_negative(value: float) -> str | None:
    """Check helper: zero or positive (a damping coefficient)."""
    return None if value >= 0 else "give a value >= 0"


def positive_frequency(value: float) -> str | None:
    """Check helper: an excitation frequency must be positive."""
    return None if value > 0 else "the excitation frequency must be > 0; give Omega > 0"


class DrivenProblem(Problem):
    """A driven problem with ``eps`` and ``Omega`` among its parameters (see the module notes)."""

    def check_values(self, values) -> None:
        super().check_values(values)
        if not values["eps"] > 0:
            raise InvalidParameterError(
                f"`eps` = {values['eps']:g} is invalid: the scale of the small terms must be > 0"
            )
