"""The symbolic Jacobian and variational equations of a SymbolicRHS are kept on disk, per field."""

import pytest
import sympy as sp

import perturb.cache
import perturb.errors
from perturb.cache import bypassed
from perturb.oracle import SymbolicRHS

x, v = sp.symbols("x v")
DUFFING = ((x, v), (v, -x - x**3))


def _count(cache_folder, kind):
    return len(list(cache_folder.glob(f"{kind}-*.pkl")))


def test_jacobian_is_read_back_for_an_equal_field(cache_folder, monkeypatch):
    first = SymbolicRHS(*DUFFING).jacobian_expressions
    assert _count(cache_folder, "jacobian") == 1
    monkeypatch.setattr(SymbolicRHS, "_derive_jacobian", lambda self: pytest.fail("recomputed"))
    again = SymbolicRHS(*DUFFING).jacobian_expressions  # a new object: nothing in memory
    assert again == first == sp.Matrix([[0, 1], [-1 - 3 * x**2, 0]])


def test_another_field_is_another_entry(cache_folder):
    duffing = SymbolicRHS(*DUFFING).jacobian_expressions
    softer = SymbolicRHS((x, v), (v, -x - sp.Rational(1, 3) * x**3)).jacobian_expressions
    assert softer != duffing
    assert softer[1, 0] == -1 - x**2
    renamed = SymbolicRHS((v, x), (x, -v - v**3)).jacobian_expressions  # same field, other state
    assert renamed == sp.Matrix([[0, 1], [-1 - 3 * v**2, 0]])
    assert _count(cache_folder, "jacobian") == 3


def test_variational_read_back_is_the_same_system(cache_folder, monkeypatch):
    first = SymbolicRHS(*DUFFING).variational
    assert _count(cache_folder, "variational") == 1
    monkeypatch.setattr(SymbolicRHS, "_derive_variational", lambda self: pytest.fail("recomputed"))
    again = SymbolicRHS(*DUFFING).variational
    assert again == first  # the same dummies Phi, the same expressions
    assert again([1.0, 0.5, 1.0, 0.0, 0.0, 1.0]).tolist() == first([1.0, 0.5, 1, 0, 0, 1]).tolist()


def test_variational_from_disk_equals_a_fresh_derivation(cache_folder):
    stored = SymbolicRHS(*DUFFING).variational
    with bypassed():
        fresh = SymbolicRHS(*DUFFING).variational
    assert _count(cache_folder, "variational") == 1
    rename = dict(zip(fresh.state, stored.state, strict=True))  # fresh dummies are new ones
    assert tuple(e.xreplace(rename) for e in fresh.expressions) == stored.expressions


def test_a_corrupt_entry_is_recomputed(cache_folder):
    expected = SymbolicRHS(*DUFFING).jacobian_expressions
    (entry,) = cache_folder.glob("jacobian-*.pkl")
    entry.write_bytes(b"perturb-cache\n" + bytes(64))
    with pytest.warns(perturb.errors.CacheWarning, match="recomputed"):
        assert SymbolicRHS(*DUFFING).jacobian_expressions == expected
