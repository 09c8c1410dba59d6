"""sympy → heyoka translation (issue 9 item 3): exact powers at a zero base, checked against sympy.

The check compares heyoka's Taylor coefficients with sympy's own derivatives: along the straight
line :math:`x(t) = x_0 + c\\,t` the system :math:`\\dot x = c,\\ \\dot z = f(x)` has
:math:`z^{[1]} = f(x_0)` and :math:`z^{[2]} = \\tfrac12 \\nabla f(x_0)\\cdot c`, and every further
coefficient must be finite where :math:`f` is smooth.  A float ``pow`` fails exactly there: its
Taylor recurrence divides by the base, so :math:`x^3` at :math:`x = 0` gives NaN.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from perturb.errors import InvalidParameterError
from perturb.oracle import Heyoka, Scipy, SymbolicRHS, heyoka_available, to_heyoka

pytestmark = pytest.mark.skipif(not heyoka_available(), reason="heyoka is not installed")

#: Relative agreement (on max(1, |reference|)) of heyoka's double-precision Taylor coefficients with
#: sympy's 30-digit evaluation: an expression of <= 8 leaves costs a few tens of roundings, each
#: 1.1e-16, amplified by cancellation in sums and by powers up to the 6th (relative error x6).
TRANSLATION_RTOL = 1e-11

#: Digits of the sympy reference: far beyond double, so that it is exact for the comparison.
REFERENCE_DIGITS = 30

#: Examples drawn: each compiles a small Taylor integrator (~0.05 s); 40 covers every node type
#: several times at zero, negative and positive states (derandomized in the ci profile).
N_EXAMPLES = 40

STATE = sp.symbols("s0:3")
VELOCITY = (1.0, -0.5, 2.0)  # c: non-zero, so that the first derivative of a power reaches its base


def _positive(e: sp.Expr) -> sp.Expr:
    """A base that cannot vanish, for the negative and fractional powers (1 + e**2 >= 1)."""
    return 1 + e**2


def _extend(children):
    pair = st.tuples(children, children)
    return st.one_of(
        pair.map(lambda ab: ab[0] + ab[1]),
        pair.map(lambda ab: ab[0] * ab[1]),
        pair.map(lambda ab: ab[0] - 2 * ab[1]),
        # integer powers of anything: zero and negative bases included
        st.tuples(children, st.integers(2, 6)).map(lambda en: en[0] ** en[1]),
        # negative integer and half-integer powers of a base that cannot vanish
        st.tuples(children, st.integers(-3, -1)).map(lambda en: _positive(en[0]) ** en[1]),
        st.tuples(children, st.sampled_from([-3, -1, 1, 3, 5])).map(
            lambda ek: _positive(ek[0]) ** sp.Rational(ek[1], 2)
        ),
        children.map(lambda e: _positive(e) ** sp.Rational(1, 3)),  # a general real power
        children.map(sp.sin),
        children.map(sp.cos),
        children.map(sp.atan),
        children.map(sp.tanh),
        children.map(lambda e: sp.exp(sp.sin(e))),
        children.map(lambda e: sp.log(_positive(e))),
        children.map(lambda e: sp.sec(sp.tanh(e))),  # rewritten as 1/cos
    )


EXPRESSIONS = st.recursive(
    st.sampled_from(STATE) | st.sampled_from([sp.Integer(3), sp.Rational(-1, 3), sp.pi]),
    _extend,
    max_leaves=8,
)
COMPONENT = st.one_of(st.just(0.0), st.floats(-2.0, 2.0, allow_nan=False, width=64))


def _taylor_coefficients(expression: sp.Expr, start) -> np.ndarray:
    """heyoka's Taylor coefficients of z in x' = c, z' = f(x) after one step from (start, 0)."""
    import heyoka as hy

    names = [*(f"s{i}" for i in range(len(STATE))), "z"]
    variables = hy.make_vars(*names)
    table = dict(zip(STATE, variables[:-1], strict=True))
    system = [(v, hy.expression(c)) for v, c in zip(variables, VELOCITY, strict=False)]
    system.append((variables[-1], to_heyoka(expression, table)))
    ta = hy.taylor_adaptive(system, [*start, 0.0])
    ta.step(write_tc=True)
    return np.array(ta.tc[-1])


def _reference(expression: sp.Expr, start) -> tuple[float, float]:
    """f(x0) and 1/2 grad f(x0) . c, evaluated by sympy at REFERENCE_DIGITS digits."""
    point = {s: sp.Float(v, REFERENCE_DIGITS) for s, v in zip(STATE, start, strict=True)}
    value = expression.evalf(REFERENCE_DIGITS, subs=point)
    slope = sum(
        sp.diff(expression, s).evalf(REFERENCE_DIGITS, subs=point) * c
        for s, c in zip(STATE, VELOCITY, strict=True)
    )
    return float(value), float(slope) / 2


