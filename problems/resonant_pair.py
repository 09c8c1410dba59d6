"""Two identical Duffing oscillators with linear coupling: a 1:1 resonant, conservative pair.

    ẍ + x = ε[−x³ + κ (y − x)],    ÿ + y = ε[−y³ + κ (x − y)]

With x(0) = A the amplitude equations have the in-phase (y = x) and anti-phase (y = −x) normal modes
among their roots; ``mode`` = +1 or −1 selects one.
"""

from __future__ import annotations

import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, Problem, positive

X, Y, XDOT, YDOT = sp.symbols("x y xdot ydot")
KAPPA, AMPLITUDE = sp.symbols("kappa amplitude", positive=True)


def _mode(value: float) -> str | None:
    return None if value in (1.0, -1.0) else "give +1 (in-phase mode) or -1 (anti-phase mode)"


@register
class ResonantPair(Problem):
    """Coupled Duffing pair in 1:1 resonance; its normal modes by the resonant Poincaré conditions.

    Examples
    --------
    >>> from problems import get_problem
    >>> pair = get_problem("resonant-pair").create(eps=0.1, kappa=0.5)
    >>> [family.name for family in pair.families(1)][:2]
    ['anti-phase', 'in-phase']
    >>> pair.solve(1, family="in-phase").frequency_series()  # as one Duffing oscillator
    -21*amplitude**4*epsilon**2/256 + 3*amplitude**2*epsilon/8 + 1
    """

    name = "resonant-pair"
    summary = "coupled Duffing pair, 1:1 resonance; mode=+1 in-phase, -1 anti-phase"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "nonlinearity and coupling scale (small parameter)"),
        ParameterSpec("kappa", 0.5, "coupling constant", positive),
        ParameterSpec("amplitude", 1.0, "x(0)", positive),
        ParameterSpec("mode", 1.0, "+1 in-phase, -1 anti-phase", _mode),
    )

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X, Y],
            velocities=[XDOT, YDOT],
            frequencies=[1, 1],
            rhs=[EPS * (-(X**3) + KAPPA * (Y - X)), EPS * (-(Y**3) + KAPPA * (X - Y))],
            parameter=EPS,
            parameters=[KAPPA, AMPLITUDE],
            name="resonant-pair",
            first_integrals=[
                (XDOT**2 + YDOT**2 + X**2 + Y**2) / 2
                + EPS * ((X**4 + Y**4) / 4 + KAPPA * (X - Y) ** 2 / 2)
            ],
        )

    def method_options(self) -> dict:
        sign = int(self.values["mode"])
        return {"amplitudes": {"x": AMPLITUDE}, "branch": {"a_y0": sign * AMPLITUDE}}
