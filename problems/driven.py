"""A base for driven problems whose excitation frequency Ω is a user parameter.

The quasilinear form of a driven system is written in the detuning σ of
:math:`\\Omega = (p/q)\\,\\omega + \\varepsilon\\sigma`; users think in Ω. :class:`DrivenProblem`
keeps ``Omega`` (and the scaled coefficients, which multiply ε in the equations) as parameters and
gives the system σ = (Ω − (p/q)ω)/ε. Rescaling ε for the order check keeps the scaled problem
fixed: σ and the scaled coefficients stay, Ω moves to (p/q)ω + ε'σ.

A user's own driven problem does not need this base: any :class:`~problems.base.Problem` whose
system has an ``excitation`` is driven (it may take σ as a parameter directly).
"""

from __future__ import annotations

import math

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
    """A driven problem with ``eps`` and ``Omega`` among its parameters (see the module notes).

    Subclasses set :attr:`resonance_frequency`: (p/q) ω of the resonance studied, in terms of
    the parameter values (a number or a function of them).
    """

    #: (p/q) * omega of the resonance (Omega = resonance_frequency + eps * sigma).
    resonance_frequency: float = 1.0
    #: The parameters that vanish in the unforced, undamped system (the backbone's), by name.
    unforced: dict = {}

    def _resonance(self, values) -> float:
        rf = self.resonance_frequency
        return float(rf(values)) if callable(rf) else float(rf)

    def detuning(self) -> float:
        """σ = (Ω − (p/q)ω)/ε."""
        return (self.values["Omega"] - self._resonance(self.values)) / self.values["eps"]

    def check_values(self, values) -> None:
        super().check_values(values)
        if not values["eps"] > 0:
            raise InvalidParameterError(
                f"`eps` = {values['eps']:g} is invalid: the scale of the small terms must be > 0"
            )

    def symbol_values(self) -> dict[str, float]:
        values = {**self.values, "sigma": self.detuning()}
        return {p.name: values[p.name] for p in self.system().parameters if p.name in values}

    def backbone_system(self, parameter: str):
        """``(free system, coordinate, ω -> Ω)`` of the backbone when sweeping ``Omega``.

        The free system is this one with :attr:`unforced` put in and no excitation; its
        frequency ω(a) at amplitude a is where the forced response peaks, at Ω = (p/q) ω.
        """
        import attrs

        if parameter != "Omega" or not self.unforced:
            return None
        system = self.system()
        names = {p.name for p in system.parameters}
        free = attrs.evolve(
            system.with_values({k: v for k, v in self.unforced.items() if k in names}),
            excitation=None,
        )
        detuning = system.excitation.detuning
        free = attrs.evolve(free, parameters=tuple(p for p in free.parameters if p != detuning))
        ratio = float(system.excitation.ratio)
        coordinate = system.coordinates[system.reference_index].name
        return free, coordinate, lambda w: ratio * w

    def with_epsilon(self, eps: float) -> Problem | None:
        if not (isinstance(eps, int | float) and math.isfinite(eps) and eps > 0):
            return None
        omega = self._resonance(self.values) + eps * self.detuning()
        if not omega > 0:
            return None
        return self.with_parameters(eps=eps, Omega=omega)
