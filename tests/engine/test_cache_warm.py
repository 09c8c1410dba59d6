"""A warm read of the cache gives what a cold derivation gives, and a changed input misses it.

The cache keeps sympy's sums, products and powers as their canonical arguments (read back without
evaluating them again) and a system's content digest with the system (its key is not printed
again): both are shortcuts of the warm path, so here each is held against the long way.
"""

import pickle

import pytest
import sympy as sp

import perturb.cache
import perturb.method.poincare
from perturb import EPS, PoincareMethod, QuasilinearSystem
from perturb.cache import cached

x, xd, A, k = sp.symbols("x xdot A k")
SYSTEM = QuasilinearSystem([x], [xd], [1], [-EPS * x**3], parameters=[A])
VDP = QuasilinearSystem([x], [xd], [1], [EPS * (1 - x**2) * xd])


def _expressions():
    """Sums, products and powers of every kind the engine stores, nested."""
    a, b = sp.symbols("a b", positive=True)
    p, q = sp.symbols("p q", commutative=False)
    return [
        sp.Rational(3, 8) * A**2 * EPS - sp.Rational(21, 256) * A**4 * EPS**2 + 1,
        sp.cos(2 * x) * sp.sqrt(a + b) / (1 + x**2) ** sp.Rational(3, 2),
        sp.exp(-x * a) * sp.sin(x) ** 3 - sp.I * sp.pi * b,
        p * q - q * p + 2 * p**2,  # non-commutative products keep their order
        sp.Float("0.1", 30) * x + sp.Float(2.5) * x**-1,
        sp.Add(x, x, evaluate=False),  # stored unevaluated, read back as stored
        sp.Pow(2, 3, evaluate=False) * sp.Mul(x, 1, evaluate=False),
        sp.ImmutableMatrix([[x * a, x + b], [x**a, 1 / x]]),
        sp.Matrix([[x * a + b**2, sp.sin(x) / a], [x**-a, 3 * x * b]]),  # mutable: not hashed
    ]


def test_expressions_read_back_equal_and_identically_built(cache_folder):
    stored = _expressions()
    assert cached("demo", ("exprs",), lambda: stored) == stored  # written
    read = cached("demo", ("exprs",), lambda: "not called")
    assert read is not stored
    for before, after in zip(stored, read, strict=True):
        assert after == before
        assert sp.srepr(after) == sp.srepr(before)
        if not isinstance(before, sp.MutableDenseMatrix):
            assert hash(after) == hash(before)
        if isinstance(before, sp.MatrixBase):
            assert (after - before).is_zero_matrix
        else:
            assert after.is_commutative == before.is_commutative
            assert sp.expand(after - before) == 0  # usable: arithmetic still evaluates


def test_sums_come_back_as_stored_not_evaluated_again(cache_folder):
    """What the entry holds re-creates sums and products from their arguments, never by
    evaluating them: a sum whose evaluation would change it comes back unchanged."""
    unevaluated = sp.Add(x, x, evaluate=False)
    assert pickle.loads(pickle.dumps(unevaluated)) == 2 * x  # sympy's own pickle evaluates
    cached("demo", ("sum",), lambda: unevaluated)
    read = cached("demo", ("sum",), lambda: "not called")
    assert read.args == (x, x)


def _solution_facts(solution):
    return (
        solution.status,
        solution.frequency,
        [sp.srepr(solution.coordinate(name)) for name in solution.system.state_names[:1]],
        solution.frequency_series(),
    )


def test_a_warm_solution_is_the_cold_one(cache_folder):
    for system, options in ((SYSTEM, {"amplitudes": {"x": A}}), (VDP, {})):
        method = PoincareMethod(order=2, **options)
        cold = method.solve(system)  # derived and written
        warm = method.solve(system)  # read back
        fresh = PoincareMethod(order=2, cache=False, **options).solve(system)
        assert warm is not cold
        assert _solution_facts(warm) == _solution_facts(cold) == _solution_facts(fresh)
        assert warm.system == system
        assert warm.system.content_digest == system.content_digest


