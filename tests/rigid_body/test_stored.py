"""The rigid body's derivations on disk: keyed by every input and source, refused when damaged."""

import secrets

import numpy as np
import pytest
import sympy as sp

import perturb.cache
from perturb.cache import bypassed
from perturb.errors import CacheWarning
from problems import get_problem
from problems.rigid_body import _body, _stored, equations, numeric, true_orbit
from problems.rigid_body.reduction import _reduce

PAPER = {
    "A": 9.0, "B": 11.0, "C": 20.0, "M": 200.0, "g": 1.5e-7, "R": 2000.0,
    "x0": 1.0, "y0": 6.0, "z0": 0.0, "r0": 1.3e-5, "gamma3_0": 7e-6,
}  # fmt: skip


def _entries(cache_folder, kind):
    return sorted(cache_folder.glob(f"{kind}-*.pkl"))


def _rhs(values):
    """The body's numeric rhs through the disk (the in-memory layer skipped)."""
    return _body._symbolic_rhs.__wrapped__(tuple(sorted(values.items())))[1]


def _fresh_rhs(values):
    with bypassed():
        return _rhs(values)


def test_a_body_reads_back_its_own_equations(cache_folder, monkeypatch):
    first = _rhs(PAPER)
    fresh = _fresh_rhs(PAPER)
    (entry,) = _entries(cache_folder, "body-rhs")
    written = entry.stat().st_mtime_ns

    def not_again(items):
        raise AssertionError("recomputed although an entry exists")

    monkeypatch.setattr(_body, "_rhs_with_values", not_again)
    assert _rhs(PAPER) == first == fresh
    assert entry.stat().st_mtime_ns == written  # read, not rewritten


@pytest.mark.parametrize("name", ["A", "B", "C", "M", "g", "R", "x0", "y0", "z0"])
def test_another_body_parameter_is_another_entry(cache_folder, name):
    _rhs(PAPER)
    other = {**PAPER, name: PAPER[name] + 0.5}
    assert _rhs(other) == _fresh_rhs(other) != _rhs(PAPER)
    assert len(_entries(cache_folder, "body-rhs")) == 2


def test_the_initial_state_does_not_enter_the_equations_key(cache_folder):
    _rhs(PAPER)
    assert _rhs({**PAPER, "r0": 30.2, "gamma3_0": 0.3}) == _rhs(PAPER)
    assert len(_entries(cache_folder, "body-rhs")) == 1


def test_an_edited_derivation_does_not_read_older_entries(cache_folder, monkeypatch):
    stored = _stored.stored("demo", ("equations.py",), (1,), lambda: "old")
    monkeypatch.setattr(_stored, "source_fingerprint", lambda names: "edited")
    assert stored == "old"
    assert _stored.stored("demo", ("equations.py",), (1,), lambda: "new") == "new"
    assert len(_entries(cache_folder, "demo")) == 2


def test_the_fingerprint_follows_the_sources():
    one = _stored.source_fingerprint(("equations.py",))
    assert one != _stored.source_fingerprint(("equations.py", "_body.py"))
    assert one != _stored.source_fingerprint(("_body.py",))


@pytest.mark.parametrize("damage", ["garbage", "truncated", "foreign"])
def test_a_damaged_or_foreign_entry_is_refused_and_recomputed(cache_folder, monkeypatch, damage):
    expected = _rhs(PAPER)
    (entry,) = _entries(cache_folder, "body-rhs")
    blob = entry.read_bytes()
    if damage == "garbage":
        entry.write_bytes(b"\x80\x04not a perturb entry")
    elif damage == "truncated":
        entry.write_bytes(blob[: len(blob) // 2])
    else:  # a well-formed entry signed with another key: a forgery to this user's perturb
        key = entry.name.removeprefix("body-rhs-").removesuffix(".pkl")
        entry.write_bytes(
            perturb.cache.encode("body-rhs", key, ("forged",), secrets.token_bytes(32))
        )
    with pytest.warns(CacheWarning, match="recomputed"):
        assert _rhs(PAPER) == expected


def test_the_body_potential_and_dimensional_expressions_read_back_equal(cache_folder):
    potential = equations.body_potential.__wrapped__(2)
    expressions = numeric._dimensional_expressions.__wrapped__()
    assert (
        len(_entries(cache_folder, "body-potential"))
        == len(_entries(cache_folder, "body-dimensional"))
        == 1
    )
    assert equations.body_potential.__wrapped__(2) == potential == equations._body_potential(2)
    again = numeric._dimensional_expressions.__wrapped__()
    assert again == expressions == numeric._derive_dimensional()


def _conditioning():
    x = sp.Rational(1, 3)
    return (x, 2 * x, 30, 1, 0, sp.Rational(7, 10**6)), (1e-3, 1e-3, 30.2, 1, 1, 1), 1e-9


def test_the_conditioned_equations_are_keyed_by_every_input(cache_folder):
    problem = get_problem("disk").create(r0=30.2)
    ref, scales, lam = _conditioning()
    first = true_orbit._conditioned_rhs(problem, ref, scales, lam, bits=113)
    assert true_orbit._conditioned_rhs(problem, ref, scales, lam, bits=113) == first
    assert len(_entries(cache_folder, "true-orbit-rhs")) == 1
    variants = [
        (problem, ref, scales, lam, 64),
        (problem, ref, scales, lam * 2, 113),
        (problem, (*ref[:5], sp.Rational(8, 10**6)), scales, lam, 113),
        (problem, ref, (*scales[:2], 30.3, 1, 1, 1), lam, 113),
        (get_problem("disk").create(r0=30.3), ref, scales, lam, 113),
    ]
    for n, (prob, r, s, la, bits) in enumerate(variants, start=2):
        got = true_orbit._conditioned_rhs(prob, r, s, la, bits=bits)
        with bypassed():
            assert got == true_orbit._conditioned_rhs(prob, r, s, la, bits=bits)
        assert got != first
        assert len(_entries(cache_folder, "true-orbit-rhs")) == n


def test_the_forward_map_from_disk_computes_the_same_numbers(cache_folder):
    values = {"a": 0.45, "b": 0.55, "k": 0.5, "x0p": 0.6, "y0p": 0.8, "gamma3_0": 0.3}
    y = np.array([[0.1, -0.2], [0.05, 0.3], [1.0, 0.99], [0.2, 0.4], [0.1, -0.1], [0.3, 0.31]])
    with bypassed():
        fresh = _reduce("disk", 1, ()).forward_function(values, 0.01)(y)
    _reduce("disk", 1, ()).forward_function(values, 0.01)  # writes the entry
    assert len(_entries(cache_folder, "forward-map")) == 1
    stored = _reduce("disk", 1, ()).forward_function(values, 0.01)(y)  # reads it
    assert stored.tobytes() == fresh.tobytes()
