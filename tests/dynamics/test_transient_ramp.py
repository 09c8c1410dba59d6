"""Transients beside the slow flow, and ramps whose jumps tend to the folds as the rate goes to 0."""

from __future__ import annotations

import math

import numpy as np
import pytest

from perturb.dynamics.ramp import ramp
from perturb.dynamics.transient import transient
from perturb.errors import InvalidParameterError
from problems import get_problem


def test_from_rest_the_motion_settles_on_the_lower_state(bistable):
    result = transient(bistable, {"x": 0.0, "xdot": 0.0}, 300)
    assert result.settled == "lower" and result.success
    assert 0 < result.settle_time < 300 * 2 * math.pi / 1.05
    assert result.slow_settled.startswith("lower")
    lower = result.catalogue.attractors[0]
    # the true envelope's end is the lower orbit's amplitude read at t = end
    end = result.envelope()[-1, 0]
    assert end == pytest.approx(float(np.hypot(*lower.points[0] * [1, 1 / 1.05])), rel=0.05)
    # the slow flow (first order) ends within O(eps) of the true envelope
    assert abs(result.envelope(slow=True)[-1, 0] - end) <= 0.05 * end


def test_a_transient_that_jumps_to_the_upper_state(bistable):
    result = transient(bistable, {"x": 2.0, "xdot": 0.0}, 300, order=2)
    assert result.settled == "upper" and result.slow_settled.startswith("upper")
    # the envelope grows to the upper state's amplitude, the slow flow's with it
    env, slow = result.envelope()[:, 0], result.envelope(slow=True)[:, 0]
    assert env[-1] > 1.5 and abs(slow[-1] - env[-1]) <= 0.05 * env[-1]


def test_the_higher_order_slow_flow_ends_nearer_the_truth(bistable):
    first = transient(bistable, {"x": 2.0, "xdot": 0.0}, 300, order=1)
    second = transient(bistable, {"x": 2.0, "xdot": 0.0}, 300, order=2)
    gap = [abs(r.envelope(slow=True)[-1, 0] - r.envelope()[-1, 0]) for r in (first, second)]
    assert gap[1] < gap[0]


def test_bad_transients_are_refused(bistable):
    with pytest.raises(InvalidParameterError, match="not a coordinate"):
        transient(bistable, {"y": 1.0}, 10)
    with pytest.raises(InvalidParameterError, match="finite"):
        transient(bistable, {"x": math.nan}, 10)
    with pytest.raises(InvalidParameterError, match="periods"):
        transient(bistable, {"x": 1.0}, 0)


@pytest.fixture(scope="module")
def ramps():
    """The forced Duffing of docs/forced.md's fold table (eps = 0.02, F = 0.5): folds at
    1.0104720693 and 1.0424015806 (order 3), ramped both ways at four rates."""
    problem = get_problem("forced-duffing").create(eps=0.02, F=0.5)
    return ramp(problem, "Omega", 0.99, 1.06, [1e-5, 5e-6, 2.5e-6, 1.25e-6], both_ways=True,
                order=3)  # fmt: skip


def test_the_folds_are_the_response_curves(ramps):
    assert ramps.folds == pytest.approx((1.0104720693, 1.0424015806), abs=1e-8)


@pytest.mark.parametrize("direction", ["up", "down"])
def test_the_jump_tends_to_the_fold_as_the_rate_goes_to_zero(ramps, direction):
    runs = [r for r in ramps.runs if r.direction == direction]
    assert [r.rate for r in runs] == [1e-5, 5e-6, 2.5e-6, 1.25e-6]
    fold = 1.0424015806 if direction == "up" else 1.0104720693
    assert all(r.fold == pytest.approx(fold, abs=1e-8) for r in runs)
    delays = [r.delay for r in runs]
    assert all(d > 0 for d in delays)  # the jump comes after the fold ...
    assert all(b < a for a, b in zip(delays, delays[1:], strict=False))  # ... less so as r -> 0
    # a saddle-node's delay goes as r^(2/3): the slope over the rates is near it
    slope = np.polyfit(np.log([r.rate for r in runs]), np.log(delays), 1)[0]
    assert 0.3 <= slope <= 1.0
    # the jump is down (up-ramp, hardening) or up (down-ramp)
    assert all((r.jump_size < 0) == (direction == "up") for r in runs)


def test_bad_ramps_are_refused():
    problem = get_problem("forced-duffing").create()
    with pytest.raises(InvalidParameterError, match="rate"):
        ramp(problem, "Omega", 0.9, 1.1, 0.0)
    with pytest.raises(InvalidParameterError, match="does not move"):
        ramp(problem, "Omega", 1.0, 1.0, 1e-4)
    with pytest.raises(InvalidParameterError, match="does not move the drive frequency"):
        ramp(problem, "F", 0.5, 1.0, 1e-4)
    with pytest.raises(InvalidParameterError, match="does not move the drive frequency"):
        ramp(problem, "eps", 0.05, 0.06, 1e-4)  # Omega = 1 + eps*sigma is the user's Omega
    with pytest.raises(InvalidParameterError, match="not a parameter"):
        ramp(problem, "Q", 0.9, 1.1, 1e-4)


@pytest.mark.slow
def test_the_jump_is_where_plain_scipy_puts_it(ramps):
    """An independent ramp: the equation written by hand, scipy's DOP853, the same protocol
    (settled 400 periods at the start from rest, then Omega' = r): its envelope jumps where the
    ramp's does, to within the envelope's own resolution (the parameter moves by r T a period)."""
    from scipy.integrate import solve_ivp

    from perturb.dynamics.ramp import _jump

    eps, zeta, gamma, force, rate, start, stop = 0.02, 0.1, 1.0, 0.5, 1e-5, 0.99, 1.06

    def f(t, y, slope):
        x, v, theta, omega = y
        return [v, -x - eps * (2 * zeta * v + gamma * x**3 - force * math.cos(theta)), omega,
                slope]  # fmt: skip

    settle = solve_ivp(f, (0, 400 * 2 * math.pi / start), [0, 0, 0, start], args=(0.0,),
                       method="DOP853", rtol=1e-10, atol=1e-12)  # fmt: skip
    duration = (stop - start) / rate
    periods = int(math.ceil(duration / (4 * math.pi / (start + stop))))
    t = np.linspace(0, duration, periods * 40 + 1)
    run = solve_ivp(f, (0, duration), settle.y[:, -1], args=(rate,), method="DOP853", rtol=1e-10,
                    atol=1e-12, t_eval=t)  # fmt: skip
    x, omega = np.abs(run.y[0]), run.y[3]
    envelope = x[: periods * 40].reshape(periods, 40).max(axis=1)
    values = omega[40 : periods * 40 + 1 : 40]
    jump, _ = _jump(values, envelope)
    up = next(r for r in ramps.runs if r.direction == "up" and r.rate == rate)
    assert abs(jump - up.jump) <= 2 * rate * 2 * math.pi
