"""The certified real-root solver (issue 22): counts known by hand, proofs of no root, budgets.

Every expected count below is derived by hand in the test's docstring, never taken from the code
under test; exact roots are checked by putting them back into the equations.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from perturb import EPS, PoincareMethod, QuasilinearSystem, Status
from perturb.algebra import (
    RootStatus,
    SystemSize,
    certified_real_roots,
    exact_real_roots,
    msolve_binary,
)
from perturb.errors import InvalidSystemError

x, y, z = sp.symbols("x y z")
BACKENDS = ["sympy"] + (["msolve"] if msolve_binary() else [])


def _solve(eqs, unknowns, backend):
    return certified_real_roots(eqs, unknowns, seconds=60, backend=backend)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize(
    ("eqs", "unknowns", "count"),
    [
        # circle and diagonal: x = y = ±1/sqrt(2)
        ([x**2 + y**2 - 1, x - y], [x, y], 2),
        # y = x^2 on x^3 = x: x in {-1, 0, 1}
        ([x**3 - x, y - x**2], [x, y], 3),
        # x^2 = 2, y^2 = 3: four sign choices (a lex basis not in shape position)
        ([x**2 - 2, y**2 - 3], [x, y], 4),
        # (x - 1)^2 (x + 2) = 0 with y = x: the double root counts once
        ([(x - 1) ** 2 * (x + 2), y - x], [x, y], 2),
        # x^2 + y^2 = 4, x y = 1: t = x^2 solves t^2 - 4t + 1 = 0, t = 2 ± sqrt(3) > 0, so 4 roots
        ([x**2 + y**2 - 4, x * y - 1], [x, y], 4),
        # a linear unknown z (pivot) with a cubic: x^3 - 2 = 0 has one real root
        ([z - x**2 - 1, x**3 - 2], [z, x], 1),
    ],
)
def test_real_root_counts_known_by_hand(eqs, unknowns, count, backend):
    found = _solve(eqs, unknowns, backend)
    assert found.status is RootStatus.SOLVED, found.message
    assert len(found.roots) == count
    assert len(found.certificates) == count
    for root in found.roots:
        residual = max(abs(float(sp.sympify(e).xreplace(root))) for e in eqs)
        assert residual < 1e-9


def test_exact_roots_vanish_exactly():
    eqs = [x**2 - 2, y**2 - 3]
    found = exact_real_roots(eqs, [x, y])
    assert sorted((float(r[x]), float(r[y])) for r in found.exact) == sorted(
        (sx * 2**0.5, sy * 3**0.5) for sx in (-1, 1) for sy in (-1, 1)
    )
    for root in found.exact:
        assert all(sp.simplify(e.xreplace(root)) == 0 for e in eqs)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize(
    "eqs",
    [
        [x**2 + 1],  # no real root
        [x**2 + y**2 - 1, x * y - 1],  # x^2 + 1/x^2 >= 2 > 1: no real root
        [x - 1, x - 2],  # no root at all: the basis is {1}
    ],
)
def test_no_real_root_is_proved(eqs, backend):
    unknowns = sorted(set().union(*(e.free_symbols for e in eqs)), key=str)
    found = _solve(eqs, unknowns, backend)
    assert found.status is RootStatus.NO_REAL_ROOT and found.status.success


def test_a_continuum_is_reported_with_its_dimension_and_free_unknowns():
    found = exact_real_roots([x * y, x * z], [x, y, z])  # the plane x = 0 and the line y = z = 0
    assert found.status is RootStatus.POSITIVE_DIMENSIONAL
    assert found.dimension == 2 and set(found.free) == {y, z}


def test_a_budget_spent_is_reported_with_the_size_of_the_system():
    rng = np.random.default_rng(22)
    unknowns = sp.symbols("u0:7")
    monomials = [m for m in sp.itermonomials(unknowns, 3)]
    eqs = [
        sum(int(rng.integers(-9, 10)) * m for m in monomials if rng.random() < 0.5) + 1
        for _ in unknowns
    ]
    found = certified_real_roots(eqs, unknowns, seconds=0.5, backend="sympy")
    assert found.status is RootStatus.BUDGET_EXCEEDED and not found.status.success
    assert "7 unknowns" in found.message and "0.5 s" in found.message
    assert found.size == SystemSize.of(eqs, unknowns)


def test_float_coefficients_are_refused():
    with pytest.raises(InvalidSystemError, match="rational coefficients"):
        certified_real_roots([x**2 - 0.5], [x], seconds=10)


def test_no_root_status_of_the_construction_is_a_proof():
    """x'' + x = eps (1 + x^2) x': the amplitude equation a (1 + a^2/4) = 0 has only a = 0."""
    xx, xd = sp.symbols("x xdot")
    system = QuasilinearSystem([xx], [xd], [1], [EPS * (1 + xx**2) * xd])
    solution = PoincareMethod(order=1, cache=False).solve(system)
    assert solution.status is Status.NO_ROOT
    assert "proved" in solution.message


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_continuum_beside_an_isolated_root_is_reported_with_both(backend):
    """a (a² + b² - 1) = b (a² + b² - 1) = 0, w = 3: the circle (dimension 1) and the isolated
    point a = b = 0. The pieces a = 0 and b = 0 also hold (0, ±1), (±1, 0): points of the circle,
    not isolated roots, so exactly one isolated root is reported."""
    a, b, w = sp.symbols("a b w")
    circle = a**2 + b**2 - 1
    found = certified_real_roots(
        [a * circle, b * circle, w - 3], [w, a, b], seconds=60, backend=backend
    )
    assert found.status is RootStatus.POSITIVE_DIMENSIONAL and not found.status.success
    assert [(d, len(free)) for d, free, _ in found.continua] == [(1, 1)]
    assert set(found.continua[0][1]) <= {a, b}
    assert [(r[a], r[b], r[w]) for r in found.roots] == [(0.0, 0.0, 3.0)]
    assert "dimension 1" in found.describe_continua()


