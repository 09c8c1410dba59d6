"""A chain of n Duffing resonators joined by soft springs, fixed ends, forced at one end.

.. math:: \\ddot x_i + x_i = \\varepsilon\\,[-2\\zeta\\dot x_i - \\gamma x_i^3
          + \\kappa(x_{i-1} - 2x_i + x_{i+1}) + F\\delta_{i1}\\cos\\Omega t],
          \\qquad x_0 = x_{n+1} = 0, \\qquad \\Omega = 1 + \\varepsilon\\sigma.

Every linear frequency is 1 + O(ε): all n normal modes are in 1:1 resonance with the forcing,
and the first-order amplitude equations are 2n cubics in 2n amplitudes (Bezout bound 9ⁿ). The
forcing is localised on x1; the response spreads along the chain or stays localised, and above the
linear resonances the branches multiply (the chain of 4 has 31 at σ = 2, five of them stable).
Each size is its own class: ``forced-chain-3``, ``forced-chain-4``, or any n through
:func:`forced_chain_of`.
"""

from __future__ import annotations

from typing import ClassVar

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, non_negative, positive_frequency

THETA = sp.Symbol("theta")
ZETA, GAMMA, KAPPA, FORCE, SIGMA = sp.symbols("zeta gamma kappa F sigma")


def forced_chain_system(n: int) -> QuasilinearSystem:
    """The forced chain's quasilinear system (see the module notes).

    Examples
    --------
    >>> forced_chain_system(2).rhs[1]
    epsilon*(-gamma*x2**3 + kappa*(x1 - 2*x2) - 2*x2dot*zeta)
    """
    coordinates = [sp.Symbol(f"x{i}") for i in range(1, n + 1)]
    velocities = [sp.Symbol(f"x{i}dot") for i in range(1, n + 1)]
    padded = [sp.S.Zero, *coordinates, sp.S.Zero]
    rhs = []
    for i, (x, v) in enumerate(zip(coordinates, velocities, strict=True)):
        force = -2 * ZETA * v - GAMMA * x**3 + KAPPA * (padded[i] - 2 * x + padded[i + 2])
        if i == 0:
            force += FORCE * sp.cos(THETA)
        rhs.append(EPS * force)
    return QuasilinearSystem(
        coordinates=coordinates,
        velocities=velocities,
        frequencies=[1] * n,
        rhs=rhs,
        parameters=[ZETA, GAMMA, KAPPA, FORCE, SIGMA],
        excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
        name=f"forced-chain-{n}",
    )


class ForcedChain(DrivenProblem):
    """A forced chain of ``n`` coupled Duffings (subclasses fix ``n``; see the module notes).

    Examples
    --------
    >>> from perturb.response import steady_state_of
    >>> from problems import get_problem
    >>> state = steady_state_of(get_problem("forced-chain-3").create(Omega=1.05), 1)
    >>> len(state.points), sum(point.stable is True for point in state.points)
    (5, 2)
    """

    n: ClassVar[int]
    summary = "chain of coupled damped Duffings, fixed ends, forced on x1 near Omega ~ 1"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "scale of the small terms", positive),
        ParameterSpec("zeta", 0.05, "scaled damping of each resonator", non_negative),
        ParameterSpec("gamma", 1.0, "scaled cubic stiffness of each resonator"),
        ParameterSpec("kappa", 0.5, "scaled stiffness of the springs between neighbours"),
        ParameterSpec("F", 1.0, "scaled forcing amplitude on x1", positive),
        ParameterSpec("Omega", 1.05, "excitation frequency", positive_frequency),
    )  # fmt: skip
    parameter_map = {"sigma": "(Omega - 1)/eps"}  # Omega = 1 + eps*sigma

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return forced_chain_system(cls.n)


@register
class ForcedChain3(ForcedChain):
    """The forced chain of 3 (see :class:`~problems.forced_chain.ForcedChain`).

    Examples
    --------
    >>> ForcedChain3.build_system().coordinates
    (x1, x2, x3)
    """

    name = "forced-chain-3"
    n = 3


@register
class ForcedChain4(ForcedChain):
    """The forced chain of 4 (see :class:`~problems.forced_chain.ForcedChain`).

    Examples
    --------
    >>> ForcedChain4.build_system().rhs[3]
    epsilon*(-gamma*x4**3 + kappa*(x3 - 2*x4) - 2*x4dot*zeta)
    """

    name = "forced-chain-4"
    n = 4


def forced_chain_of(n: int) -> type[ForcedChain]:
    """The problem class of a forced chain of ``n`` (not registered).

    Examples
    --------
    >>> forced_chain_of(5).build_system().coordinates[-1]
    x5
    """
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValueError(f"`n` must be an integer >= 1, got {n!r}")
    return type(f"ForcedChain{n}", (ForcedChain,), {"name": f"forced-chain-{n}", "n": n})
