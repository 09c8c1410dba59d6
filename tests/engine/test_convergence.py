"""Against the true periodic orbits the error of an order-N solution falls as eps^(N+1)."""

import numpy as np
import pytest
from scipy.special import ellipk

from perturb.validation import original_rhs
from problems import get_problem
from tests.helpers import fitted_slope, integrate, shoot_1dof

EPS_DECADE = np.geomspace(0.01, 0.1, 5)  # a decade of the small parameter
SLOPE_TOL = 0.3  # issue 2: the fitted slope must be within 0.3 of N + 1


def duffing_period_exact(eps, amplitude):
    """x'' + x + eps x^3 = 0, x(0) = A: x = A cn(w t | m), w^2 = 1 + eps A^2, m = eps A^2 / (2 w^2)."""
    w2 = 1 + eps * amplitude**2
    return 4 * ellipk(eps * amplitude**2 / (2 * w2)) / np.sqrt(w2)


@pytest.mark.parametrize("order", [1, 2, 3])
def test_duffing_error_slope(order):
    period_err, state_err = [], []
    for eps in EPS_DECADE:
        problem = get_problem("duffing").create(eps=eps, amplitude=1.0)
        sol = problem.solve(order)
        T = problem.period(sol)
        period_err.append(abs(T - duffing_period_exact(eps, 1.0)))
        t = np.linspace(0, T, 64)
        y0 = sol.initial_state(eps, problem.symbol_values())
        truth = integrate(original_rhs(problem), y0, t)
        state_err.append(np.max(np.abs(sol.evaluate(t, eps, problem.symbol_values()) - truth)))
    # the period is known to the order of the frequency series, the state to eps^order
    n_freq = len(sol.frequency)
    assert abs(fitted_slope(EPS_DECADE, period_err) - n_freq) < SLOPE_TOL
    assert abs(fitted_slope(EPS_DECADE, state_err) - (order + 1)) < SLOPE_TOL


@pytest.mark.parametrize("order", [1, 2])
def test_van_der_pol_error_slope(order):
    state_err = []
    for eps in EPS_DECADE:
        problem = get_problem("van-der-pol").create(eps=eps)
        sol = problem.solve(order)
        x0, T = shoot_1dof(original_rhs(problem), 2.0, 2 * np.pi)
        t = np.linspace(0, T, 64)
        truth = integrate(original_rhs(problem), [x0, 0.0], t)
        state_err.append(np.max(np.abs(sol.evaluate(t, eps, {}) - truth)))
    assert abs(fitted_slope(EPS_DECADE, state_err) - (order + 1)) < SLOPE_TOL


def test_van_der_pol_limit_cycle_amplitude_and_period():
    # textbook: amplitude 2 + eps^2/96 * ..., period 2 pi (1 + eps^2/16) + O(eps^4)
    eps = 0.05
    problem = get_problem("van-der-pol").create(eps=eps)
    sol = problem.solve(2)
    x0, T = shoot_1dof(original_rhs(problem), 2.0, 2 * np.pi)
    assert problem.period(sol) == pytest.approx(T, abs=10 * eps**4)
    assert sol.initial_state(eps, {})[0] == pytest.approx(x0, abs=10 * eps**3)
