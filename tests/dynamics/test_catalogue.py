"""The catalogue: every branch of the series shot, the stable ones attractors, the saddle kept,
each proved by the shooting; its points on the section integrated by a second route."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from perturb.dynamics.attractors import CatalogueStatus, StateKind, catalogue, decode, encode
from perturb.errors import InvalidParameterError
from problems import get_problem

#: scipy DOP853 at rtol 1e-12 against the shooting's orbit over one period: both are good to
#: ~1e-10 (the shooting's floor); 1e-8 leaves room for 1000 x the floor.
ORBIT_AGREE = 1e-8


def test_the_bistable_duffing_has_two_attractors_and_a_saddle(chart):
    assert chart.status is CatalogueStatus.OK
    assert [s.name for s in chart.attractors] == ["lower", "upper"]
    assert [s.name for s in chart.saddles] == ["middle"]
    for state in chart.attractors:
        assert state.kind is StateKind.ATTRACTOR and state.largest_multiplier < 1
        # linear damping: |mu|^2 = exp(-2 eps zeta T) for a focus (Liouville)
        assert state.largest_multiplier == pytest.approx(
            math.exp(-0.05 * 0.1 * 2 * math.pi / 1.05), rel=1e-8
        )
    assert chart.saddles[0].largest_multiplier > 1
    # the capture radii are a tenth of the distance to the nearest other state
    lower, upper = chart.attractors
    saddle = chart.saddles[0]
    gap = float(np.linalg.norm(lower.points[0] - saddle.points[0]))
    assert lower.radius == pytest.approx(0.1 * gap)


def test_each_point_is_a_periodic_orbit_by_plain_scipy(chart, motion):
    def f(t, y):
        x, v = y
        return [v, -x - 0.05 * x**3 - 0.01 * v + 0.05 * math.cos(1.05 * t)]

    for state in chart.states:
        y0 = state.points[0]
        end = solve_ivp(f, (0, 2 * math.pi / 1.05), y0, method="DOP853", rtol=1e-12, atol=1e-14)
        assert np.max(np.abs(end.y[:, -1] - y0)) <= ORBIT_AGREE, state.name


def test_a_section_at_another_phase_holds_the_same_orbits(bistable, motion, chart):
    moved = catalogue(bistable, 1, 1.0, motion)
    assert [s.name for s in moved.states] == [s.name for s in chart.states]
    for a, b in zip(chart.states, moved.states, strict=True):
        # the orbit through a's point at theta = 0, at theta = 1
        from perturb.oracle import choose

        traj = choose(None, symbolic=True).integrate(
            motion.rhs, (0.0, 1.0 / motion.omega), np.append(a.points[0], 0.0)
        )
        assert np.max(np.abs(traj.y_final[:2] - b.points[0])) <= ORBIT_AGREE


def test_the_catalogue_round_trips_through_json(chart):
    again = decode(encode(chart))
    assert [s.name for s in again.states] == [s.name for s in chart.states]
    for a, b in zip(again.states, chart.states, strict=True):
        np.testing.assert_array_equal(a.points, b.points)
        assert a.radius == b.radius and a.kind is b.kind and a.multipliers == b.multipliers


def test_an_undamped_response_is_no_attractor():
    undamped = get_problem("forced-duffing").create(zeta=0.0)
    chart = catalogue(undamped, 1)
    assert chart.status is CatalogueStatus.NO_STABLE_STATE and not chart.attractors
    assert "marginal" in chart.message


def test_bad_requests_are_refused(bistable):
    with pytest.raises(InvalidParameterError, match="order"):
        catalogue(bistable, 0)
    with pytest.raises(InvalidParameterError, match="phase"):
        catalogue(bistable, 1, math.nan)
    with pytest.raises(InvalidParameterError, match="driven"):
        catalogue(get_problem("duffing").create(), 1)
