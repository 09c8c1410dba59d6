"""The forced, damped Duffing oscillator near its primary resonance: ``perturb response forced-duffing``.

.. math:: \\ddot x + 2\\zeta\\varepsilon\\dot x + x + \\gamma\\varepsilon x^3 = F\\varepsilon\\cos\\Omega t,
          \\qquad \\Omega = 1 + \\varepsilon\\sigma

(ζ, γ, F the scaled damping, stiffness and forcing; γ > 0 hardening, γ < 0 softening). Its
first-order response is :math:`[(\\sigma - 3\\gamma a^2/8)^2 + \\zeta^2]a^2 = (F/2)^2`, its backbone
:math:`\\Omega = 1 + 3\\gamma\\varepsilon a^2/8`; both are derived by the engine, not entered here.
"""

from __future__ import annotations

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from perturb.errors import InvalidParameterError
from problems import register
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

X, XDOT, THETA = sp.symbols("x xdot theta")
ZETA, GAMMA, FORCE, SIGMA = sp.symbols("zeta gamma F sigma")


@register
class ForcedDuffing(DrivenProblem):
    """ẍ + 2ζεẋ + x + γεx³ = Fε cos Ωt near Ω = 1.

    Examples
    --------
    >>> from problems import get_problem
    >>> duffing = get_problem("forced-duffing").create(Omega=1.05)
    >>> [(f.name, f.solution.message.split("; ")[1]) for f in duffing.families(1)]
    [('lower', 'stable (Floquet)'), ('middle', 'unstable (Floquet)'), ('upper', 'stable (Floquet)')]
    """

    name = "forced-duffing"
    summary = (
        "forced damped Duffing xddot + 2 zeta eps xdot + x + gamma eps x^3 = F eps cos(Omega t), "
        "primary resonance Omega ~ 1"
    )
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms (damping, cubic stiffness, forcing)",
                      positive),
        ParameterSpec("zeta", 0.1, "scaled damping (the damping ratio is eps*zeta)", non_negative),
        ParameterSpec("gamma", 1.0, "scaled cubic stiffness (> 0 hardening, < 0 softening)"),
        ParameterSpec("F", 1.0, "scaled forcing amplitude (the force is eps*F)", positive),
        ParameterSpec("Omega", 1.0, "excitation frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 1)/eps"}  # Omega = 1 + eps*sigma

    def check_values(self, values) -> None:
        super().check_values(values)
        if values["zeta"] == 0 and values["gamma"] == 0:
            raise InvalidParameterError(
                "`zeta` = 0 with `gamma` = 0 is invalid: an undamped linear oscillator forced at "
                "resonance has no bounded response; give zeta > 0 (damping) or gamma != 0"
            )

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X],
            velocities=[XDOT],
            frequencies=[1],
            rhs=[EPS * (-2 * ZETA * XDOT - GAMMA * X**3 + FORCE * sp.cos(THETA))],
            parameters=[ZETA, GAMMA, FORCE, SIGMA],
            excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
            name="forced-duffing",
        )
