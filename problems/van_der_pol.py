"""Van der Pol's oscillator  ẍ + x = ε (1 − x²) ẋ: an isolated limit cycle."""

from __future__ import annotations

import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, Problem

X, XDOT = sp.symbols("x xdot")


@register
class VanDerPol(Problem):
    """ẍ + x = ε (1 − x²) ẋ; the amplitude of the limit cycle comes from the periodicity conditions.

    Examples
    --------
    >>> from problems import get_problem
    >>> vdp = get_problem("van-der-pol").create(eps=0.1)
    >>> solution = vdp.solve(2)
    >>> solution.frequency_series()  # the classical 1 - eps^2/16
    1 - epsilon**2/16
    >>> round(float(vdp.state(solution, [0.0])["x"][0]), 6)  # the limit cycle's amplitude, near 2
    2.000104
    """

    name = "van-der-pol"
    summary = "van der Pol oscillator xddot + x = eps (1 - x^2) xdot (isolated limit cycle)"
    parameter_specs = (ParameterSpec("eps", 0.1, "damping parameter (small parameter)"),)

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X],
            velocities=[XDOT],
            frequencies=[1],
            rhs=[EPS * (1 - X**2) * XDOT],
            parameter=EPS,
            name="van-der-pol",
        )
