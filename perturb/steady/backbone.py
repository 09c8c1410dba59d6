"""The backbone of a driven system: the free, conservative motion's frequency against amplitude.

Near a resonance the forced response peaks where the excitation meets the free motion of the
same amplitude. The free motion is the system with the excitation taken away and only its
time-reversible part kept: every term with the phase θ = Ωt goes (the forcing, a parametric
pump), and so does every term odd in the velocities (damping, self-excitation). No problem has
to say which of its parameters force or damp: the backbone follows from the equations, and from
the :class:`~perturb.case.ParameterMap` that carries it into the swept parameter
(:math:`\\Omega = (p/q)\\,\\omega(a)`, σ = (p/q)(ω(a) − ω_ref)/ε, then σ back to the user's
parameter exactly).
"""

from __future__ import annotations

import math

import attrs
import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import BACKBONE_REACH, BACKBONE_SAMPLES
from perturb.errors import PerturbError
from perturb.system import QuasilinearSystem

__all__ = ["Backbone", "backbone", "free_system"]


@frozen
class Backbone:
    """The free, undamped system's frequency against its amplitude (the response's spine).

    Attributes
    ----------
    coordinate : str
    amplitudes : tuple of float
    values : tuple of float
        The swept parameter's value at which the forced system resonates with the free motion of
        that amplitude.
    """

    coordinate: str
    amplitudes: tuple = field(converter=tuple)
    values: tuple = field(converter=tuple)


def _time_reversible(expr: sp.Expr, velocities) -> sp.Expr:
    """The part of ``expr`` even in the velocities (unchanged when every velocity changes sign)."""
    flipped = expr.xreplace({v: -v for v in velocities})
    return sp.expand((expr + flipped) / 2)


def free_system(system: QuasilinearSystem) -> QuasilinearSystem | None:
    """The conservative, unforced system of a driven ``system`` (None if nothing is left to
    vibrate nonlinearly, or the system is not driven).

    Examples
    --------
    >>> import sympy as sp
    >>> from perturb import EPS, Excitation, QuasilinearSystem
    >>> from perturb.steady.backbone import free_system
    >>> x, xdot, th, z, g, F, s = sp.symbols("x xdot theta zeta gamma F sigma")
    >>> forced = QuasilinearSystem([x], [xdot], [1],
    ...     [EPS * (-2 * z * xdot - g * x**3 + F * sp.cos(th))], parameters=[z, g, F, s],
    ...     excitation=Excitation(phase=th, ratio=1, detuning=s))
    >>> free = free_system(forced)
    >>> free.rhs, free.parameters
    ((-epsilon*gamma*x**3,), (gamma,))
    """
    if not system.frame.frequency_given:
        return None
    phase = system.excitation.phase
    rhs = []
    for f in system.rhs:
        terms = sp.Add.make_args(sp.expand(f))
        unforced = sp.Add(*(t for t in terms if phase not in t.free_symbols))
        rhs.append(_time_reversible(unforced, system.velocities))
    used = set().union(*(f.free_symbols for f in rhs))
    parameters = tuple(p for p in system.parameters if p in used)
    if all(f == 0 for f in rhs):
        return None
    return attrs.evolve(system, rhs=tuple(rhs), parameters=parameters, excitation=None)


def backbone(
    case, parameter: str, top: float, order: int, measure: str = "initial"
) -> Backbone | None:
    """The backbone of ``case``'s system in the user ``parameter``, up to amplitude ``top``.

    ``measure`` is the amplitude's (``initial``: the free series' amplitude parameter, as drawn
    before issue 29; ``peak``: max ``|x|`` over a period of the free series; ``first-harmonic``: its
    first harmonic), so that the backbone lies in the response's own axis.

    None when ``parameter`` does not move the detuning, the free system is linear, or its free
    frequency cannot be derived (several modes in internal resonance).
    """
    from perturb.method.poincare import PoincareMethod

    system = case.system
    free = free_system(system)
    detuning = system.excitation.detuning if free is not None else None
    if detuning is None or not detuning.is_Symbol or detuning.name not in case.moves(parameter):
        return None
    coordinate = system.coordinates[system.reference_index].name
    amplitude = sp.Symbol("backbone_amplitude", positive=True)
    free = attrs.evolve(free, parameters=(*free.parameters, amplitude))
    try:
        solution = PoincareMethod(order=max(order, 1), amplitudes={coordinate: amplitude}).solve(
            free
        )
    except ValueError:
        return None
    if not solution.success or not (math.isfinite(top) and top > 0):
        return None
    values = case.symbol_values
    eps = case.epsilon
    ratio = float(system.excitation.ratio)
    amplitudes = np.linspace(0.0, BACKBONE_REACH * top, BACKBONE_SAMPLES)
    out = []
    for a in amplitudes:
        try:
            period = float(solution.period_at(eps, {**values, amplitude.name: float(a)}))
        except PerturbError:  # a divisor of the free series vanishes: no backbone to draw
            return None
        omega = ratio * (2 * math.pi / period)  # the drive meets the free motion
        sigma = system.frame.detuning_value(system, omega, values, eps)
        out.append(case.to_user(parameter, detuning.name, sigma))
    if measure != "initial":
        amplitudes = _measured(solution, coordinate, eps, values, amplitude, amplitudes, measure)
    return Backbone(coordinate, tuple(amplitudes), tuple(out))


def _measured(solution, coordinate, eps, values, amplitude, amplitudes, measure) -> np.ndarray:
    """The free series' ``measure`` at each of its amplitude parameters (max ``|x|`` over a period,
    or its first harmonic), all in one vectorised evaluation."""
    from perturb.steady.measures import peak_abs

    index = [c.name for c in solution.system.coordinates].index(coordinate)
    _, cos, sin = solution.coefficients(eps, {**values, amplitude.name: amplitudes})
    c = np.moveaxis(np.asarray(cos[index], dtype=float), 0, -1)
    s = np.moveaxis(np.asarray(sin[index], dtype=float), 0, -1)
    if measure == "peak":
        return peak_abs(c, s)
    return np.hypot(c[:, 1], s[:, 1]) if c.shape[1] > 1 else np.zeros(len(amplitudes))
