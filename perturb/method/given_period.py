"""The order-by-order template when the period is given: a driven system's construction.

:class:`DrivenOrderByOrder` is :class:`~perturb.method.construction.OrderByOrder` with the frame
of a driven system (see :mod:`perturb.method.driven` for the mathematics): the frequency is the
excitation's (:math:`\\nu = \\omega_{ref}/q + \\varepsilon\\sigma/p`), so the frequency
coefficients are known and no coordinate's phase is free — the forcing fixes the time origin.
"""

from __future__ import annotations

import sympy as sp
from attrs import frozen

from perturb.errors import InvalidSystemError, bad_value
from perturb.method.conditions import ConditionSolver
from perturb.method.construction import OrderByOrder

__all__ = ["DrivenOrderByOrder", "ForcedConditions"]


@frozen
class ForcedConditions(ConditionSolver):
    """The periodicity conditions of a driven system: the forcing fixes the phase, so the phase
    coordinate's cosine amplitude may vanish (no Rabinowitsch condition), and the default branch
    is the one of largest amplitude :math:`a^2 + b^2` of that coordinate."""

    def phase_amplitude_nonzero(self) -> bool:
        return False

    def size(self, generating) -> sp.Expr:
        a, b = generating.cos_amplitudes[self.phase], generating.sin_amplitudes[self.phase]
        return a**2 + b**2


class DrivenOrderByOrder(OrderByOrder):
    """The order-by-order template for a driven system (see the module docstring)."""

    def _setup_phase_and_harmonics(self):
        method, system = self.method, self.system
        drive = system.excitation
        if method.amplitudes:
            raise bad_value(
                "amplitudes", method.amplitudes,
                "a driven system's response amplitudes are fixed by its forcing: drop them "
                "(choose a branch with `branch` or `find_families`)",
                InvalidSystemError,
            )  # fmt: skip
        if method.phase_coordinate is not None:
            raise bad_value(
                "phase_coordinate", method.phase_coordinate,
                "the forcing fixes the time origin of a driven system: drop it",
                InvalidSystemError,
            )  # fmt: skip
        if method.dependent_condition == "phase-sine":
            raise bad_value(
                "dependent_condition", method.dependent_condition,
                "a driven system has no redundant periodicity condition: use 'auto' or 'none'",
                InvalidSystemError,
            )  # fmt: skip
        self.phase = system.reference_index
        self.drop_phase_sine = False
        self.w_ref = system.frequencies[self.phase] / drive.q
        self.harmonics = []
        for w in system.frequencies:
            ratio = sp.nsimplify(sp.simplify(w / self.w_ref))
            self.harmonics.append(int(ratio) if ratio.is_Integer and ratio > 0 else None)

    def _phase_fixed_by(self, i: int) -> bool:
        return False

    def _frequency_coefficient(self, k: int):
        drive = self.system.excitation
        value = drive.detuning / drive.p if k == 1 else sp.S.Zero
        return self.conv.to_native(sp.sympify(value))

    def _make_solver(self) -> ConditionSolver:
        return ForcedConditions(self.method.branch, self.method.solve_seconds, self.phase)
