"""The parametrically excited, damped Duffing (Mathieu–Duffing) oscillator near Ω = 2.

.. math:: \\ddot x + 2\\zeta\\varepsilon\\dot x + (1 + 2h\\varepsilon\\cos\\Omega t)\\,x
          + \\gamma\\varepsilon x^3 = 0, \\qquad \\Omega = 2 + \\varepsilon\\sigma

The trivial response x = 0 loses its stability inside the instability tongue around Ω = 2, from
which the nonlinear branches (bent by γ) grow: the response has period 2 forcing periods
(p/q = 2). Everything, the tongue included, is derived by the engine.
"""

from __future__ import annotations

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

X, XDOT, THETA = sp.symbols("x xdot theta")
ZETA, H, GAMMA, SIGMA = sp.symbols("zeta h gamma sigma")


@register
class ParametricDuffing(DrivenProblem):
    """ẍ + 2ζεẋ + (1 + 2hε cos Ωt) x + γεx³ = 0 near Ω = 2.

    Examples
    --------
    >>> from perturb.response import steady_state_of
    >>> from problems import get_problem
    >>> mathieu = get_problem("parametric-duffing").create(Omega=2.0)
    >>> [(p.trivial, p.stable) for p in steady_state_of(mathieu, 1).points]
    [(True, False), (False, True)]
    """

    name = "parametric-duffing"
    summary = (
        "parametrically excited damped Duffing xddot + 2 zeta eps xdot + (1 + 2 h eps cos Omega t) x "
        "+ gamma eps x^3 = 0, principal parametric resonance Omega ~ 2"
    )
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms", positive),
        ParameterSpec("zeta", 0.1, "scaled damping (the damping ratio is eps*zeta)", non_negative),
        ParameterSpec("h", 1.0, "scaled depth of the stiffness modulation", positive),
        ParameterSpec("gamma", 1.0, "scaled cubic stiffness"),
        ParameterSpec("Omega", 2.0, "excitation frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 2)/eps"}  # Omega = 2 + eps*sigma

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X],
            velocities=[XDOT],
            frequencies=[1],
            rhs=[EPS * (-2 * ZETA * XDOT - 2 * H * X * sp.cos(THETA) - GAMMA * X**3)],
            parameters=[ZETA, H, GAMMA, SIGMA],
            excitation=Excitation(phase=THETA, ratio=2, detuning=SIGMA),
            name="parametric-duffing",
        )
