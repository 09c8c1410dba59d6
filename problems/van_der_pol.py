"""Van der Pol's oscillator  ẍ + x = ε (1 − x²) ẋ: an isolated limit cycle."""

from __future__ import annotations

import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, Problem

X, XDOT = sp.symbols("x xdot")


@register
class VanDerPol(Problem):
    """ẍ + x = ε (1 − x²) ẋ; the amplitude of the limit cycle comes from the periodicity conditions."""

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
