"""A chain of n identical oscillators with cubic nearest-neighbour springs, fixed ends (FPU-β type).

    ẍᵢ + xᵢ = −ε [(xᵢ − xᵢ₋₁)³ + (xᵢ − xᵢ₊₁)³],    i = 1 … n,    x₀ = xₙ₊₁ = 0

Every frequency is 1: all n coordinates are in 1:1 resonance, and the periodicity conditions of
order 1 are n polynomial equations of degree 3 in the amplitudes (x₁'s amplitude fixed). Their
real roots are the nonlinear normal modes of the chain — in-phase, anti-phase, localised — and
their number grows fast with n, which makes the chain the test bed of the amplitude-equation solver
(:mod:`perturb.roots`).

A problem's system is derived once per class, so each size is its own class: ``resonant-chain-2``,
``-3``, ``-4``, ``-6``, or any n through :func:`chain_of`.
"""

from __future__ import annotations

from typing import ClassVar

import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, Problem, positive


def chain_symbols(n: int) -> tuple[list[sp.Symbol], list[sp.Symbol]]:
    """The coordinates ``x1 … xn`` and velocities ``x1dot … xndot`` of a chain of ``n``."""
    return (
        [sp.Symbol(f"x{i}") for i in range(1, n + 1)],
        [sp.Symbol(f"x{i}dot") for i in range(1, n + 1)],
    )


def chain_system(n: int) -> QuasilinearSystem:
    """The chain's quasilinear system, derived from its potential energy.

    ``V = Σ (xᵢ − xᵢ₋₁)⁴ / 4`` over the n + 1 springs (ends fixed), and ``ẍᵢ + xᵢ = −ε ∂V/∂xᵢ``.

    Examples
    --------
    >>> chain_system(2).rhs[0]
    -epsilon*(x1**3 + (x1 - x2)**3)
    """
    coordinates, velocities = chain_symbols(n)
    padded = [sp.S.Zero, *coordinates, sp.S.Zero]
    potential = sum((padded[i + 1] - padded[i]) ** 4 / 4 for i in range(n + 1))
    rhs = [-EPS * sp.factor_terms(sp.diff(potential, x)) for x in coordinates]
    energy = sum((v**2 + x**2) / 2 for x, v in zip(coordinates, velocities, strict=True))
    return QuasilinearSystem(
        coordinates=coordinates,
        velocities=velocities,
        frequencies=[1] * n,
        rhs=rhs,
        parameter=EPS,
        name=f"resonant-chain-{n}",
        first_integrals=[energy + EPS * potential],
    )


class ResonantChain(Problem):
    """A resonant chain of ``n`` cubic-coupled oscillators (subclasses fix ``n``); x1(0) = amplitude.

    Examples
    --------
    >>> from problems import get_problem
    >>> chain = get_problem("resonant-chain-2").create(eps=0.05)
    >>> sorted(family.name for family in chain.families(1))[:2]
    ['anti-phase', 'in-phase']
    """

    n: ClassVar[int]
    summary = "resonant chain of cubic springs, fixed ends (FPU-beta type)"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "strength of the cubic springs (small parameter)"),
        ParameterSpec("amplitude", 1.0, "x1(0), every velocity zero", positive),
    )

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return chain_system(cls.n)

    def method_options(self) -> dict:
        # A number, put in exactly: the amplitude equations then have numeric coefficients and
        # every branch is found by the certified real-root solver (perturb.algebra).
        return {"amplitudes": {"x1": sp.nsimplify(self.values["amplitude"], rational=True)}}


@register
class ResonantChain2(ResonantChain):
    """The resonant chain of 2 (see :class:`~problems.resonant_chain.ResonantChain`).

    Examples
    --------
    >>> sorted(f.name for f in ResonantChain2.create(eps=0.05).families(1))
    ['anti-phase', 'in-phase']
    """

    name = "resonant-chain-2"
    n = 2


@register
class ResonantChain3(ResonantChain):
    """The resonant chain of 3 (see :class:`~problems.resonant_chain.ResonantChain`).

    Examples
    --------
    >>> sorted(f.name for f in ResonantChain3.create(eps=0.01).families(1))
    ['anti-phase-1', 'anti-phase-2', 'anti-phase-3', 'in-phase', 'shape-p0n']
    """

    name = "resonant-chain-3"
    n = 3


@register
class ResonantChain4(ResonantChain):
    """The resonant chain of 4 (see :class:`~problems.resonant_chain.ResonantChain`).

    Examples
    --------
    >>> ResonantChain4.build_system().rhs[1]  # x2, between two springs
    -epsilon*((-x1 + x2)**3 - (-x2 + x3)**3)
    """

    name = "resonant-chain-4"
    n = 4


@register
class ResonantChain6(ResonantChain):
    """The resonant chain of 6 (see :class:`~problems.resonant_chain.ResonantChain`).

    Examples
    --------
    >>> ResonantChain6.build_system().coordinates[-1]
    x6
    """

    name = "resonant-chain-6"
    n = 6


def chain_of(n: int) -> type[ResonantChain]:
    """The problem class of a chain of ``n`` (not registered; ``perturb`` takes it by object).

    Examples
    --------
    >>> chain_of(5).build_system().coordinates[-1]
    x5
    """
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValueError(f"`n` must be an integer >= 1, got {n!r}")
    return type(f"ResonantChain{n}", (ResonantChain,), {"name": f"resonant-chain-{n}", "n": n})
