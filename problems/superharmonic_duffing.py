"""The Duffing oscillator's superharmonic resonance Ω ≈ 1/3 under a hard excitation.

.. math:: \\ddot x + 2\\zeta\\varepsilon\\dot x + x + \\gamma\\varepsilon x^3 = F\\cos\\Omega t,
          \\qquad \\Omega = \\tfrac13 + \\varepsilon\\sigma

The forcing is not small: its non-resonant response :math:`\\Lambda\\cos\\Omega t`,
:math:`\\Lambda = F/(1 - \\Omega^2)`, is split off exactly, :math:`x = u + \\Lambda\\cos\\Omega t`, and
the remainder is quasilinear (derived here, Λ and Ω analytic in ε):

.. math:: \\ddot u + u = \\varepsilon\\,[-2\\zeta\\dot u + 2\\zeta\\Omega\\Lambda\\sin\\Omega t
          - \\gamma(u + \\Lambda\\cos\\Omega t)^3].

Its cube holds :math:`\\Lambda^3\\cos^3\\Omega t \\ni \\Lambda^3\\cos 3\\Omega t/4`, which drives u at
its own frequency 3Ω ≈ 1: the superharmonic response (the state is u; x = u + Λ cos Ωt).
"""

from __future__ import annotations

import math

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from perturb.errors import InvalidParameterError
from problems import register
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

U, UDOT, THETA = sp.symbols("u udot theta")
ZETA, GAMMA, FORCE, SIGMA = sp.symbols("zeta gamma F sigma")
#: The excitation frequency and the amplitude of the forced (non-resonant) part, exact in ε.
OMEGA = sp.Rational(1, 3) + EPS * SIGMA
LAMBDA = FORCE / (1 - OMEGA**2)


@register
class SuperharmonicDuffing(DrivenProblem):
    """ẍ + 2ζεẋ + x + γεx³ = F cos Ωt near Ω = 1/3 (state u = x − Λ cos Ωt).

    Examples
    --------
    >>> from problems import get_problem
    >>> duffing = get_problem("superharmonic-duffing").create()
    >>> solution = duffing.solve(1)
    >>> solution.generating.harmonics  # u responds at 3 Omega: harmonic 3 of Omega t
    (3,)
    """

    name = "superharmonic-duffing"
    summary = (
        "Duffing under a hard excitation F cos(Omega t) near the superharmonic resonance "
        "Omega ~ 1/3 (the response at 3 Omega); state u = x - F cos(Omega t)/(1 - Omega^2)"
    )
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms (damping, cubic stiffness)", positive),
        ParameterSpec("zeta", 0.05, "scaled damping (the damping ratio is eps*zeta)", non_negative),
        ParameterSpec("gamma", 1.0, "scaled cubic stiffness"),
        ParameterSpec("F", 1.0, "forcing amplitude (not small: a hard excitation)", positive),
        ParameterSpec("Omega", 1.0 / 3.0, "excitation frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 1/3)/eps"}  # Omega = 1/3 + eps*sigma

    def check_values(self, values) -> None:
        super().check_values(values)
        # the forced part's amplitude F/(1 - Omega^2), as the system computes it from sigma
        sigma = (values["Omega"] - 1.0 / 3.0) / values["eps"]  # as parameter_map has it
        omega = 1.0 / 3.0 + values["eps"] * sigma
        if not math.isfinite(sigma) or 1.0 - omega * omega == 0.0:
            raise InvalidParameterError(
                f"`Omega` = {values['Omega']:g} is invalid: it is the primary resonance, where the "
                "forced response F/(1 - Omega^2) is infinite; this model is for Omega near 1/3 "
                "(forced-duffing is the primary resonance)"
            )

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        theta = THETA
        rhs = EPS * (
            -2 * ZETA * UDOT
            + 2 * ZETA * OMEGA * LAMBDA * sp.sin(theta)
            - GAMMA * (U + LAMBDA * sp.cos(theta)) ** 3
        )
        return QuasilinearSystem(
            coordinates=[U],
            velocities=[UDOT],
            frequencies=[1],
            rhs=[rhs],
            parameters=[ZETA, GAMMA, FORCE, SIGMA],
            excitation=Excitation(phase=theta, ratio=sp.Rational(1, 3), detuning=SIGMA),
            name="superharmonic-duffing",
        )