def test_the_content_digest_is_kept_through_a_pickle_and_follows_the_equations():
    system = QuasilinearSystem([x], [xd], [1], [-EPS * k * x**3], parameters=[k])
    digest = system.content_digest
    read = pickle.loads(pickle.dumps(system))
    assert read == system
    assert object.__getattribute__(read, "content_digest") == digest  # carried, not recomputed
    rebuilt = QuasilinearSystem([x], [xd], [1], [-EPS * k * x**3], parameters=[k])
    assert rebuilt.content_digest == digest  # a function of the equations alone
    changed = [
        QuasilinearSystem([x], [xd], [1], [-EPS * k * x**5], parameters=[k]),
        QuasilinearSystem([x], [xd], [2], [-EPS * k * x**3], parameters=[k]),
        QuasilinearSystem([x], [xd], [1], [-EPS * k * x**3], parameters=[k], first_integrals=[x]),
        QuasilinearSystem([x], [xd], [1], [-EPS * x**3], parameters=[k]),
    ]
    assert len({digest, *(s.content_digest for s in changed)}) == 1 + len(changed)


def test_a_changed_system_or_option_misses_the_cache(cache_folder, monkeypatch):
    derived = []
    original = perturb.method.poincare._construct

    def counting(method, system):
        derived.append((method.order, system.rhs))
        return original(method, system)

    monkeypatch.setattr(perturb.method.poincare, "_construct", counting)
    method = PoincareMethod(order=1, amplitudes={"x": A})
    method.solve(SYSTEM)
    method.solve(SYSTEM)
    assert len(derived) == 1  # the second is read back
    quintic = QuasilinearSystem([x], [xd], [1], [-EPS * x**5], parameters=[A])
    solution = method.solve(quintic)
    assert len(derived) == 2  # another right-hand side: derived, not read
    assert solution.frequency[1] == sp.Rational(5, 16) * A**4
    PoincareMethod(order=2, amplitudes={"x": A}).solve(SYSTEM)
    assert len(derived) == 3  # another order
    renamed = QuasilinearSystem([x], [xd], [1], [-EPS * x**3], parameters=[A], name="other")
    PoincareMethod(order=1, amplitudes={"x": A}).solve(renamed)
    assert len(derived) == 4  # another name (it is printed in the solution)


def test_an_entry_of_the_previous_format_is_not_read(cache_folder, monkeypatch):
    """Entries written before sums were kept as arguments are stale: recomputed, not misread."""
    current = perturb.cache.CACHE_FORMAT
    perturb.cache._environment.cache_clear()
    monkeypatch.setattr(perturb.cache, "CACHE_FORMAT", current - 1)
    try:
        cached("demo", ("old",), lambda: "old format")
    finally:
        monkeypatch.setattr(perturb.cache, "CACHE_FORMAT", current)
        perturb.cache._environment.cache_clear()
    assert len(list(cache_folder.glob("demo-*.pkl"))) == 1
    assert cached("demo", ("old",), lambda: "recomputed") == "recomputed"  # keyed apart: a miss
    assert cached("demo", ("old",), lambda: "not called") == "recomputed"


def _forced_map(sigma_of: str = "(Omega - 1)/eps"):
    from perturb.case import ParameterMap

    sigma, zeta = sp.symbols("sigma zeta")
    return ParameterMap.declare([sigma, zeta], ["eps", "zeta", "Omega"], {"sigma": sigma_of})


def test_a_parameter_map_moves_epsilon_alike_warm_and_cold(cache_folder):
    point = {"eps": 0.05, "zeta": 0.1, "Omega": 1.1}
    with perturb.cache.bypassed():
        expected = [_forced_map().with_epsilon(point, e) for e in (0.025, 0.1)]
    from perturb.case import parameters

    parameters._solve_move_cached.cache_clear()
    cold = [_forced_map().with_epsilon(point, e) for e in (0.025, 0.1)]  # moves kept on disk
    assert len(list(cache_folder.glob("parameter-moves-*.pkl"))) == 1
    assert len(list(cache_folder.glob("parameter-move-*.pkl"))) == 1  # the move solved, kept
    parameters._solve_move_cached.cache_clear()  # as in a new process
    warm = [_forced_map().with_epsilon(point, e) for e in (0.025, 0.1)]  # a new map: read back
    assert len(list(cache_folder.glob("parameter-move-*.pkl"))) == 1
    assert cold == warm == expected
    assert expected[0] == {"eps": 0.025, "zeta": 0.1, "Omega": pytest.approx(1.05, rel=1e-12)}
    # another expression of sigma: its own entry, and its own move (Omega = sigma * eps)
    other = _forced_map("Omega/eps").with_epsilon(point, 0.025)
    assert len(list(cache_folder.glob("parameter-moves-*.pkl"))) == 2
    assert other["Omega"] == pytest.approx(point["Omega"] * 0.025 / 0.05, rel=1e-12)


