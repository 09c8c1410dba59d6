"""Invariants of the constructed solutions over random valid parameters (hypothesis)."""

import numpy as np
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb import PoincareMethod
from perturb.validation import original_rhs
from perturb.validation.model import parameter_value_of
from problems import get_problem
from tests.helpers import integrate

#: Safety factor on the truncation-error estimate eps^(N+1) * |next-order term|: the estimate leaves out
#: the O(eps^(N+2)) remainder and the phase drift of the higher frequency terms.
SAFETY = 8.0
#: Round-off allowance for comparisons that are exact in exact arithmetic.
ROUNDOFF = 1e-12

problems = st.sampled_from(["duffing", "van-der-pol", "resonant-pair", "linear-pair"])
eps_values = st.floats(0.005, 0.05, allow_nan=False, allow_infinity=False)
orders = st.integers(1, 2)


def truncation_bound(problem, order, eps):
    """eps^(N+1) times the size of the order-(N+1) terms over one period (state and phase drift)."""
    nxt = problem.solve(order + 1)
    vals = {sp.Symbol(k, positive=True): v for k, v in problem.symbol_values().items()}
    vals.update({sp.Symbol(k): v for k, v in problem.symbol_values().items()})
    size = 0.0
    for row in nxt.terms:
        for c, s_ in row[order + 1].terms.values():
            size = max(size, abs(float(c.xreplace(vals))) + abs(float(s_.xreplace(vals))))
    omega_next = (
        abs(float(nxt.frequency[order + 1].xreplace(vals)))
        if len(nxt.frequency) > order + 1
        else 0.0
    )
    amplitude = float(
        np.max(
            np.abs(
                problem.solve(order).initial_state(
                    parameter_value_of(problem), problem.symbol_values()
                )
            )
        )
    )
    return eps ** (order + 1) * (3 * size + 2 * np.pi * omega_next * (1 + amplitude)) + ROUNDOFF


@given(problems, eps_values, orders, st.floats(0.0, 1.0))
def test_time_shift_invariance(name, eps, order, phase):
    """Starting the true flow anywhere on the analytic orbit, it stays on it to the truncation order."""
    problem = get_problem(name).create(eps=eps)
    sol = problem.solve(order)
    values = problem.symbol_values()
    T = problem.period(sol)
    t0 = phase * T
    t = np.linspace(0.0, T, 33)
    start = sol.evaluate(np.array(t0), eps, values)
    truth = integrate(original_rhs(problem), start, t)
    analytic = sol.evaluate(t0 + t, eps, values)
    assert np.max(np.abs(truth - analytic)) <= SAFETY * truncation_bound(problem, order, eps)


@given(problems, eps_values, orders)
def test_state_at_one_period_equals_initial_state(name, eps, order):
    problem = get_problem(name).create(eps=eps)
    sol = problem.solve(order)
    values = problem.symbol_values()
    T = problem.period(sol)
    y0 = sol.initial_state(eps, values)
    # the analytic orbit is exactly T-periodic ...
    np.testing.assert_allclose(sol.evaluate(np.array(T), eps, values), y0, atol=ROUNDOFF * (1 + T))
    # ... and the true flow closes it to the truncation order
    yT = integrate(original_rhs(problem), y0, [0.0, T])[:, -1]
    assert np.max(np.abs(yT - y0)) <= SAFETY * truncation_bound(problem, order, eps)


@given(problems, st.floats(0.01, 0.2), orders)
def test_regime_equivalence(name, eps, order):
    """Solving the system written in mu = 1/eps gives the same orbit after the renaming."""
    problem = get_problem(name).create(eps=eps)
    small = problem.solve(order)
    large = PoincareMethod(order=order, **problem.method_options()).solve(
        problem.system().as_large_parameter()
    )
    values = problem.symbol_values()
    t = np.linspace(0.0, 7.0, 9)
    np.testing.assert_allclose(
        large.evaluate(t, 1.0 / eps, values), small.evaluate(t, eps, values), rtol=1e-12, atol=1e-12
    )
    assert (
        sp.simplify(
            large.period_series().subs(large.parameter, 1 / sp.Symbol("e"))
            - small.period_series().subs(small.parameter, sp.Symbol("e"))
        )
        == 0
    )
