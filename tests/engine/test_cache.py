"""The disk cache returns what was computed, survives corrupt entries and can be switched off."""

import contextlib

import pytest
import sympy as sp

import perturb.cache
from perturb import EPS, PoincareMethod, QuasilinearSystem
from perturb.cache import cache_dir
from perturb.errors import CacheWarning

x, xd, A = sp.symbols("x xdot A")
SYSTEM = QuasilinearSystem([x], [xd], [1], [-EPS * x**3], parameters=[A])


def test_second_solve_reads_the_same_solution(tmp_path, monkeypatch):
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    first = PoincareMethod(order=2, amplitudes={"x": A}).solve(SYSTEM)
    files = list(tmp_path.glob("solution-*.pkl"))
    assert len(files) == 1
    second = PoincareMethod(order=2, amplitudes={"x": A}).solve(SYSTEM)
    assert second is not first  # read back from disk ...
    assert sp.expand(second.coordinate("x") - first.coordinate("x")) == 0  # ... and equal
    assert second.frequency == first.frequency
    # a different option is a different entry
    PoincareMethod(order=1, amplitudes={"x": A}).solve(SYSTEM)
    assert len(list(tmp_path.glob("solution-*.pkl"))) == 2


def test_corrupt_entry_is_recomputed(tmp_path, monkeypatch):
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(perturb.cache, "_WARNED", set())
    PoincareMethod(order=1, amplitudes={"x": A}).solve(SYSTEM)
    (entry,) = tmp_path.glob("solution-*.pkl")
    entry.write_bytes(b"not a pickle")
    with pytest.warns(CacheWarning, match="recomputed"):
        sol = PoincareMethod(order=1, amplitudes={"x": A}).solve(SYSTEM)
    assert sol.success and sol.frequency[1] == sp.Rational(3, 8) * A**2


def test_cache_can_be_switched_off(tmp_path, monkeypatch):
    monkeypatch.setenv("PERTURB_CACHE_DIR", "off")
    assert cache_dir() is None
    assert PoincareMethod(order=1, amplitudes={"x": A}).solve(SYSTEM).success
    assert not list(tmp_path.iterdir())


def test_bypassed_computes_afresh_and_leaves_the_cache_alone(tmp_path, monkeypatch):
    from perturb.cache import bypassed, cached

    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    calls = []
    assert cached("demo", ("k",), lambda: calls.append(1) or "stored") == "stored"
    entries = sorted(p.name for p in tmp_path.iterdir())
    with bypassed():
        assert cached("demo", ("k",), lambda: calls.append(2) or "fresh") == "fresh"
    assert calls == [1, 2]  # the bypassed call computed although an entry exists ...
    assert sorted(p.name for p in tmp_path.iterdir()) == entries  # ... and wrote nothing
    assert cached("demo", ("k",), lambda: "not called") == "stored"


@pytest.mark.parametrize("setting", ["off", "bypassed"])
def test_no_key_is_built_when_the_cache_is_not_used(tmp_path, monkeypatch, setting):
    """The solution's key (srepr of the whole system) costs time; a run without the cache skips it."""
    from perturb.cache import active, bypassed

    monkeypatch.setenv("PERTURB_CACHE_DIR", "off" if setting == "off" else str(tmp_path))
    keys = []
    original = PoincareMethod._cache_key
    monkeypatch.setattr(
        PoincareMethod, "_cache_key", lambda self, s: keys.append(1) or original(self, s)
    )
    with bypassed() if setting == "bypassed" else contextlib.nullcontext():
        assert not active()
        assert PoincareMethod(order=1, amplitudes={"x": A}).solve(SYSTEM).success
    assert keys == []
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    assert active()
    PoincareMethod(order=1, amplitudes={"x": A}).solve(SYSTEM)
    assert keys == [1]  # the cache in use: the key is built


def test_a_key_given_as_a_function_is_built_only_when_the_cache_is_used(tmp_path, monkeypatch):
    from perturb.cache import bypassed, cached

    built = []

    def parts():
        built.append(1)
        return ("k",)

    monkeypatch.setenv("PERTURB_CACHE_DIR", "off")
    assert cached("demo", parts, lambda: "off") == "off" and built == []
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    with bypassed():
        assert cached("demo", parts, lambda: "bypassed") == "bypassed" and built == []
    assert cached("demo", parts, lambda: "stored") == "stored" and built == [1]
    # the function's key and the same tuple name one entry
    assert cached("demo", ("k",), lambda: "not called") == "stored"


def test_a_value_that_depends_on_the_run_is_returned_not_kept(tmp_path, monkeypatch):
    """A solve cut by its time budget (Uncached) is computed again next time: a loaded machine's
    spent budget must not become every later run's answer."""
    monkeypatch.setenv("PERTURB_CACHE_DIR", str(tmp_path))
    calls = []

    def spent():
        calls.append("spent")
        return perturb.cache.Uncached(([], "the budget was spent"))

    def solved():
        calls.append("solved")
        return ([1.0], "")

    parts = ("a system",)
    assert perturb.cache.cached("budget-test", parts, spent) == ([], "the budget was spent")
    assert perturb.cache.cached("budget-test", parts, solved) == ([1.0], "")
    assert perturb.cache.cached("budget-test", parts, spent) == ([1.0], "")  # now kept
    assert calls == ["spent", "solved"]
