"""A forced van der Pol-Duffing oscillator typed by a user: x'' - eps mu (1 - x^2) x' + x + eps gamma x^3 = eps F cos(Omega t)."""

import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, positive
from problems.driven import DrivenProblem, positive_frequency

X, V, TH = sp.symbols("x xdot theta")
MU, GAMMA, F, SIGMA = sp.symbols("mu gamma F sigma")


class VdPDuffing(DrivenProblem):
    name = "vdp-duffing"
    summary = "forced van der Pol-Duffing"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "small parameter", positive),
        ParameterSpec("mu", 1.0, "negative damping"),
        ParameterSpec("gamma", 0.5, "cubic stiffness"),
        ParameterSpec("F", 1.0, "forcing"),
        ParameterSpec("Omega", 1.0, "excitation frequency", positive_frequency),
    )
    parameter_map = {"sigma": "(Omega - 1)/eps"}  # Omega = 1 + eps*sigma

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X],
            [V],
            [1],
            [EPS * (MU * (1 - X**2) * V - GAMMA * X**3 + F * sp.cos(TH))],
            parameters=[MU, GAMMA, F, SIGMA],
            excitation=Excitation(TH, ratio=1, detuning=SIGMA),
        )
