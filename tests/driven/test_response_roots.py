"""The response equations go through the certified solver of the free systems (issue 22, item 5):
every branch at every value, each root certified in every coordinate.

Before, a lexicographic basis was back-substituted in floats, and a double root at zero of a later
variable (a mode at rest) came out of ``np.roots`` with an imaginary part and was dropped: the
autoparametric absorber's single-mode response was lost at most excitation frequencies off 2.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from perturb.response.model import problem_response
from perturb.steady.roots import real_roots
from problems import get_problem

AX, BX, AY, BY = sp.symbols("a_x b_x a_y b_y")


def test_a_mode_at_rest_is_a_root_not_a_lost_one():
    """The absorber's response equations at sigma = -22 (Omega = 0.9, eps = 0.05), with the common
    factor pi: x at rest solves the first two; the last two are then linear, so the root is known
    by hand, exactly."""
    pi = sp.pi
    eqs = [
        pi * AX * BY - pi * AX / 5 - pi * AY * BX + 22 * pi * BX,
        -pi * AX * AY - 22 * pi * AX - pi * BX * BY - pi * BX / 5,
        pi * AX * BX / 2 - pi * AY / 5 + 44 * pi * BY,
        -pi * AX**2 / 4 - 44 * pi * AY + pi * BX**2 / 4 - pi * BY / 5 + pi / 2,
    ]
    by = sp.Rational(1, 2) / (44 * 220 + sp.Rational(1, 5))  # a_y = 220 b_y from the third
    found = real_roots(eqs, [AX, BX, AY, BY])
    assert found.status.name == "SOLVED"
    assert list(found.exact) == [{AX: 0, BX: 0, AY: 220 * by, BY: by}]


def _linear_amplitude(eps, force, zeta, omega2, omega):
    """|y| of y'' + omega2^2 y = eps (-2 zeta y' + F cos(Omega t)): the exact steady state."""
    return eps * force / np.hypot(omega2**2 - omega**2, 2 * eps * zeta * omega)


def test_the_absorber_responds_at_every_frequency():
    """Off the saturation band the only response is the forced mode alone (x at rest): it is there
    at every grid point, and its amplitude is the linear oscillator's to within the first order
    left out (relative eps: C = 1)."""
    problem = get_problem("autoparametric-absorber").create(Omega=2.0)
    grid = np.linspace(1.8, 2.2, 5)
    response = problem_response(problem, "Omega", grid, order=1).response
    assert not response.failures
    v, eps = problem.values, problem.epsilon()
    for omega in grid:
        alone = [p for p in response.points if p.value == omega and p.norms["x"] == 0]
        assert len(alone) == 1, omega
        exact = _linear_amplitude(eps, v["F"], v["zeta2"], 2 + eps * v["delta"], omega)
        assert alone[0].norms["y"] == pytest.approx(exact, rel=eps)


def test_the_absorbers_folds_are_the_coupled_branchs_turns():
    """Two folds, where the coupled branches (x moving) are born in pairs; the points where x starts
    to move off the single-mode branch are branch points (reported by stability), not folds, and a
    fold is not listed twice for the response shifted by one forcing period."""
    problem = get_problem("autoparametric-absorber").create(Omega=2.0)
    grid = np.linspace(1.9, 2.1, 11)
    response = problem_response(problem, "Omega", grid, order=1).response
    assert len(response.folds) == 2
    coupled = {}
    for p in response.points:
        if p.norms["x"] > 0:
            coupled[p.value] = coupled.get(p.value, 0) + 1
    for fold in response.folds:
        assert fold.norms["x"] > 0
        # the branches at each grid value are the order-N ones (continued through the folds):
        # their number changes across the order-N fold, located on the order-N curve
        below = max(g for g in grid if g < fold.value)
        above = min(g for g in grid if g > fold.value)
        assert coupled.get(below, 0) != coupled.get(above, 0)
        assert abs(fold.value - fold.first_order) <= problem.epsilon()  # moved by O(eps)
