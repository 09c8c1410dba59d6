"""The true curve's points hold the one true-orbit value (a PeriodicOrbit found by
continuation), checked against a second route."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from perturb.oracle import OrbitRoute, SymbolicRHS, find_forced_orbit, heyoka_available
from perturb.response.model import problem_response
from problems import get_problem

pytestmark = pytest.mark.skipif(
    not heyoka_available(), reason="the true curves take minutes without heyoka"
)


def test_a_true_curve_point_holds_the_orbit_the_forced_shooting_finds():
    """Each point of the true curve holds its orbit: its period 2π/Ω, and its multipliers against
    Liouville's det M = exp(-2 ζ ε T) (the damped linear oscillator x'' + 2ζε x' + x = εF cos Ωt:
    the trace of its Jacobian is -2ζε) and against a second route, the forced shooting from the
    point's state at that period (both converge to the shots' ~1e-12: 1e-9 leaves a margin) at both ends and at the
    largest amplitude."""
    problem = get_problem("forced-duffing").create(gamma=0.0)
    result = problem_response(problem, "Omega", np.linspace(0.9, 1.1, 3), true=400)
    (curve,) = result.true_curve.curves
    eps, zeta, force = (problem.values[k] for k in ("eps", "zeta", "F"))
    x, v, th = sp.symbols("x v theta")
    points = curve.points
    largest = max(range(len(points)), key=lambda k: points[k].norm())
    second_route = {0, largest, len(points) - 1}  # both ends and the largest amplitude
    for k, p in enumerate(points):
        orbit = p.orbit
        assert orbit.found_by is OrbitRoute.CONTINUATION and orbit.success
        assert orbit.period == pytest.approx(2 * math.pi / p.value, rel=1e-14)
        assert p.multipliers == tuple(complex(z) for z in orbit.multipliers)
        assert p.state == tuple(float(y) for y in orbit.initial_state)
        det = math.exp(-2 * zeta * eps * orbit.period)
        assert complex(np.prod(orbit.multipliers)) == pytest.approx(det, rel=1e-9)
        if k in second_route:
            rhs = SymbolicRHS(
                (x, v, th), (v, -2 * zeta * eps * v - x + eps * force * sp.cos(th), p.value)
            )
            other = find_forced_orbit(rhs, list(p.state), orbit.period)
            assert other.success, other.message
            np.testing.assert_allclose(other.initial_state, orbit.initial_state, atol=1e-9)
            np.testing.assert_allclose(other.multipliers, orbit.multipliers, atol=1e-9)
    assert len(second_route) == 3
