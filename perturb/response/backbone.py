"""The backbone of a response: the free, undamped system's frequency against its amplitude, in the
amplitude measure the response is drawn by (max |x|, first harmonic or initial-value norm)."""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from perturb.response.measures import peak_abs

__all__ = ["BACKBONE_SAMPLES", "backbone_of"]

#: Amplitudes of the backbone, as fractions of the largest response amplitude found (the
#: backbone is drawn through the region the response occupies).
BACKBONE_SAMPLES = 41


def backbone_of(problem, parameter: str, points, order: int, measure: str = "initial"):
    """The free engine's frequency of the problem's unforced, undamped system, if it has one
    (``problem.backbone_system(parameter)``), as a :class:`~perturb.response.model.Backbone`
    whose amplitudes are ``measure``'s."""
    import attrs

    from perturb.response.model import Backbone

    make = getattr(problem, "backbone_system", None)
    built = make(parameter) if make is not None and points else None
    if built is None:
        return None
    free_system, coordinate, to_parameter = built
    from perturb.method.poincare import PoincareMethod

    amplitude = sp.Symbol("backbone_amplitude", positive=True)
    free_system = attrs.evolve(free_system, parameters=(*free_system.parameters, amplitude))
    method = PoincareMethod(order=max(order, 1), amplitudes={coordinate: amplitude})
    solution = method.solve(free_system)
    if not solution.success:
        return None
    top = max(p.amplitude(coordinate, measure) for p in points)
    values = dict(problem.symbol_values())
    eps = problem.epsilon()
    generating = np.linspace(0.0, 1.05 * top, BACKBONE_SAMPLES)
    index = [c.name for c in free_system.coordinates].index(coordinate)
    measured, frequencies = [], []
    for a in generating:
        omega, cos, sin = solution.coefficients(eps, {**values, amplitude.name: float(a)})
        c, s = np.asarray(cos[index], float), np.asarray(sin[index], float)
        frequencies.append(float(omega))
        if measure == "peak":
            measured.append(float(peak_abs(c, s)))
        elif measure == "first-harmonic":
            measured.append(float(math.hypot(c[1], s[1])) if len(c) > 1 else 0.0)
        else:
            j = np.arange(len(c))
            x0, v0 = float(c.sum()), float(omega) * float((s * j).sum())
            measured.append(math.hypot(x0, v0 / float(omega)) if omega else abs(x0))
    return Backbone(coordinate, tuple(measured), tuple(to_parameter(w) for w in frequencies))
