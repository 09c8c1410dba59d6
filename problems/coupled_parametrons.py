"""Two linearly coupled parametrons: Duffing resonators under one parametric pump near Ω = 2.

.. math:: \\ddot x_i + x_i = \\varepsilon\\,[-2\\zeta\\dot x_i + h\\cos(\\Omega t)\\,x_i
          - \\gamma x_i^3 + \\kappa x_j], \\qquad (i, j) = (1, 2), (2, 1),
          \\qquad \\Omega = 2 + \\varepsilon\\sigma.

The response has the period of two pump periods (ratio 2). Each normal mode (in-phase at
:math:`1 - \\varepsilon\\kappa/2`, anti-phase at :math:`1 + \\varepsilon\\kappa/2`) has its own
instability tongue; where they overlap the pair has up to a dozen steady states and several
stable ones. This is HarmonicBalance.jl's example of two coupled parametrons (Košata et al.;
Ameye et al., arXiv:2501.08793), whose equation
:math:`\\ddot x_i + \\gamma_{HB}\\dot x_i + (\\omega_0^2 - \\lambda\\cos 2\\omega t)x_i + \\alpha x_i^3
- J x_j = 0` with :math:`\\omega_0 = 1` is this one with :math:`\\lambda = \\varepsilon h`,
:math:`\\gamma_{HB} = 2\\varepsilon\\zeta`, :math:`\\alpha = \\varepsilon\\gamma`,
:math:`J = \\varepsilon\\kappa` and :math:`\\omega = \\Omega/2`; the defaults are its parameters
(J = γ_HB = 0.005, α = 1, λ = 0.02) at ε = 0.01.
"""

from __future__ import annotations

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

X1, X2, V1, V2, THETA = sp.symbols("x1 x2 x1dot x2dot theta")
ZETA, H, GAMMA, KAPPA, SIGMA = sp.symbols("zeta h gamma kappa sigma")


@register
class CoupledParametrons(DrivenProblem):
    """Two coupled parametrons pumped near Ω = 2 (see the module notes).

    Examples
    --------
    >>> from perturb.response import steady_state_of
    >>> from problems import get_problem
    >>> state = steady_state_of(get_problem("coupled-parametrons").create(Omega=2.0), 1)
    >>> [(name, point.stable) for name, point in zip(state.names, state.points)]
    [('trivial', False), ('anti-phase', False), ('in-phase', True)]
    """

    name = "coupled-parametrons"
    summary = (
        "two coupled parametrons x_i'' + x_i = eps[-2 zeta x_i' + h cos(Omega t) x_i - gamma x_i^3 "
        "+ kappa x_j], pumped near Omega ~ 2 (HarmonicBalance.jl's example)"
    )
    parameter_specs = (
        ParameterSpec("eps", 0.01, "scale of the small terms", positive),
        ParameterSpec("zeta", 0.25, "scaled damping of each resonator", non_negative),
        ParameterSpec("h", 2.0, "scaled depth of the stiffness modulation (the pump)", positive),
        ParameterSpec("gamma", 100.0, "scaled cubic stiffness of each resonator"),
        ParameterSpec("kappa", 0.5, "scaled linear coupling"),
        ParameterSpec("Omega", 2.0, "pump frequency (the response has half of it)",
                      positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 2)/eps"}  # Omega = 2 + eps*sigma

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        pump = H * sp.cos(THETA)
        return QuasilinearSystem(
            coordinates=[X1, X2],
            velocities=[V1, V2],
            frequencies=[1, 1],
            rhs=[
                EPS * (-2 * ZETA * V1 + pump * X1 - GAMMA * X1**3 + KAPPA * X2),
                EPS * (-2 * ZETA * V2 + pump * X2 - GAMMA * X2**3 + KAPPA * X1),
            ],
            parameters=[ZETA, H, GAMMA, KAPPA, SIGMA],
            excitation=Excitation(phase=THETA, ratio=2, detuning=SIGMA),
            name="coupled-parametrons",
        )
