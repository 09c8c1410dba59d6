"""The numeric-quadrature fallback: equal to the exact path on polynomials, convergent otherwise."""

import numpy as np
import pytest
import sympy as sp

from perturb import EPS, PoincareMethod, QuasilinearSystem, Status
from tests.helpers import fitted_slope, integrate

x, xd, k = sp.symbols("x xdot k")
#: FFT quadrature of O(1) trigonometric polynomials is exact to a few ulps of the largest coefficient.
QUADRATURE_ROUNDOFF = 1e-12


def test_numeric_path_equals_exact_path_on_a_polynomial():
    duffing = QuasilinearSystem([x], [xd], [1], [-EPS * x**3])
    exact = PoincareMethod(order=3, amplitudes={"x": 1}, cache=False).solve(duffing)
    numeric = PoincareMethod(order=3, amplitudes={"x": 1}, quadrature="numeric", cache=False).solve(
        duffing
    )
    assert numeric.success
    t = np.linspace(0, 10, 11)
    np.testing.assert_allclose(
        numeric.evaluate(t, 0.1), exact.evaluate(t, 0.1), atol=QUADRATURE_ROUNDOFF
    )
    for a, b in zip(exact.frequency, numeric.frequency, strict=True):
        assert float(a) == pytest.approx(float(b), abs=QUADRATURE_ROUNDOFF)


@pytest.mark.parametrize("order", [1, 2])
def test_non_polynomial_perturbation_converges_at_the_predicted_rate(order):
    """xddot + x = -eps sin(x): error of the order-N solution against the true motion ~ eps^(N+1)."""
    pendulum = QuasilinearSystem([x], [xd], [1], [-EPS * sp.sin(x)])
    sol = PoincareMethod(order=order, amplitudes={"x": 1}, cache=False).solve(pendulum)
    assert sol.success
    eps_values = np.geomspace(0.01, 0.1, 4)
    errors = []
    for eps in eps_values:
        T = float(sol.period_at(eps))
        t = np.linspace(0, T, 40)
        truth = integrate(pendulum.vector_field(eps), sol.initial_state(eps), t)
        errors.append(np.max(np.abs(sol.evaluate(t, eps) - truth)))
    assert abs(fitted_slope(eps_values, errors) - (order + 1)) < 0.3


def test_non_polynomial_needs_numbers():
    sys = QuasilinearSystem([x], [xd], [1], [-EPS * k * sp.sin(x)], parameters=[k])
    sol = PoincareMethod(order=1, amplitudes={"x": 1}, cache=False).solve(sys)
    assert sol.status is Status.NOT_POLYNOMIAL and "with_values" in sol.message
    assert (
        PoincareMethod(order=1, amplitudes={"x": 1}, cache=False)
        .solve(sys.with_values({"k": 2}))
        .success
    )