def _two_duffings():
    """x'' + x = -eps x³, y'' + y = -eps y³ with x's amplitude 1: y = 0, or y on the circle
    a_y² + b_y² = 1 (every phase of an equal-amplitude y: a continuum)."""
    xx, yy, xd, yd = sp.symbols("x y xdot ydot")
    return QuasilinearSystem([xx, yy], [xd, yd], [1, 1], [-EPS * xx**3, -EPS * yy**3])


def test_a_continuum_sympy_cannot_write_in_time_is_undetermined_not_a_budget(monkeypatch):
    """Issue 22: a continuum is never reported as a timeout. sympy's solve is made to time out
    (as it does on large systems); the certified solver has proved the continuum, so the status
    is UNDETERMINED with its dimension and free amplitude, not SOLVER_BUDGET."""
    from perturb.method import conditions

    def times_out(*args, **kwargs):
        raise TimeoutError

    monkeypatch.setattr(conditions, "solve_bounded", times_out)
    solution = PoincareMethod(order=1, cache=False, amplitudes={"x": 1}).solve(_two_duffings())
    assert solution.status is Status.UNDETERMINED
    assert "continuum" in solution.message and "dimension 1" in solution.message


def test_the_family_machinery_says_continuum_when_it_runs_out_of_time(monkeypatch):
    from perturb.method import components
    from perturb.method.conditions import OrderFailed

    def times_out(*args, **kwargs):
        raise TimeoutError

    monkeypatch.setattr(components, "_grouped", times_out)
    a, b, w = sp.symbols("a b w")
    circle = a**2 + b**2 - 1
    with pytest.raises(OrderFailed) as failed:
        components.components_or_failed(1, [a * circle, b * circle, w - 3], [w, a, b], [a, b], 30)
    assert failed.value.status is Status.UNDETERMINED and "dimension 1" in str(failed.value)


def test_irrational_coefficients_are_refused():
    """The disk's amplitude equations carry sqrt(999999999951): not for the rational routes (the
    construction then goes on with sympy, as before)."""
    with pytest.raises(InvalidSystemError, match="rational coefficients"):
        certified_real_roots([x**2 - sp.sqrt(2) * x], [x], seconds=10)
