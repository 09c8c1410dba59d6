"""The system's parameter values along one swept parameter: the line a response is continued on.

A problem's user parameter λ (Ω, a forcing level…) moves the values its system is written in (σ,
F, …) and possibly ε through the problem's own map (its :class:`~perturb.case.Case`: the point at
each λ, the exact rate of every symbol and of ε, whether they move affinely). When the map is
affine along the sweep — Ω ↦ σ = (Ω − 1)/ε, or a coefficient swept directly — the amplitude
equations restricted to the line are polynomials in (amplitudes, λ), specialised once; otherwise
the values are asked of the case at each λ and differentiated by centred differences. The continuation
runs in the scaled variable μ = (λ − λ₀)·scale, scale the largest rate at which a system value
moves (μ in the units of σ when sweeping Ω): amplitudes and parameter then weigh alike in the
arclength.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from attrs import field, frozen

from perturb._defaults import MAP_STEP
from perturb.errors import InvalidParameterError

__all__ = ["ParameterLine", "excitation_frequency", "line_of_problem", "line_of_values"]


@frozen
class ParameterLine:
    """System parameter values and ε along λ (see the module notes).

    Attributes
    ----------
    parameter : str
        The swept parameter's name.
    names : tuple of str
        The system's parameters, in its order.
    origin : float
        λ₀, where μ = 0.
    base, slope : ndarray
        Values at λ₀ and their rate dv/dλ (affine maps; a tangent at λ₀ otherwise).
    eps, eps_slope : float
    scale : float
        μ per unit of λ.
    affine : bool
    values_at : callable
        ``λ -> (values, eps)`` from the problem (None for a line given by values).
    invalid : callable
        ``λ -> str``: "" where the problem accepts λ, else its one-line reason.
    reach : float
        The size of λ on the line (the larger end's magnitude): the centred differences of a
        map that is not affine step by :data:`~perturb._defaults.MAP_STEP` times it (at most
        times 1) or times λ.
    """

    parameter: str
    names: tuple = field(converter=tuple)
    origin: float
    base: np.ndarray = field(eq=False)
    slope: np.ndarray = field(eq=False)
    eps: float
    eps_slope: float
    scale: float
    affine: bool
    values_at: Callable | None = field(eq=False, default=None)
    invalid: Callable = field(eq=False, default=lambda lam: "")
    reach: float = 1.0

    def mu(self, lam):
        return (np.asarray(lam, dtype=float) - self.origin) * self.scale

    def lam(self, mu):
        return self.origin + np.asarray(mu, dtype=float) / self.scale

    def at(self, lam: float) -> tuple[np.ndarray, float]:
        """``(values, eps)`` at λ."""
        if self.affine:
            d = float(lam) - self.origin
            return self.base + d * self.slope, self.eps + d * self.eps_slope
        return self.values_at(float(lam))

    def rate(self, lam: float) -> tuple[np.ndarray, float]:
        """``(dvalues/dλ, deps/dλ)`` at λ."""
        if self.affine:
            return self.slope, self.eps_slope
        # relative to the size of λ on the line (a sweep of eps over 1e-6..2e-6 must not step
        # to a negative eps), and one-sided where a side is outside the problem's values
        h = MAP_STEP * max(min(1.0, self.reach), abs(float(lam)))
        try:
            low, below = self.values_at(lam - h), lam - h
        except InvalidParameterError:
            low, below = self.values_at(lam), float(lam)
        try:
            high, above = self.values_at(lam + h), lam + h
        except InvalidParameterError:
            high, above = self.values_at(lam), float(lam)
        (v1, e1), (v0, e0) = high, low
        return (v1 - v0) / (above - below), (e1 - e0) / (above - below)


def _scale(slope: np.ndarray, eps_slope: float) -> float:
    top = max(float(np.max(np.abs(slope), initial=0.0)), abs(eps_slope))
    return top if top > 0 and math.isfinite(top) else 1.0


def line_of_problem(problem, parameter: str, names, low: float, high: float) -> ParameterLine:
    """The line of ``problem``'s system values along its parameter ``parameter`` over [low, high]:
    its :class:`~perturb.case.Case` gives each point, the exact rate of the symbols and ε and
    whether they move affinely (read from the parameter map, not probed)."""
    names = tuple(names)
    case = problem.case()

    def values_at(lam: float):
        point = case.at(**{parameter: float(lam)})
        values = point.symbol_values
        return np.array([float(values[n]) for n in names]), float(point.epsilon)

    def invalid(lam: float) -> str:
        try:
            case.at(**{parameter: float(lam)})
        except (InvalidParameterError, ValueError) as error:
            return str(error)
        return ""

    v0, e0 = values_at(low)
    start = case.at(**{parameter: float(low)})
    rates, eps_rate = start.rate(parameter)
    slope = np.array([float(rates.get(n, 0.0)) for n in names])
    affine = bool(case.is_affine_in(parameter))
    reach = max(abs(float(low)), abs(float(high))) or 1.0
    return ParameterLine(
        parameter, names, low, v0, slope, e0, float(eps_rate), _scale(slope, float(eps_rate)),
        affine, values_at, invalid, reach,
    )  # fmt: skip


def line_of_values(names, values: dict, eps: float, parameter: str) -> ParameterLine:
    """The line through the system values ``values`` along the system parameter ``parameter``
    (σ for one point's branches), ε fixed."""
    names = tuple(names)
    base = np.array([float(values[n]) for n in names])
    slope = np.array([1.0 if n == parameter else 0.0 for n in names])
    return ParameterLine(
        parameter, names, float(values[parameter]), base, slope, float(eps), 0.0, 1.0, True
    )


def excitation_frequency(system, values: dict, eps: float) -> float:
    """Ω of the driven ``system`` at ``values`` (by name) and ε: the frame's relation
    (:meth:`perturb.frame.DrivenFrame.frequency_value`; raises InvalidParameterError, one line,
    when Ω <= 0)."""
    return system.frame.frequency_value(system, values, eps)
