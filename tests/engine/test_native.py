"""The native coefficient backend (perturb/native.py): symbols carried across, same results as sympy.

Regression tests for issue 12 (the algebra kernel on symengine, sympy at the edges, lazy imports).
"""

import os
import subprocess
import sys

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb import EPS, PoincareMethod, QuasilinearSystem, native
from perturb.trig import SympyRing, TrigPoly
from problems import get_problem

#: The tests that compare the two backends need symengine (the engine falls back to sympy without).
needs_symengine = pytest.mark.skipif(native.se is None, reason="symengine is not installed")

A, B = sp.symbols("A B")
KAPPA = sp.Symbol("kappa", positive=True)


def test_sympy_ground_types_are_pinned():
    """tests/conftest.py pins pure-Python ground types (python-flint would switch them)."""
    from sympy.external.gmpy import GROUND_TYPES

    assert GROUND_TYPES == "python"


@needs_symengine
def test_symbols_keep_their_assumptions_through_the_backend():
    conv = native.Converter(native.SymengineRing)
    expr = KAPPA**2 / 3 + A * KAPPA - sp.Rational(5, 7)
    back = conv.to_sympy(conv.to_native(expr))
    assert back == expr
    assert {s for s in back.free_symbols if s.name == "kappa"} == {KAPPA}


@needs_symengine
def test_symbols_sharing_a_name_stay_distinct():
    conv = native.Converter(native.SymengineRing)
    plain = sp.Symbol("kappa")
    expr = plain - KAPPA  # not zero: two different symbols
    value = conv.to_native(expr)
    assert value != 0
    assert conv.to_sympy(value) == expr
    assert conv.symbols(value) == {plain, KAPPA}


@needs_symengine
def test_floats_and_forced_sympy_choose_the_sympy_ring(monkeypatch):
    assert native.ring_for(A * sp.Float(0.5)) is SympyRing
    monkeypatch.setattr(native, "BACKEND", "sympy")
    assert native.ring_for(A) is SympyRing


coefficients = st.tuples(st.integers(-3, 3), st.integers(-3, 3), st.integers(1, 4)).map(
    lambda t: t[0] * A + sp.Rational(t[1], t[2]) * B * KAPPA
)
polys = st.dictionaries(st.integers(0, 4), st.tuples(coefficients, coefficients), max_size=3)


@needs_symengine
@given(polys, polys)
def test_native_product_equals_sympy_product(p, q):
    conv = native.Converter(native.SymengineRing)
    expected = TrigPoly(p) * TrigPoly(q)
    got = conv.trig(conv.native_poly(TrigPoly(p)) * conv.native_poly(TrigPoly(q)))
    assert got.terms == expected.terms  # identical, not merely equal after expand


def _record(solution):
    return (
        [[t.terms for t in row] for row in solution.terms],
        solution.frequency,
        solution.deviations,
        [(c.name, c.expression) for step in solution.steps for c in step.conditions],
    )


@needs_symengine
@pytest.mark.parametrize(("name", "order"), [("resonant-pair", 5), ("van-der-pol", 3)])
def test_native_and_sympy_backends_give_identical_solutions(monkeypatch, name, order):
    problem = get_problem(name).create()
    method = PoincareMethod(order=order, cache=False, **problem.method_options())
    fast = method.solve(problem.system())
    monkeypatch.setattr(native, "BACKEND", "sympy")
    slow = method.solve(problem.system())
    assert fast.success and slow.success
    assert _record(fast) == _record(slow)


def test_symbolic_frequency_and_assumptions_survive_a_native_run():
    """Duffing with symbolic amplitude and stiffness: Omega_1 = 3 k a^2 / 8, symbols as given."""
    x, xd = sp.symbols("x xd")
    a = sp.Symbol("a", positive=True)
    system = QuasilinearSystem([x], [xd], [1], [-EPS * KAPPA * x**3], parameters=[KAPPA, a])
    solution = PoincareMethod(order=1, amplitudes={"x": a}, cache=False).solve(system)
    assert solution.frequency[1] == 3 * KAPPA * a**2 / 8


def test_import_and_help_load_neither_sympy_nor_numpy():
    code = (
        "import sys, perturb, perturb.cli\n"
        "heavy = [m for m in ('sympy', 'numpy', 'symengine', 'scipy') if m in sys.modules]\n"
        "print(','.join(heavy))\n"
    )
    env = dict(os.environ)
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env
    )
    assert out.stdout.strip() == ""
    help_run = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "perturb", "--help"],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    )
    imported = {line.split("|")[-1].strip() for line in help_run.stderr.splitlines()}
    assert not imported & {"sympy", "numpy", "symengine", "scipy"}


@needs_symengine
def test_what_symengine_cannot_hold_is_refused_and_the_run_redone_in_sympy(monkeypatch):
    x = sp.Symbol("x")
    with pytest.raises(native.NotNative):
        native.Converter(native.SymengineRing).to_native(sp.CRootOf(x**5 - x - 1, 0))

    problem = get_problem("resonant-pair").create()
    method = PoincareMethod(order=3, cache=False, **problem.method_options())
    expected = method.solve(problem.system())

    plain_mapping = native.Converter.mapping

    def refuse(self, mapping):  # as if a solver had returned a CRootOf
        if self.native:
            raise native.NotNative("CRootOf")
        return plain_mapping(self, mapping)

    monkeypatch.setattr(native.Converter, "mapping", refuse)
    redone = method.solve(problem.system())
    assert redone.success
    assert _record(redone) == _record(expected)


@needs_symengine
@pytest.mark.parametrize(
    ("expr", "floating"),
    [
        (sp.Float(1.5) * A, True),
        (A + sp.Float(0.25), True),
        (sp.sqrt(A) * sp.Float(2.0) * B**2, True),
        (sp.Rational(3, 2) * A, False),
        (sp.sqrt(2) * A + sp.pi, False),
    ],
)
def test_both_rings_see_a_float_wherever_it_sits(expr, floating):
    """Float inputs must be noticed (they keep a run on sympy's float arithmetic), exact ones not."""
    conv = native.Converter(native.SymengineRing)
    assert native.SymengineRing.has_float(conv.to_native(expr)) is floating
    assert SympyRing.has_float(expr) is floating
