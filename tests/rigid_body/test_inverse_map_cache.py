"""The inverse map read back from the disk cache is the one compiled afresh, per body and ε."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import problems.rigid_body.reduction as reduction_module
from perturb.cache import bypassed
from problems.rigid_body.reduction import disk_reduction, specialised_disk_reduction

#: The body of tests/rigid_body/test_reduction_series.py, in floats (as a validation gives them).
VALUES = {
    "a": 0.45,
    "b": 0.55,
    "k": 0.5,
    "x0p": 0.1643989873053573,
    "y0p": 0.9863939238321437,
    "gamma3_0": 0.3,
}
#: Reduced states (P, dP, G, dG) and their initial values, of the size the disk's orbits have.
_RNG = np.random.default_rng(11)
Z = tuple(_RNG.uniform(-0.5, 0.5, 9) for _ in range(4))
Z0 = tuple(_RNG.uniform(-0.5, 0.5) for _ in range(4))


@pytest.fixture
def compiles(monkeypatch):
    """The calls of the compiler of the inverse map (exact evaluation of its series)."""
    calls = []
    original = reduction_module.compile_polynomials

    def counting(*args):
        calls.append(args[2])
        return original(*args)

    monkeypatch.setattr(reduction_module, "compile_polynomials", counting)
    return calls


def _inverse(reduction, values, eps):
    reduction._inverse_compiled.clear()  # past the memory: the disk cache only
    return reduction.inverse_function(values, eps)(Z, Z0)


@pytest.mark.parametrize(
    "make",
    [lambda: disk_reduction(3), lambda: specialised_disk_reduction(3, _exact(VALUES))],
    ids=["disk", "disk-specialised"],
)
def test_a_kept_inverse_map_is_the_fresh_one_to_the_bit(cache_folder, compiles, make):
    reduction = make()
    cold = _inverse(reduction, VALUES, 0.01)
    warm = _inverse(reduction, VALUES, 0.01)
    assert len(compiles) == 1  # the second is read back
    with bypassed():
        fresh = _inverse(reduction, VALUES, 0.01)
    assert len(compiles) == 2
    assert np.array_equal(warm, fresh) and np.array_equal(cold, fresh)
    assert np.all(np.isfinite(fresh))


def test_another_epsilon_or_body_is_compiled_not_read(cache_folder, compiles):
    reduction = disk_reduction(3)
    base = _inverse(reduction, VALUES, 0.01)
    other_eps = _inverse(reduction, VALUES, 0.02)
    other_body = _inverse(reduction, {**VALUES, "k": 0.6}, 0.01)
    assert len(compiles) == 3
    assert len(list(cache_folder.glob("inverse-map-*.pkl"))) == 3
    assert not np.array_equal(base, other_eps)
    assert not np.array_equal(base, other_body)
    assert np.array_equal(_inverse(reduction, VALUES, 0.02), other_eps)
    assert len(compiles) == 3


def _exact(values):
    return {name: sp.Rational(value) for name, value in values.items()}
