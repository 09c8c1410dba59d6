"""A two-mode system with a 1:2 internal resonance, its second mode forced: the autoparametric
vibration absorber (saturation).

.. math::

    \\ddot x + x &= \\varepsilon\\,[-2\\zeta_1\\dot x - 2\\alpha_1 x y], \\\\
    \\ddot y + \\omega_2^2 y &= \\varepsilon\\,[-2\\zeta_2\\dot y - \\alpha_2 x^2 + F\\cos\\Omega t],
    \\qquad \\omega_2 = 2 + \\varepsilon\\delta,\\ \\Omega = 2 + \\varepsilon\\sigma.

The quasilinear form takes the frequencies 1 and 2 exactly and the internal detuning into the
right-hand side, :math:`\\omega_2^2 y = 4y + \\varepsilon(4\\delta + \\varepsilon\\delta^2)y`. Above a
threshold of F the forced mode's amplitude stops growing (it *saturates*) and the energy flows
into the first mode: the response the engine derives shows it.
"""

from __future__ import annotations

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

X, Y, XDOT, YDOT, THETA = sp.symbols("x y xdot ydot theta")
Z1, Z2, A1, A2, DELTA, FORCE, SIGMA = sp.symbols("zeta1 zeta2 alpha1 alpha2 delta F sigma")


@register
class AutoparametricAbsorber(DrivenProblem):
    """Two modes 1:2 in internal resonance, the second forced near its frequency.

    Examples
    --------
    Above the threshold the forced mode's amplitude saturates: it is the same at every F.

    >>> from perturb.response import steady_state_of
    >>> from problems import get_problem
    >>> cls = get_problem("autoparametric-absorber")
    >>> def coupled_y(force):
    ...     points = steady_state_of(cls.create(F=force), 0).points
    ...     return round(next(p.norms["y"] for p in points if p.norms["x"] > 0), 9)
    >>> coupled_y(1.0) == coupled_y(4.0)
    True
    """

    name = "autoparametric-absorber"
    summary = (
        "1:2 internal resonance x'' + x = eps(-2 zeta1 x' - 2 alpha1 x y), y'' + omega2^2 y = "
        "eps(-2 zeta2 y' - alpha2 x^2 + F cos Omega t), omega2 = 2 + eps delta, Omega ~ 2 (saturation)"
    )
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms", positive),
        ParameterSpec("zeta1", 0.1, "scaled damping of the absorber mode x", non_negative),
        ParameterSpec("zeta2", 0.1, "scaled damping of the forced mode y", non_negative),
        ParameterSpec("alpha1", 1.0, "scaled quadratic coupling in the x equation"),
        ParameterSpec("alpha2", 1.0, "scaled quadratic coupling in the y equation"),
        ParameterSpec("delta", 0.0, "internal detuning: omega2 = 2 + eps*delta"),
        ParameterSpec("F", 1.0, "scaled forcing amplitude of the y mode", positive),
        ParameterSpec("Omega", 2.0, "excitation frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 2)/eps"}  # Omega = 2 + eps*sigma

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X, Y],
            velocities=[XDOT, YDOT],
            frequencies=[1, 2],
            rhs=[
                EPS * (-2 * Z1 * XDOT - 2 * A1 * X * Y),
                EPS * (-2 * Z2 * YDOT - A2 * X**2 + FORCE * sp.cos(THETA))
                - EPS * (4 * DELTA + EPS * DELTA**2) * Y,
            ],
            parameters=[Z1, Z2, A1, A2, DELTA, FORCE, SIGMA],
            excitation=Excitation(phase=THETA, ratio=2, detuning=SIGMA, reference="x"),
            name="autoparametric-absorber",
        )