def test_a_bounded_kind_keeps_its_most_recently_written_entries(cache_folder):
    def entries():
        return {p.name: p.stat().st_mtime_ns for p in cache_folder.glob("bounded-*.pkl")}

    cached("bounded", ("a",), lambda: "a", keep=2)
    (first,) = entries()
    cached("bounded", ("b",), lambda: "b", keep=2)
    before = entries()
    assert cached("bounded", ("a",), lambda: "recomputed", keep=2) == "a"
    assert entries() == before  # a read leaves the entries as they are
    cached("bounded", ("c",), lambda: "c", keep=2)
    assert len(entries()) == 2 and first not in entries()  # the oldest written went
    assert cached("bounded", ("a",), lambda: "a again", keep=2) == "a again"
    assert cached("bounded", ("c",), lambda: "recomputed", keep=2) == "c"  # the newest stays
    cached("unbounded", ("x",), lambda: 1)
    assert len(list(cache_folder.glob("unbounded-*.pkl"))) == 1  # other kinds untouched


def test_a_generated_function_read_back_is_the_one_lambdify_generates(cache_folder):
    import inspect
    import re

    import numpy as np

    from perturb._lambdify import numpy_lambdify

    a, b = sp.symbols("a b")
    expr = [sp.sin(a) ** 2 * b + sp.sqrt(a * b) / 3, sp.exp(-a) * sp.cos(b) + a**7]
    point = (0.3, 1.7)
    with perturb.cache.bypassed():
        fresh = numpy_lambdify((a, b), expr, cse=True)
    cold = numpy_lambdify((a, b), expr, cse=True)
    warm = numpy_lambdify((a, b), expr, cse=True)
    assert len(list(cache_folder.glob("lambdified-*.pkl"))) == 1
    assert inspect.getsource(warm) == inspect.getsource(cold) == inspect.getsource(fresh)
    assert {k for k in warm.__globals__ if k != "__builtins__"} == {
        k for k in fresh.__globals__ if k != "__builtins__"
    }
    assert np.array_equal(warm(*point), fresh(*point))
    # another expression, or the same without cse, is generated again
    numpy_lambdify((a, b), expr[:1], cse=True)
    plain = numpy_lambdify((a, b), expr)
    assert len(list(cache_folder.glob("lambdified-*.pkl"))) == 3
    assert re.search(r"\bsin\(a\)", inspect.getsource(plain))


def test_a_generated_function_that_needs_more_names_is_generated_each_time(cache_folder):
    """An implemented function adds its own name to the function's globals: such a function
    is not rebuilt from its source (the name would be missing), it is generated again."""
    from sympy.utilities.lambdify import implemented_function

    from perturb._lambdify import numpy_lambdify

    a = sp.Symbol("a")
    twice = implemented_function("twice", lambda value: 2 * value)
    first = numpy_lambdify(a, twice(a) + 1)
    second = numpy_lambdify(a, twice(a) + 1)
    assert first(1.5) == second(1.5) == 4.0


def test_a_generated_function_of_a_matrix_keeps_the_symbols_lambdify_adds(cache_folder):
    """Of a single sympy object (a Matrix) lambdify puts its symbols in the function's globals,
    each under its name: the function read back has them too, the very same."""
    import numpy as np

    from perturb._lambdify import numpy_lambdify

    a, b, gamma = sp.symbols("a b gamma")  # gamma also names a numpy function
    matrix = sp.Matrix([[a * b, sp.sin(gamma)], [gamma**2, a - b]])
    args = ((a, b), (gamma,))
    with perturb.cache.bypassed():
        fresh = numpy_lambdify(args, matrix, cse=True)
    numpy_lambdify(args, matrix, cse=True)
    warm = numpy_lambdify(args, matrix, cse=True)
    entry = next(cache_folder.glob("lambdified-*.pkl"))
    assert entry.stat().st_size > 400  # a source was kept, not a refusal
    assert warm.__globals__["gamma"] is fresh.__globals__["gamma"] == gamma
    assert {k for k in warm.__globals__ if k != "__builtins__"} == {
        k for k in fresh.__globals__ if k != "__builtins__"
    }
    point = ((0.4, -1.2), (0.7,))
    assert np.array_equal(warm(*point), fresh(*point))


def test_the_digest_is_the_trees_whichever_parts_are_one_object():
    """A value built afresh shares its equal parts differently from one read back: one digest."""
    from perturb.cache import digest

    part = sp.sin(x) * A**2 + EPS * x**3
    copy = pickle.loads(pickle.dumps(part))
    assert copy == part and copy is not part
    assert digest((part, part)) == digest((part, copy)) == digest((copy, copy))
    assert digest((part, part)) != digest((part, part + 1))
    assert digest([part]) != digest((part,))  # a list and a tuple are generated differently
