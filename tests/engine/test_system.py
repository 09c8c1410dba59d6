"""Validation of QuasilinearSystem: every bad input names the argument and the fix."""

import pytest
import sympy as sp

from perturb import EPS, InvalidSystemError, QuasilinearSystem, Regime

x, xd, y, yd, k = sp.symbols("x xdot y ydot k")


def duffing(**kw):
    base = dict(coordinates=[x], velocities=[xd], frequencies=[1], rhs=[-EPS * x**3])
    base.update(kw)
    return QuasilinearSystem(**base)


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"frequencies": [0]}, "frequencies[0]"),
        ({"frequencies": [-2]}, "positive"),
        ({"frequencies": [sp.I]}, "positive"),
        ({"rhs": [-EPS * k * x**3]}, "undeclared symbols ['k']"),
        ({"rhs": [x**3]}, "lowest power of epsilon must be positive"),
        ({"rhs": [-EPS * x, 0]}, "`rhs` has 2 entries"),
        ({"initial_values": ["x0"]}, "`initial_values` has 1"),
    ],
)
def test_bad_systems_raise_one_clear_error(kwargs, fragment):
    with pytest.raises(InvalidSystemError) as info:
        duffing(**kwargs)
    assert fragment in str(info.value)
    assert isinstance(info.value, ValueError)


def test_expansion_and_leading_order():
    sys = QuasilinearSystem(
        [x, y], [xd, yd], [1, 1], [EPS**2 * x * y + EPS**3 * y, EPS**2 * x**2], parameter=EPS
    )
    assert sys.leading_order == 2
    coeffs = sys.expansion(3)
    assert coeffs[0][2] == x * y and coeffs[0][3] == y and coeffs[1][1] == 0


def test_large_parameter_form_is_the_same_system():
    mu = sp.Symbol("mu")
    large = QuasilinearSystem([x], [xd], [1], [-(x**3) / mu], parameter=mu, regime=Regime.LARGE)
    assert sp.simplify(large.rhs_in_epsilon[0] - duffing().rhs_in_epsilon[0]) == 0
    assert duffing().as_large_parameter().rhs_in_epsilon == duffing().rhs_in_epsilon


def test_large_parameter_must_vanish_at_infinity():
    mu = sp.Symbol("mu")
    with pytest.raises(InvalidSystemError, match="lowest power"):
        QuasilinearSystem([x], [xd], [1], [mu * x**3], parameter=mu, regime="large")
