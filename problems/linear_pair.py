"""A linear coupled pair with exactly known frequencies (non-resonant).

    ẍ + x = ε κ y,    ÿ + ω² y = ε κ x

The normal-mode frequencies λ solve (1 − λ²)(ω² − λ²) = ε²κ²; the mode that continues x = A cos t has
λ² = [1 + ω² − √((ω² − 1)² + 4ε²κ²)]/2 (for ω > 1) and y/x = εκ/(ω² − λ²).
"""

from __future__ import annotations

import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems import register
from problems.base import ParameterSpec, Problem, positive

X, Y, XDOT, YDOT = sp.symbols("x y xdot ydot")
KAPPA, OMEGA, AMPLITUDE = sp.symbols("kappa omega amplitude", positive=True)


def _not_resonant(value: float) -> str | None:
    if value <= 0:
        return "give a frequency > 0"
    if abs(value - round(value)) < 1e-9:
        return "give a non-integer frequency ratio (an integer makes the pair resonant; see resonant-pair)"
    return None


@register
class LinearPair(Problem):
    """Two linearly coupled oscillators, x continuing the unit-frequency mode.

    Examples
    --------
    The exact frequencies solve (1 − Ω²)(ω² − Ω²) = ε²κ², so Ω = 1 − ε²κ²/(2(ω² − 1)) + O(ε⁴)
    — the engine's second order:

    >>> from problems import get_problem
    >>> get_problem("linear-pair").create().solve(2).frequency_series()
    -epsilon**2*kappa**2/(2*omega**2 - 2) + 1
    """

    name = "linear-pair"
    summary = (
        "linear pair xddot + x = eps kappa y, yddot + omega^2 y = eps kappa x (exact frequencies)"
    )
    parameter_specs = (
        ParameterSpec("eps", 0.1, "coupling scale (small parameter)"),
        ParameterSpec("kappa", 1.0, "coupling constant"),
        ParameterSpec("omega", 2.5, "frequency of y (not an integer)", _not_resonant),
        ParameterSpec("amplitude", 1.0, "x(0)", positive),
    )

    @classmethod
    def build_system(cls) -> QuasilinearSystem:
        return QuasilinearSystem(
            coordinates=[X, Y],
            velocities=[XDOT, YDOT],
            frequencies=[1, OMEGA],
            rhs=[EPS * KAPPA * Y, EPS * KAPPA * X],
            parameter=EPS,
            parameters=[KAPPA, OMEGA, AMPLITUDE],
            name="linear-pair",
        )

    def method_options(self) -> dict:
        return {"amplitudes": {"x": AMPLITUDE}}

    def exact_frequency(self) -> float:
        """λ of the mode through x(0) = A, from the characteristic equation."""
        e, k, w = self.values["eps"], self.values["kappa"], self.values["omega"]
        disc = ((w**2 - 1) ** 2 + 4 * (e * k) ** 2) ** 0.5
        lam2 = (1 + w**2 - disc) / 2 if w > 1 else (1 + w**2 + disc) / 2
        return lam2**0.5
