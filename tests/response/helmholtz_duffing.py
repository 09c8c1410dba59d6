"""A forced Helmholtz-Duffing oscillator typed by a user (quadratic and cubic stiffness):
x'' + 2 eps zeta x' + x + eps alpha x^2 + eps gamma x^3 = eps F cos(Omega t)."""

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, positive_frequency

X, V, TH = sp.symbols("x xdot theta")
ZETA, ALPHA, GAMMA, F, SIGMA = sp.symbols("zeta alpha gamma F sigma")


class HelmholtzDuffing(DrivenProblem):
    name = "helmholtz-duffing"
    summary = "forced Helmholtz-Duffing"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "small parameter", positive),
        ParameterSpec("zeta", 0.1, "damping"),
        ParameterSpec("alpha", 2.0, "quadratic stiffness"),
        ParameterSpec("gamma", 1.0, "cubic stiffness"),
        ParameterSpec("F", 0.5, "forcing"),
        ParameterSpec("Omega", 1.0, "excitation frequency", positive_frequency),
    )
    parameter_map = {"sigma": "(Omega - 1)/eps"}  # Omega = 1 + eps*sigma

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X],
            [V],
            [1],
            [EPS * (-2 * ZETA * V - ALPHA * X**2 - GAMMA * X**3 + F * sp.cos(TH))],
            parameters=[ZETA, ALPHA, GAMMA, F, SIGMA],
            excitation=Excitation(TH, ratio=1, detuning=SIGMA),
        )
