"""Exact trigonometric arithmetic against sympy's own trigonometric simplification."""

import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb.trig import TrigPoly

s = sp.Symbol("s")
small_int = st.integers(min_value=-3, max_value=3)


@st.composite
def trig_polys(draw):
    terms = {}
    for j in range(draw(st.integers(0, 3)) + 1):
        terms[j] = (draw(small_int), draw(small_int))
    return TrigPoly(terms)


@given(trig_polys(), trig_polys())
def test_product_is_the_linearised_product(p, q):
    expected = sp.expand(p.as_expr(s) * q.as_expr(s))
    got = (p * q).as_expr(s)
    assert sp.expand((expected - got).rewrite(sp.exp)) == 0


@given(trig_polys())
def test_derivative_and_value_at_zero(p):
    assert sp.expand(p.derivative().as_expr(s) - sp.diff(p.as_expr(s), s)) == 0
    assert p.at_zero() == p.as_expr(s).subs(s, 0)


def test_symbolic_coefficients_and_sign_of_difference_harmonics():
    a, b = sp.symbols("a b")
    p = TrigPoly({1: (a, 0)})
    q = TrigPoly({3: (0, b)})
    # cos(s) sin(3s) = [sin(4s) + sin(2s)]/2
    assert p * q == TrigPoly({4: (0, a * b / 2), 2: (0, a * b / 2)})
    assert q * p == p * q
