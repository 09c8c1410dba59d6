"""The disk's analytic state against the full Euler–Poisson motion (scipy DOP853, rtol 1e-12)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from problems import get_problem

Disk = get_problem("disk")

#: eps = c/r0 values of the slope fit (reference section (f): k = 0.5, gamma0'' = 0.3).
EPSILONS = (0.04, 0.02, 0.01, 0.005)
#: Periods followed in each run.
PERIODS = 5
#: The errors must fall at least like eps**2; the fitted exponent may undershoot 2 by this much.
SLOPE_SLACK = 0.15


def reference_set(eps: float):
    """Paper geometry with c = 1 (so r0 = 1/eps), k = 0.5 and gamma3_0 = 0.3."""
    arm, C, M = math.hypot(1, 6), 20.0, 200.0
    return Disk.create(g=C / (M * arm), R=3 * C / (0.5 * M * arm), r0=1 / eps, gamma3_0=0.3)


@pytest.fixture(scope="module")
def runs():
    out = {}
    for eps in EPSILONS:
        problem = reference_set(eps)
        assert problem.epsilon() == pytest.approx(eps, rel=1e-12)
        assert problem.symbol_values()["k"] == pytest.approx(0.5, rel=1e-12)
        out[eps] = problem.true_motion_errors(problem.solve(1), periods=PERIODS)
    return out


def _slope(runs, name):
    eps = np.array(EPSILONS)
    err = np.array([runs[e][name] for e in EPSILONS])
    return np.polyfit(np.log(eps), np.log(err), 1)[0]


@pytest.mark.parametrize("name", ["p", "q", "gamma1", "gamma2", "gamma3"])
def test_errors_fall_at_least_like_eps_squared(runs, name):
    assert _slope(runs, name) > 2 - SLOPE_SLACK


def test_error_sizes_match_the_reference(runs):
    # reference (f), 10 periods: p1 errors 2.3e-4, 2.9e-5, 3.6e-6 at eps = 0.02, 0.01, 0.005
    assert runs[0.005]["p"] < 1e-5
    assert runs[0.005]["gamma1"] < 1e-4


def test_integrals_are_conserved_along_the_integration(runs):
    assert max(r["integrals"] for r in runs.values()) < 1e-10


def test_solution_closes_after_one_period():
    problem = reference_set(0.01)
    solution = problem.solve(1)
    period = problem.period(solution)
    start = problem.state_vector(solution, 0.0)
    end = problem.state_vector(solution, period)
    scale = np.array([problem.scale_c()] * 2 + [problem.values["r0"]] + [1.0] * 3)
    np.testing.assert_allclose(end / scale, start / scale, atol=1e-12)
