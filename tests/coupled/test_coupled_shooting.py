"""The shipped coupled resonators against shooting (issue 30): every analytic branch is a true
steady state, no true steady state is missing, and stability agrees with the true Floquet
multipliers.

Two independent routes: the certified first-order census continued to order N (the response), and
forced shooting of the true equations (:func:`perturb.oracle.find_forced_orbit`), seeded by each
analytic branch and, in the slow tests, from seeded random initial states that know nothing of the
analytic ones (:mod:`tests.coupled.census`).
"""

from __future__ import annotations

import numpy as np
import pytest

from perturb.oracle import heyoka_available
from perturb.response import steady_state_of
from perturb.validation import state_along
from perturb.validation.model import parameter_value_of
from problems import get_problem
from tests.coupled.census import add_orbit, census, seeded, shooting_setup

pytestmark = pytest.mark.skipif(
    not heyoka_available(), reason="the shootings take minutes without heyoka"
)

#: C of the initial-state error C·eps^(N+1) of an order-N branch against its true orbit: the
#: forced pair's worst branch measures 2.7 at N = 1 and 5.6 at N = 2, the pumped pair's 0.24 and
#: 0.64; an order lost (an error of eps^N) would measure 1/eps = 20 times more.
ORBIT_CONSTANT = 15.0


def _distinct_true_orbits(problem, order):
    """The seeded shootings: each converged, their orbits pairwise distinct (none is a shift of
    another), and each branch's true stability."""
    rhs, _, shift = shooting_setup(problem)
    p = problem.system().excitation.p
    found = []
    rows = []
    for name, point, orbit in seeded(problem, order):
        assert orbit.success, f"{name}: {orbit.message}"
        assert add_orbit(found, orbit, rhs, shift, p), f"{name} shot onto another branch's orbit"
        rows.append((name, point, orbit))
    return rows, found


def _initial_error(problem, order, name, orbit) -> float:
    state = steady_state_of(problem, order)
    values = state_along(
        state.solution(name), [0.0], parameter_value_of(problem), problem.symbol_values()
    ).values()
    analytic = np.array([float(v[0]) for v in values][:-1])
    true = np.asarray(orbit.initial_state)
    return float(np.max(np.abs(true - analytic)) / max(1.0, float(np.max(np.abs(true)))))


@pytest.mark.parametrize(
    ("name", "omega"),
    [
        ("coupled-duffings", 1.05),  # five: three localised on x1, two spread over both
        ("coupled-parametrons", 2.0),  # three: at rest, in-phase, anti-phase
    ],
)
@pytest.mark.parametrize("order", [1, 2])
def test_every_branch_is_a_distinct_true_orbit_of_its_stability(name, omega, order):
    problem = get_problem(name).create(Omega=omega)
    rows, found = _distinct_true_orbits(problem, order)
    assert len(found) == len(rows) > 1
    eps = problem.epsilon()
    for branch, point, orbit in rows:
        largest = float(np.max(np.abs(orbit.floquet_multipliers)))
        assert point.stable is (largest < 1.0), (branch, point.stable, largest)
        error = _initial_error(problem, order, branch, orbit)
        assert error <= ORBIT_CONSTANT * eps ** (order + 1), (branch, error)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "omega", "starts", "box"),
    [
        ("coupled-duffings", 1.05, 120, 3.0),
        ("coupled-parametrons", 2.03, 150, 0.4),  # 13 steady states, 5 stable
        ("forced-chain-3", 1.1, 150, 3.0),  # 15 steady states, 4 stable
    ],
)
def test_no_true_steady_state_is_missing(name, omega, starts, box):
    """Shooting from seeded random states finds no steady state outside the analytic ones; every
    analytic one is a distinct true orbit, of the same stability."""
    problem = get_problem(name).create(Omega=omega)
    rows, found = _distinct_true_orbits(problem, 1)
    for branch, point, orbit in rows:
        largest = float(np.max(np.abs(orbit.floquet_multipliers)))
        assert point.stable is (largest < 1.0), (branch, point.stable, largest)
    rhs, _, shift = shooting_setup(problem)
    p = problem.system().excitation.p
    random = census(problem, starts=starts, box=box, seed=30)
    assert random, "no random start converged: the census proves nothing"

    class _Orbit:  # a census orbit in the form add_orbit takes
        def __init__(self, orbit):
            self.initial_state = orbit.state
            self.floquet_multipliers = [orbit.largest_multiplier]

    extra = [o for o in random if add_orbit(found, _Orbit(o), rhs, shift, p)]
    assert not extra, f"true steady states the response does not have: {extra}"


@pytest.mark.slow
def test_the_forced_chain_of_four_at_its_richest():
    """Every order-2 steady state at Omega = 1.1 (27 of them) a distinct true orbit, stability
    agreeing. At order 1 there are 29, two of which (in-phase-lower and -upper, 0.3 % apart) lie
    within eps^2 of a fold that the true motion has already passed: no true orbit there, their
    shootings stall; order 2 drops them."""
    problem = get_problem("forced-chain-4").create(Omega=1.1)
    rows, found = _distinct_true_orbits(problem, 2)
    assert len(found) == len(rows) > 20
    stable = [point.stable for _, point, _ in rows]
    true = [bool(np.max(np.abs(o.floquet_multipliers)) < 1.0) for _, _, o in rows]
    assert stable == true
