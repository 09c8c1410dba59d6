"""The ensemble's two routes agree; classification captures, tells a recurrence apart and never
forces a state into a known class; a classified state integrated further stays there."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from perturb.dynamics.classify import Outcome, classify
from perturb.dynamics.ensemble import ensemble
from perturb.errors import InvalidParameterError

#: Heyoka (tol 1e-10) against the numpy RK4 (256 steps a period) over 20 periods from |x| <= 3:
#: RK4's global error, 6e-5 measured at 128 steps, falls as h^4 to 4e-6 at 256; 2e-5 leaves a
#: factor 5 (heyoka's own error is ~1e-9).
ROUTES_AGREE = 2e-5


@pytest.fixture(scope="module")
def states():
    rng = np.random.default_rng(7)
    return rng.uniform(-3, 3, size=(13, 2))  # 13: one batch of 8 lanes and a partial one


def test_heyoka_and_numpy_give_the_same_returns(motion, states):
    a = ensemble(motion, 0.3, "heyoka").returns(states, 20)
    b = ensemble(motion, 0.3, "numpy").returns(states, 20)
    assert a.shape == b.shape == (20, 13, 2)
    assert np.max(np.abs(a - b)) <= ROUTES_AGREE


def test_the_returns_are_scipy_s_stroboscopic_map(motion, states):
    returns = ensemble(motion, 0.3, "heyoka").returns(states[:3], 5)
    period = 2 * math.pi / 1.05

    def f(t, y):
        x, v = y
        return [v, -x - 0.05 * x**3 - 0.01 * v + 0.05 * math.cos(1.05 * t + 0.3)]

    for j in range(3):
        ref = solve_ivp(f, (0, 5 * period), states[j], method="DOP853", rtol=1e-12, atol=1e-14,
                        t_eval=period * np.arange(1, 6))  # fmt: skip
        assert np.max(np.abs(ref.y.T - returns[:, j])) <= ROUTES_AGREE


def test_a_blow_up_is_nan_not_a_number(bistable):
    from perturb.dynamics.motion import motion_of
    from problems import get_problem

    softening = motion_of(get_problem("forced-duffing").create(gamma=-1.0))
    out = ensemble(softening, 0.0, "heyoka").returns([[12.0, 0.0], [0.1, 0.0]], 30)
    assert not np.all(np.isfinite(out[:, 0])) and np.all(np.isfinite(out[:, 1]))


@pytest.mark.parametrize("backend", ["heyoka", "numpy"])
def test_classified_states_stay_at_their_attractor(motion, chart, backend):
    """Every classified state, integrated 100 periods further by plain scipy, is within its
    attractor's capture radius and closer to it than where it was classified."""
    rng = np.random.default_rng(11)
    states = rng.uniform(-3, 3, size=(10, 2))
    result = classify(ensemble(motion, 0.0, backend), chart, states, 1000)
    assert np.all(result.codes >= 0) and not result.found
    period = 2 * math.pi / 1.05

    def f(t, y):
        x, v = y
        return [v, -x - 0.05 * x**3 - 0.01 * v + 0.05 * math.cos(1.05 * t)]

    for code, final in zip(result.codes, result.final, strict=True):
        attractor = chart.attractors[code]
        before = float(attractor.distance(final[None])[0])
        assert before <= attractor.radius
        later = solve_ivp(f, (0, 100 * period), final, method="DOP853", rtol=1e-10, atol=1e-12)
        after = float(attractor.distance(later.y[:, -1][None])[0])
        assert after < before and after <= attractor.radius


def test_the_two_routes_classify_alike(motion, chart):
    states = np.random.default_rng(3).uniform(-3, 3, size=(40, 2))
    a = classify(ensemble(motion, 0.0, "heyoka"), chart, states, 1000)
    b = classify(ensemble(motion, 0.0, "numpy"), chart, states, 1000)
    np.testing.assert_array_equal(a.codes, b.codes)


def test_a_cap_too_short_is_no_convergence_never_a_guess(motion, chart):
    states = np.array([[2.9, -2.9], [-2.0, 2.5]])
    result = classify(ensemble(motion, 0.0), chart, states, 3)
    assert list(result.codes) == [Outcome.NO_CONVERGENCE.code] * 2
    assert list(result.periods) == [3, 3]


def test_a_state_past_the_barrier_escapes():
    from perturb.dynamics.attractors import catalogue
    from perturb.dynamics.motion import motion_of
    from problems import get_problem

    softening = get_problem("forced-duffing").create(gamma=-1.0, F=0.2)
    chart = catalogue(softening, 1)
    result = classify(ensemble(motion_of(softening)), chart, [[8.0, 0.0], [0.0, 0.0]], 200)
    assert result.codes[0] == Outcome.ESCAPED.code
    assert result.codes[1] >= 0


