"""Coefficients of a right-hand side polynomial in ε (perturb.analytic.polynomial_coefficients).

The native route (symengine sorts the expanded terms by their power of ε) must give exactly what the
sympy route gives (``Poly(expand(f), eps).coeff_monomial(eps**k)``, expanded), and None exactly
where that route raises ``PolynomialError`` (issue 12: the disk's right-hand side took 0.3 s per
``Poly`` and three were built per system).
"""

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb import EPS, QuasilinearSystem, native
from perturb.analytic import polynomial_coefficients

X, Y = sp.symbols("x y")
KAPPA = sp.Symbol("kappa", positive=True)
KAPPA_PLAIN = sp.Symbol("kappa")  # same name, other assumptions: must stay a different symbol

needs_symengine = pytest.mark.skipif(native.se is None, reason="symengine is not installed")


def _sympy_route(expr):
    try:
        poly = sp.Poly(sp.expand(expr), EPS)
    except sp.PolynomialError:
        return None
    if poly.is_zero:
        return (sp.S.Zero,)
    return tuple(sp.expand(poly.coeff_monomial(EPS**k)) for k in range(poly.degree() + 1))


atoms = st.sampled_from(
    [X, Y, KAPPA, KAPPA_PLAIN, EPS, sp.Rational(-2, 3), sp.Integer(5), sp.sqrt(2), sp.sin(X)]
)
eps_breakers = st.sampled_from(
    [1 / (1 + EPS), sp.sqrt(EPS), sp.sin(EPS * X), 1 / EPS, sp.exp(EPS), EPS ** sp.Rational(3, 2)]
)


@st.composite
def expressions(draw, depth=3):
    if depth == 0 or draw(st.booleans()):
        return draw(atoms)
    left, right = draw(expressions(depth=depth - 1)), draw(expressions(depth=depth - 1))
    op = draw(st.sampled_from(["add", "mul", "pow", "div"]))
    if op == "add":
        return left + right
    if op == "mul":
        return left * right
    if op == "pow":
        return left ** draw(st.integers(0, 3))
    return left / draw(st.sampled_from([KAPPA, 1 + Y**2, sp.Integer(3)]))


@needs_symengine
@given(expressions(), st.one_of(st.none(), eps_breakers))
def test_native_route_equals_the_sympy_poly_route(expr, breaker):
    if breaker is not None:
        expr = expr + X * breaker
    assert polynomial_coefficients(expr, EPS) == _sympy_route(expr)


def test_symbols_come_back_with_their_assumptions():
    coefficients = polynomial_coefficients(EPS * KAPPA * X + EPS**2 * KAPPA_PLAIN, EPS)
    assert coefficients == (0, KAPPA * X, KAPPA_PLAIN)
    assert coefficients[2].free_symbols == {KAPPA_PLAIN}


def test_floats_keep_sympy_arithmetic():
    """A float input takes the sympy route (its precision is sympy's, as it always was)."""
    expr = EPS * sp.Float("0.1", 30) * X + EPS**2 * sp.Float(1) / 3
    assert polynomial_coefficients(expr, EPS) == _sympy_route(expr)


def test_the_system_reads_its_expansion_from_the_coefficients():
    system = QuasilinearSystem(
        [X], [Y], [1], [EPS**2 * X**3 + EPS * Y * X / (1 + KAPPA)], parameters=[KAPPA]
    )
    assert system.leading_order == 1
    assert system.expansion(3)[0] == (0, X * Y / (KAPPA + 1), X**3, 0)
