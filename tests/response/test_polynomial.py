"""Polynomials compiled to arrays and to generated code: the same numbers as sympy's evaluation
(another route), gradients included, and the line specialisation equal to substituting it.

Tolerance: the compiled rows sum the same monomials as sympy's float evaluation in another order;
ROUNDING = 1e-12 relative to the sum of the terms' sizes covers that reordering for rows of a few
hundred terms of size O(1) (each addition rounds by 1.1e-16).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb.steady.polynomial import compile_polynomials

ROUNDING = 1e-12
X, Y, P, Q = sp.symbols("x y p q")
ROWS = [
    3 * X**3 * Y - sp.pi * X * P**2 + sp.Rational(1, 7) * Q - 2,
    X**2 * Y**2 * P * Q + 5 * Y**4 - sp.sqrt(2) * P,
    sp.S.Zero,
]
finite = st.floats(-3, 3, allow_nan=False)


@given(finite, finite, finite, finite)
def test_values_and_gradients_are_sympys(x, y, p, q):
    compiled = compile_polynomials(ROWS, [X, Y, P, Q])
    point = {X: x, Y: y, P: p, Q: q}
    values, gradient = compiled.values_and_gradient(np.array([x, y, p, q]))
    generated = compiled.function()(np.array([x, y, p, q]))
    for i, row in enumerate(ROWS):
        scale = 1 + sum(abs(float(t.xreplace(point))) for t in sp.Add.make_args(sp.expand(row)))
        assert values[i] == pytest.approx(float(row.xreplace(point)), abs=ROUNDING * scale)
        assert generated[0][i] == pytest.approx(values[i], abs=ROUNDING * scale)
        for j, v in enumerate((X, Y, P, Q)):
            exact = float(sp.diff(row, v).xreplace(point))
            assert gradient[i, j] == pytest.approx(exact, abs=10 * ROUNDING * scale)
            assert generated[1][i, j] == pytest.approx(gradient[i, j], abs=10 * ROUNDING * scale)


@given(finite, finite, finite)
def test_the_line_specialisation_is_the_substitution(x, y, lam):
    compiled = compile_polynomials(ROWS, [X, Y, P, Q])
    line = compiled.specialized({"q": 0.5}, {"p": (1.25, -0.75)})
    assert line.names == ("x", "y", "lam")
    for i, row in enumerate(ROWS):
        exact = row.xreplace({X: x, Y: y, P: 1.25 - 0.75 * lam, Q: 0.5})
        scale = 1 + abs(float(sp.expand(row).xreplace({X: abs(x), Y: abs(y), P: 3, Q: 1})))
        assert line.values(np.array([x, y, lam]))[i] == pytest.approx(
            float(exact), abs=10 * ROUNDING * scale
        )


def test_rows_that_are_not_polynomial_are_refused():
    assert compile_polynomials([sp.sqrt(X) + 1], [X]) is None
    assert compile_polynomials([X * sp.Symbol("unknown")], [X]) is None
    assert compile_polynomials([sp.I * X], [X]) is None