def test_an_orbit_the_series_does_not_know_is_found_not_forced(motion, chart):
    """A catalogue without the upper state: the states that go there are not put into `lower`:
    they are a period-1 orbit found by recurrence, at the upper state's point."""
    import attrs

    lower, upper = chart.attractors
    partial = attrs.evolve(chart, states=(lower, *chart.saddles))
    states = np.array([[upper.points[0][0] + 0.3, upper.points[0][1]], [-0.5, 0.0]])
    result = classify(ensemble(motion, 0.0), partial, states, 1000)
    assert result.codes[1] == 0  # lower
    assert result.codes[0] == 1 and len(result.found) == 1
    found = result.found[0]
    assert found.period == 1 and found.name == "period-1-1"
    assert np.max(np.abs(found.points[0] - upper.points[0])) <= 1e-4
    # shot with its period fixed, it is the upper state, with its multipliers
    from perturb.dynamics.attractors import confirm

    proved = confirm(motion, found, 0.0)
    assert "proved by shooting" in proved.message
    assert proved.largest_multiplier == pytest.approx(upper.largest_multiplier, rel=1e-8)


def test_bad_ensembles_are_refused(motion):
    with pytest.raises(InvalidParameterError, match="backend"):
        ensemble(motion, 0.0, "rk4")
    with pytest.raises(InvalidParameterError, match="phase"):
        ensemble(motion, math.inf)
    with pytest.raises(InvalidParameterError, match="shape"):
        ensemble(motion).returns(np.zeros((3, 3)), 2)


def test_a_state_on_the_saddle_is_said_so(motion, chart):
    saddle = chart.saddles[0]
    result = classify(ensemble(motion, 0.0), chart, saddle.points[:1], 1000)
    assert result.codes[0] == Outcome.ON_SADDLE.code and not result.found


def test_a_state_carried_to_another_phase_goes_to_the_same_attractor(bistable, motion, chart):
    """The section at drive phase 1: each state carried there by the motion (scipy) reaches the
    attractor of the same name as from phase 0."""
    from perturb.dynamics.attractors import catalogue

    moved_chart = catalogue(bistable, 1, 1.0, motion)
    states = np.random.default_rng(5).uniform(-3, 3, size=(12, 2))

    def f(t, y):
        x, v = y
        return [v, -x - 0.05 * x**3 - 0.01 * v + 0.05 * math.cos(1.05 * t)]

    carried = np.array([
        solve_ivp(f, (0, 1.0 / 1.05), y, method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
        for y in states
    ])  # fmt: skip
    at_zero = classify(ensemble(motion, 0.0), chart, states, 1000)
    at_one = classify(ensemble(motion, 1.0), moved_chart, carried, 1000)
    names = [chart.attractors[c].name for c in at_zero.codes]
    assert names == [moved_chart.attractors[c].name for c in at_one.codes]
    assert set(names) == {"lower", "upper"}


def test_threads_sharing_an_ensemble_get_the_same_returns(motion, states):
    """Each thread integrates with its own copy of the compiled integrator (Dask's threaded
    workers share a process): four at once give the returns of one alone."""
    import threading

    integrator = ensemble(motion, 0.0, "heyoka")
    alone = integrator.returns(states, 20)
    out: dict = {}
    threads = [
        threading.Thread(target=lambda i=i: out.__setitem__(i, integrator.returns(states, 20)))
        for i in range(4)
    ]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert all(np.array_equal(out[i], alone) for i in range(4))


def test_orbits_found_in_two_chunks_are_one(chart):
    """The driver merges the orbits each chunk found: the same orbit (its points a little apart,
    as two runs converge to it) is one code; another period is another."""
    from perturb.dynamics.attractors import StateKind, SteadyOrbit
    from perturb.dynamics.classify import merge_found

    one = SteadyOrbit("period-1-1", StateKind.FOUND, [[0.5, 0.5]], radius=0.05)
    same = SteadyOrbit("period-1-1", StateKind.FOUND, [[0.5 + 1e-6, 0.5]], radius=0.05)
    two = SteadyOrbit("period-2-1", StateKind.FOUND, [[0.5, 0.5], [-0.5, -0.5]], radius=0.05)
    known: list = []
    assert merge_found(known, (one,), chart.scale) == {0: 0}
    assert merge_found(known, (two, same), chart.scale) == {0: 1, 1: 0}
    assert [o.name for o in known] == ["period-1-1", "period-2-1"]
