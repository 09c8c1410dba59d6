"""The slow flow: its equilibria are the response's branches (another route), its flow reaches
the stable ones, its section map inverts, its separatrix starts at the saddle."""

from __future__ import annotations

import numpy as np
import pytest

from perturb.dynamics.slowflow import slow_flow_of
from perturb.errors import InvalidParameterError
from perturb.steady import steady_state

#: Newton on the order-N displacement function (scipy's fsolve from the certified first-order
#: roots) against the response's continuation with its own Newton polish: both to ~1e-12.
SAME_ROOT = 1e-8


def test_the_equilibria_are_the_response_branches(bistable):
    """The slow flow of order 2 (Delta u to eps^2) holds the equations of `perturb response
    --order 1`: its equilibria, found from the certified first-order roots by Newton, are the
    branches the response continues (names and stability alike)."""
    flow = slow_flow_of(bistable, 2)
    found = sorted(flow.equilibria(), key=lambda e: float(np.hypot(*e.amplitudes)))
    steady = steady_state(bistable.system(), bistable.symbol_values(), bistable.epsilon(), 1)
    assert len(found) == len(steady.points) == 3
    for eq, point, name in zip(found, steady.points, steady.names, strict=True):
        u = np.array([point.amplitudes["a_x"], point.amplitudes["b_x"]])
        assert np.max(np.abs(eq.amplitudes - u)) <= SAME_ROOT, name
        assert (eq.kind == "stable") == bool(point.stable), name
    assert [e.kind for e in found] == ["stable", "saddle", "stable"]


def test_the_averaged_flow_reaches_its_stable_equilibria(bistable):
    flow = slow_flow_of(bistable, 1)
    stable = [e.amplitudes for e in flow.equilibria() if e.kind == "stable"]
    for start in ([0.1, 0.1], [2.5, 0.0]):
        end = flow.integrate(start, np.linspace(0, 4000, 3))[-1]
        gaps = [float(np.max(np.abs(end - s))) for s in stable]
        assert min(gaps) <= 1e-3


def test_the_section_map_inverts(bistable):
    flow = slow_flow_of(bistable, 1)
    u = np.array([[0.3, -0.7], [1.2, 0.4]])
    for phase in (0.0, 1.3, np.array([0.2, 5.0])):
        y = flow.to_section(u, phase)
        np.testing.assert_allclose(flow.from_section(y, phase), u, rtol=0, atol=1e-14)
    # at phase 0: x = a, xdot = nu b
    np.testing.assert_allclose(flow.to_section(u[0], 0.0), [0.3, -0.7 * 1.05], atol=1e-15)


def test_the_separatrix_leaves_the_saddle_both_ways(bistable):
    flow = slow_flow_of(bistable, 1)
    saddle = next(e for e in flow.equilibria() if e.kind == "saddle")
    curves = flow.separatrix([(-3, 3), (-3, 3)])
    assert len(curves) == 2
    start = flow.to_section(saddle.amplitudes)
    for curve in curves:
        np.testing.assert_allclose(curve[0], start, atol=1e-12)
        assert curve.shape[0] > 10 and np.max(np.abs(curve[-1])) >= 3  # out of the box


def test_orders_below_one_are_refused(bistable):
    with pytest.raises(InvalidParameterError, match="order"):
        slow_flow_of(bistable, 0)