@settings(max_examples=N_EXAMPLES)
@given(expression=EXPRESSIONS, start=st.tuples(COMPONENT, COMPONENT, COMPONENT))
def test_translation_matches_sympy_at_random_states(expression, start):
    value, half_slope = _reference(expression, start)
    if not (math.isfinite(value) and math.isfinite(half_slope)):
        return  # an overflowing draw (nested large powers) has nothing to compare
    tc = _taylor_coefficients(expression, start)
    assert np.all(np.isfinite(tc)), f"non-finite Taylor coefficients of {expression} at {start}"
    assert tc[1] == pytest.approx(value, rel=TRANSLATION_RTOL, abs=TRANSLATION_RTOL)
    assert tc[2] == pytest.approx(
        half_slope, rel=TRANSLATION_RTOL, abs=TRANSLATION_RTOL * max(1.0, abs(value))
    )


@pytest.mark.parametrize(
    "expression",
    [
        STATE[0] ** 3,
        STATE[0] ** 2,
        STATE[0] ** 7 - STATE[1] ** 4,
        STATE[0] ** sp.Float(3.0),  # integer-valued float exponent from user input
        STATE[0] ** 3 * _positive(STATE[1]) ** sp.Rational(3, 2),
    ],
    ids=str,
)
def test_integer_powers_are_finite_at_a_zero_base(expression):
    """Regression (issue 9.3): a float pow made every x**n NaN at x = 0."""
    tc = _taylor_coefficients(expression, (0.0, 0.0, -1.0))
    value, half_slope = _reference(expression, (0.0, 0.0, -1.0))
    assert np.all(np.isfinite(tc))
    assert tc[1] == pytest.approx(value, abs=TRANSLATION_RTOL)
    assert tc[2] == pytest.approx(half_slope, abs=TRANSLATION_RTOL)


def test_powers_become_products_reciprocals_and_square_roots():
    import heyoka as hy

    x = sp.Symbol("x")
    var = hy.make_vars("x")
    assert "**" not in str(to_heyoka(x**5, {x: var}))
    # x * sqrt(x) (heyoka 7 prints its sqrt as **0.5), not the power 1.5
    assert "1.5" not in str(to_heyoka(x ** sp.Rational(3, 2), {x: var}))
    reciprocal = str(to_heyoka(x**-3, {x: var}))
    assert "-1" in reciprocal and "3" not in reciprocal  # 1/(x*x*x), not x**-3
    assert str(to_heyoka(x ** sp.Rational(-1, 2), {x: var})) == str(hy.sqrt(var) ** -1.0)


def test_unsupported_functions_name_the_alternatives():
    import heyoka as hy

    x = sp.Symbol("x")
    with pytest.raises(InvalidParameterError, match="heyoka implements only.*scipy"):
        to_heyoka(sp.Abs(x), {x: hy.make_vars("x")})


#: Rayleigh parameter: a clearly nonlinear damping with a limit cycle of amplitude ~2.
RAYLEIGH_EPS = sp.Rational(1, 2)

#: Agreement of heyoka (eps) and DOP853 (rtol 1e-12) over RAYLEIGH_HORIZON: DOP853's global error
#: grows ~1e-12 per unit time on this unit-frequency cycle, ~3e-11 over 30; 1e-9 leaves margin.
RAYLEIGH_AGREEMENT = 1e-9
RAYLEIGH_HORIZON = 30.0


def test_rayleigh_oscillator_integrates_from_rest_with_heyoka():
    """x'' + x = eps (x' - x'**3 / 3) from x'(0) = 0 (issue 9.3: heyoka failed at once)."""
    x, v = sp.symbols("x v")
    rayleigh = SymbolicRHS((x, v), (v, -x + RAYLEIGH_EPS * (v - v**3 / 3)))
    t = np.linspace(0.0, RAYLEIGH_HORIZON, 61)
    taylor = Heyoka().integrate(rayleigh, (0.0, RAYLEIGH_HORIZON), [1.0, 0.0], t_eval=t)
    assert taylor.success, taylor.message
    dop = Scipy("DOP853").integrate(rayleigh, (0.0, RAYLEIGH_HORIZON), [1.0, 0.0], t_eval=t)
    np.testing.assert_allclose(taylor.y, dop.y, rtol=0, atol=RAYLEIGH_AGREEMENT)
