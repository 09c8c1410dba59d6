"""Duffing's oscillator  ẍ + x + ε x³ = 0  started at rest from x(0) = amplitude."""

from __future__ import annotations

import sympy as sp

from perturb import EPS, QuasilinearSystem
from perturb.errors import InvalidParameterError
from problems import register
from problems.base import ParameterSpec, Problem, positive

X, XDOT, AMPLITUDE = sp.symbols("x xdot amplitude")


@register
class Duffing(Problem):
    """ẍ + x + ε x³ = 0 with x(0) = ``amplitude``, ẋ(0) = 0 (a conservative family).

    Examples
    --------
    >>> from problems import get_problem
    >>> duffing = get_problem("duffing").create(eps=0.1, amplitude=1.0)
    >>> solution = duffing.solve(2)
    >>> solution.frequency_series()
    -21*amplitude**4*epsilon**2/256 + 3*amplitude**2*epsilon/8 + 1
    >>> round(duffing.period(solution), 6)
    6.060874
    """

    name = "duffing"
    summary = "Duffing oscillator xddot + x + eps x^3 = 0, x(0) = amplitude (conservative family)"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "strength of the cubic term (small parameter)"),
        ParameterSpec("amplitude", 1.0, "initial displacement x(0), velocity zero", positive),
    )

    def check_values(self, values) -> None:
        """A softening spring (eps < 0) has a periodic motion from x(0) = amplitude at rest only
        inside its separatrix: the potential x²/2 + eps x⁴/4 peaks at x² = -1/eps, so
        eps amplitude² must stay above -1 (at -1 the motion takes for ever to reach the peak;
        below, it escapes)."""
        super().check_values(values)
        stiffness = values["eps"] * values["amplitude"] ** 2
        if stiffness <= -1:
            raise InvalidParameterError(
                f"`eps` = {values['eps']:g} with `amplitude` = {values['amplitude']:g} has no "
                f"periodic motion: eps*amplitude^2 = {stiffness:g} puts x(0) on or past the "
                "separatrix of the softening spring (x^2 = -1/eps); give eps*amplitude^2 > -1"
            )

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X],
            velocities=[XDOT],
            frequencies=[1],
            rhs=[-EPS * X**3],
            parameter=EPS,
            parameters=[AMPLITUDE],
            name="duffing",
        )

    def method_options(self) -> dict:
        return {"amplitudes": {"x": AMPLITUDE}}
