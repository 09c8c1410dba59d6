"""Two weakly coupled, damped Duffing oscillators in 1:1 resonance, the first one forced.

.. math:: \\ddot x_1 + x_1 = \\varepsilon\\,[-2\\zeta\\dot x_1 - \\gamma x_1^3
          + \\kappa(x_2 - x_1) + F\\cos\\Omega t], \\qquad
          \\ddot x_2 + x_2 = \\varepsilon\\,[-2\\zeta\\dot x_2 - \\gamma x_2^3 + \\kappa(x_1 - x_2)],

:math:`\\Omega = 1 + \\varepsilon\\sigma`: a pair of MEMS resonators joined by a soft spring (the
in-phase normal mode at frequency 1, the anti-phase one at :math:`1 + \\varepsilon\\kappa`), driven
on one of them. Both modes share the forcing's frequency, so the first-order amplitude equations
are four cubics in the four amplitudes (Bezout bound 81): every real root is certified at every Ω
(``perturb response coupled-duffings --sweep Omega=...``), and besides the forced resonator's own
lower, middle and upper responses there are branches localised on the unforced one, reached only
through the spring.
"""

from __future__ import annotations

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

X1, X2, V1, V2, THETA = sp.symbols("x1 x2 x1dot x2dot theta")
ZETA, GAMMA, KAPPA, FORCE, SIGMA = sp.symbols("zeta gamma kappa F sigma")


@register
class CoupledDuffings(DrivenProblem):
    """Two coupled Duffings in 1:1, the first forced near Ω = 1 (see the module notes).

    Examples
    --------
    >>> from perturb.response import steady_state_of
    >>> from problems import get_problem
    >>> pair = get_problem("coupled-duffings").create(Omega=1.05)
    >>> points = steady_state_of(pair, 1).points
    >>> len(points), sum(p.stable is True for p in points)
    (5, 3)
    """

    name = "coupled-duffings"
    summary = (
        "two coupled damped Duffings in 1:1, x1'' + x1 = eps[-2 zeta x1' - gamma x1^3 + "
        "kappa (x2 - x1) + F cos Omega t] and the same for x2 unforced, Omega ~ 1"
    )
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms", positive),
        ParameterSpec("zeta", 0.05, "scaled damping of each resonator", non_negative),
        ParameterSpec("gamma", 1.0, "scaled cubic stiffness of each resonator"),
        ParameterSpec("kappa", 0.1, "scaled stiffness of the coupling spring"),
        ParameterSpec("F", 1.0, "scaled forcing amplitude on x1", positive),
        ParameterSpec("Omega", 1.05, "excitation frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 1)/eps"}  # Omega = 1 + eps*sigma

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X1, X2],
            velocities=[V1, V2],
            frequencies=[1, 1],
            rhs=[
                EPS * (-2 * ZETA * V1 - GAMMA * X1**3 + KAPPA * (X2 - X1) + FORCE * sp.cos(THETA)),
                EPS * (-2 * ZETA * V2 - GAMMA * X2**3 + KAPPA * (X1 - X2)),
            ],
            parameters=[ZETA, GAMMA, KAPPA, FORCE, SIGMA],
            excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
            name="coupled-duffings",
        )
