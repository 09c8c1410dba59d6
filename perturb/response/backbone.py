"""The backbone of a response: the free, undamped system's frequency against its amplitude, in the
amplitude measure the response is drawn by (max |x|, first harmonic or initial-value norm)."""

from __future__ import annotations

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
    omega, cos, sin = solution.coefficients(eps, {**values, amplitude.name: generating})
    omega = np.broadcast_to(np.asarray(omega, dtype=float), generating.shape)
    c, s = np.moveaxis(np.asarray(cos[index]), 0, -1), np.moveaxis(np.asarray(sin[index]), 0, -1)
    frequencies = [float(w) for w in omega]
    if measure == "peak":
        measured = [float(v) for v in peak_abs(c, s)]
    elif measure == "first-harmonic":
        measured = (
            [float(v) for v in np.hypot(c[:, 1], s[:, 1])] if c.shape[1] > 1 else [0.0] * len(c)
        )
    else:
        j = np.arange(c.shape[1])
        x0, v0 = c.sum(axis=1), omega * (s * j).sum(axis=1)
        measured = [float(v) for v in np.hypot(x0, v0 / np.where(omega != 0, omega, 1.0))]
    return Backbone(coordinate, tuple(measured), tuple(to_parameter(w) for w in frequencies))
